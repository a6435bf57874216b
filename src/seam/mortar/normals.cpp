#include "seam/mortar/normals.hpp"

#include <algorithm>
#include <cmath>

#include "seam/common/error.hpp"

namespace seam::mortar {

namespace {

/// Sums the unit normals of the facets `which` (all facets if null) at their nodes.
template <int Dim>
void accumulate_facet_normals(const FacetSet& facets, const std::vector<local_index>* which,
                              std::vector<double>& sum) {
  constexpr int p = Dim - 1;
  const auto n_facets = which ? static_cast<local_index>(which->size()) : facets.n_facets();
  for (local_index k = 0; k < n_facets; ++k) {
    const local_index f = which ? (*which)[static_cast<std::size_t>(k)] : k;
    const Facet<Dim> facet = gather_facet<Dim>(facets, f);
    const auto nodes = facets.facet_nodes(f);
    const double* reference = fem::reference_nodes(facet.type).data();
    for (int i = 0; i < facet.n_nodes; ++i) {
      const auto point = evaluate(facet, reference + i * p);
      const Eigen::Matrix<double, Dim, 1> n = scaled_normal<Dim>(point.dx);
      const double length = n.norm();
      SEAM_CHECK(length > 0.0, InputError, "slave facet ", f,
                 " is degenerate (zero Jacobian at its node ", i, ")");
      const auto base = static_cast<std::size_t>(nodes[static_cast<std::size_t>(i)]) * Dim;
      for (int a = 0; a < Dim; ++a) sum[base + static_cast<std::size_t>(a)] += n(a) / length;
    }
  }
}

} // namespace

namespace {

/// The averaged normals of the nodes `nodes` (every node on a facet if null) from the facets
/// `which` (all if null), which must hold every facet around those nodes. A node whose facet
/// normals cancel throws InputError, or, with `folded`, is stored there (the first such node;
/// -1 if none) and keeps a zero normal.
std::vector<double> averaged_normals(const FacetSet& facets, const std::vector<local_index>* which,
                                     std::span<const local_index>* nodes,
                                     local_index* folded = nullptr) {
  validate(facets, "slave");
  const auto dim = static_cast<std::size_t>(facets.dim);
  std::vector<double> normals(facets.coordinates.size(), 0.0);
  if (facets.dim == 2) {
    accumulate_facet_normals<2>(facets, which, normals);
  } else {
    accumulate_facet_normals<3>(facets, which, normals);
  }
  std::vector<char> on_surface(normals.size() / dim, 0);
  if (nodes) {
    // The listed nodes on one of the facets (a listed node on none keeps a zero normal).
    std::vector<char> listed(on_surface.size(), 0);
    for (const local_index node : *nodes) listed[static_cast<std::size_t>(node)] = 1;
    for (const local_index f : *which)
      for (const local_index node : facets.facet_nodes(f))
        on_surface[static_cast<std::size_t>(node)] = listed[static_cast<std::size_t>(node)];
    // The other nodes of the facets have partial sums only.
    for (std::size_t node = 0; node < on_surface.size(); ++node)
      if (!on_surface[node])
        for (std::size_t a = 0; a < dim; ++a) normals[node * dim + a] = 0.0;
  } else {
    for (const local_index node : facets.nodes) on_surface[static_cast<std::size_t>(node)] = 1;
  }
  for (std::size_t node = 0; node < on_surface.size(); ++node) {
    if (!on_surface[node]) continue;
    double length = 0.0;
    for (std::size_t a = 0; a < dim; ++a)
      length += normals[node * dim + a] * normals[node * dim + a];
    length = std::sqrt(length);
    if (folded && !(length > min_normal_sum)) {
      if (*folded < 0) *folded = static_cast<local_index>(node);
      for (std::size_t a = 0; a < dim; ++a) normals[node * dim + a] = 0.0;
      continue;
    }
    SEAM_CHECK(length > min_normal_sum, InputError, "slave node ", node,
               ": the normals of its facets cancel (the surface folds back onto itself)");
    for (std::size_t a = 0; a < dim; ++a) normals[node * dim + a] /= length;
  }
  return normals;
}

} // namespace

std::vector<double> averaged_nodal_normals(const FacetSet& facets) {
  return averaged_normals(facets, nullptr, nullptr);
}

std::vector<double> averaged_nodal_normals(const FacetSet& facets,
                                           std::span<const local_index> adjacent,
                                           std::span<const local_index> nodes) {
  SEAM_ASSERT(std::is_sorted(adjacent.begin(), adjacent.end()));
  const std::vector<local_index> which(adjacent.begin(), adjacent.end());
  return averaged_normals(facets, &which, &nodes);
}

local_index folded_node(const FacetSet& facets) {
  local_index folded = -1;
  averaged_normals(facets, nullptr, nullptr, &folded);
  return folded;
}

} // namespace seam::mortar
