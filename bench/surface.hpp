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

/// n line2/line3 segments of length h from x = origin on the curve y = curve(x); the slave
/// runs right to left (outward normal (t_y, -t_x) up), the master left to right (normal down).
template <class Curve>
Surface surface_2d(fem::CellType type, int n, double h, double origin, Curve&& curve, bool slave) {
  Surface s;
  s.dim = 2;
  const int order = type == fem::CellType::line3 ? 2 : 1;
  for (int i = 0; i <= order * n; ++i) {
    const double x = origin + i * h / order;
    s.coords.insert(s.coords.end(), {x, curve(x)});
  }
  for (int e = 0; e < n; ++e) {
    const local_index a = order * e, b = order * (e + 1);
    std::vector<local_index> f{slave ? b : a, slave ? a : b};
    if (type == fem::CellType::line3) f.push_back(a + 1);
    s.add(type, f);
  }
  return s;
}

} // namespace seam::bench
