#pragma once
// A facet surface built in memory by the benchmarks: flat arrays in the layouts the mortar
// integration (FacetSet) and the search (FacetSurface) read.
#include "seam/mortar/facet.hpp"
#include "seam/search/facets.hpp"

#include <vector>

namespace seam::bench {

struct Surface {
  int dim = 3;
  std::vector<double> coords;
  std::vector<fem::CellType> types;
  std::vector<local_index> offsets{0};
  std::vector<local_index> nodes;

  mortar::FacetSet facets() const { return {dim, coords, types, offsets, nodes}; }
  search::FacetSurface view() const { return {dim, coords, offsets, nodes}; }
  void add(fem::CellType type, const std::vector<local_index>& facet_nodes) {
    types.push_back(type);
    nodes.insert(nodes.end(), facet_nodes.begin(), facet_nodes.end());
    offsets.push_back(static_cast<local_index>(nodes.size()));
  }
};

} // namespace seam::bench
