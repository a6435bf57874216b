#include "seam/search/facets.hpp"

#include "seam/common/error.hpp"

#include <cmath>
#include <limits>

namespace seam::search {

int n_corners(int dim, int n_nodes) {
  if (dim == 2) return (n_nodes == 2 || n_nodes == 3) ? 2 : 0;
  if (n_nodes == 3 || n_nodes == 6) return 3;
  if (n_nodes == 4 || n_nodes == 8 || n_nodes == 9) return 4;
  return 0;
}

void check_surface(const FacetSurface& s) {
  SEAM_CHECK(s.dim == 2 || s.dim == 3, InputError, "search: surface dimension must be 2 or 3, got ",
             s.dim);
  SEAM_CHECK(s.coords.size() % static_cast<std::size_t>(s.dim) == 0, InputError,
             "search: ", s.coords.size(), " coordinates are not a multiple of dim = ", s.dim);
  // No offsets at all is an empty surface (e.g. a rank that owns no facet of an interface).
  SEAM_CHECK(s.offsets.empty() ? s.connectivity.empty() : s.offsets[0] == 0, InputError,
             "search: facet offsets must hold n_facets + 1 entries starting at 0");
  SEAM_CHECK(s.offsets.empty() ||
                 static_cast<std::size_t>(s.offsets.back()) == s.connectivity.size(),
             InputError, "search: last facet offset does not match the ", s.connectivity.size(),
             " connectivity entries");
  const local_index n_nodes = s.n_nodes();
  for (local_index f = 0; f < s.n_facets(); ++f) {
    const local_index n = s.offsets[f + 1] - s.offsets[f];
    SEAM_CHECK(n_corners(s.dim, n) > 0, InputError, "search: facet ", f, " has ", n,
               " nodes, which is no supported ", s.dim, "D facet type");
    for (local_index i = s.offsets[f]; i < s.offsets[f + 1]; ++i)
      SEAM_CHECK(s.connectivity[i] >= 0 && s.connectivity[i] < n_nodes, InputError,
                 "search: facet ", f, " refers to node ", s.connectivity[i], " of ", n_nodes);
  }
  for (std::size_t i = 0; i < s.coords.size(); ++i)
    SEAM_CHECK(std::isfinite(s.coords[i]), InputError, "search: coordinate ", i % s.dim,
               " of node ", i / s.dim, " is not finite");
}

double min_edge_length(const FacetSurface& s) {
  double min_sq = std::numeric_limits<double>::infinity();
  for (local_index f = 0; f < s.n_facets(); ++f) {
    const local_index* nodes = s.connectivity.data() + s.offsets[f];
    const int nc = n_corners(s.dim, s.offsets[f + 1] - s.offsets[f]);
    const int n_edges = nc == 2 ? 1 : nc;
    for (int e = 0; e < n_edges; ++e) {
      const double* a = s.coords.data() + static_cast<std::size_t>(nodes[e]) * s.dim;
      const double* b = s.coords.data() + static_cast<std::size_t>(nodes[(e + 1) % nc]) * s.dim;
      double sq = 0.0;
      for (int d = 0; d < s.dim; ++d) sq += (a[d] - b[d]) * (a[d] - b[d]);
      if (sq > 0.0 && sq < min_sq) min_sq = sq;
    }
  }
  return std::isfinite(min_sq) ? std::sqrt(min_sq) : 0.0;
}

} // namespace seam::search
