#include "seam/mortar/normals.hpp"

#include <cmath>

#include "seam/common/error.hpp"

namespace seam::mortar {

namespace {

template <int Dim> void accumulate_facet_normals(const FacetSet& facets, std::vector<double>& sum) {
  constexpr int p = Dim - 1;
  for (local_index f = 0; f < facets.n_facets(); ++f) {
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

std::vector<double> averaged_nodal_normals(const FacetSet& facets) {
  validate(facets, "slave");
  const auto dim = static_cast<std::size_t>(facets.dim);
  std::vector<double> normals(facets.coordinates.size(), 0.0);
  if (facets.dim == 2) {
    accumulate_facet_normals<2>(facets, normals);
  } else {
    accumulate_facet_normals<3>(facets, normals);
  }
  std::vector<char> on_surface(normals.size() / dim, 0);
  for (const local_index node : facets.nodes) on_surface[static_cast<std::size_t>(node)] = 1;
  for (std::size_t node = 0; node < on_surface.size(); ++node) {
    if (!on_surface[node]) continue;
    double length = 0.0;
    for (std::size_t a = 0; a < dim; ++a)
      length += normals[node * dim + a] * normals[node * dim + a];
    length = std::sqrt(length);
    SEAM_CHECK(length > 1e-8, InputError, "slave node ", node,
               ": the normals of its facets cancel (the surface folds back onto itself)");
    for (std::size_t a = 0; a < dim; ++a) normals[node * dim + a] /= length;
  }
  return normals;
}

} // namespace seam::mortar
