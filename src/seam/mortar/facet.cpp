#include "seam/mortar/facet.hpp"

#include <array>

#include "seam/common/error.hpp"

namespace seam::mortar {

namespace {

using fem::CellType;

// Gmsh node order: tri6 edge nodes 3 (0-1), 4 (1-2), 5 (2-0); quad8/quad9 edge nodes
// 4 (0-1), 5 (1-2), 6 (2-3), 7 (3-0), quad9 centre 8. Every piece keeps the parent's
// counter-clockwise orientation in the reference domain, hence the parent's normal.
constexpr std::array<SubFacet, 1> tri3_pieces = {{{3, {0, 1, 2, 0}}}};
constexpr std::array<SubFacet, 1> quad4_pieces = {{{4, {0, 1, 2, 3}}}};
constexpr std::array<SubFacet, 4> tri6_pieces = {{
    {3, {0, 3, 5, 0}},
    {3, {3, 1, 4, 0}},
    {3, {5, 4, 2, 0}},
    {3, {3, 4, 5, 0}},
}};
constexpr std::array<SubFacet, 5> quad8_pieces = {{
    {3, {0, 4, 7, 0}},
    {3, {4, 1, 5, 0}},
    {3, {5, 2, 6, 0}},
    {3, {6, 3, 7, 0}},
    {4, {4, 5, 6, 7}},
}};
constexpr std::array<SubFacet, 4> quad9_pieces = {{
    {4, {0, 4, 8, 7}},
    {4, {4, 1, 5, 8}},
    {4, {8, 5, 2, 6}},
    {4, {7, 8, 6, 3}},
}};

} // namespace

bool is_interface_facet(CellType type, int dim) {
  switch (type) {
  case CellType::line2:
  case CellType::line3:
    return dim == 2;
  case CellType::tri3:
  case CellType::tri6:
  case CellType::quad4:
  case CellType::quad8:
  case CellType::quad9:
    return dim == 3;
  default:
    return false;
  }
}

void validate(const FacetSet& facets, const char* side) {
  SEAM_CHECK(facets.dim == 2 || facets.dim == 3, InputError, side,
             " facets: dimension must be 2 or 3, got ", facets.dim);
  SEAM_CHECK(facets.coordinates.size() % static_cast<std::size_t>(facets.dim) == 0, InputError,
             side, " facets: coordinate array length ", facets.coordinates.size(),
             " is not a multiple of the dimension ", facets.dim);
  SEAM_CHECK(facets.offsets.size() == facets.types.size() + 1, InputError, side,
             " facets: expected ", facets.types.size() + 1, " offsets for ", facets.types.size(),
             " facets, got ", facets.offsets.size());
  SEAM_CHECK(facets.offsets[0] == 0 &&
                 static_cast<std::size_t>(facets.offsets.back()) == facets.nodes.size(),
             InputError, side, " facets: offsets must start at 0 and end at the node count ",
             facets.nodes.size());
  const local_index n_nodes = facets.n_nodes();
  for (local_index f = 0; f < facets.n_facets(); ++f) {
    const CellType type = facets.types[static_cast<std::size_t>(f)];
    SEAM_CHECK(is_interface_facet(type, facets.dim), InputError, side, " facet ", f, ": a ",
               fem::name(type), " is not an interface facet in ", facets.dim, "D");
    const local_index begin = facets.offsets[static_cast<std::size_t>(f)];
    const local_index end = facets.offsets[static_cast<std::size_t>(f) + 1];
    SEAM_CHECK(end - begin == fem::n_nodes(type), InputError, side, " facet ", f, ": a ",
               fem::name(type), " has ", fem::n_nodes(type), " nodes, got ", end - begin);
    for (const local_index node : facets.facet_nodes(f)) {
      SEAM_CHECK(node >= 0 && node < n_nodes, InputError, side, " facet ", f, ": node index ", node,
                 " is outside the coordinate array (", n_nodes, " nodes)");
    }
  }
}

template <int Dim> Facet<Dim> gather_facet(const FacetSet& facets, local_index f) {
  SEAM_ASSERT(facets.dim == Dim);
  Facet<Dim> facet;
  facet.type = facets.types[static_cast<std::size_t>(f)];
  const auto nodes = facets.facet_nodes(f);
  facet.n_nodes = static_cast<int>(nodes.size());
  for (int i = 0; i < facet.n_nodes; ++i) {
    const auto base = static_cast<std::size_t>(nodes[static_cast<std::size_t>(i)]) * Dim;
    for (int a = 0; a < Dim; ++a)
      facet.x(a, i) = facets.coordinates[base + static_cast<std::size_t>(a)];
  }
  return facet;
}

template <int Dim> FacetPoint<Dim> evaluate(const Facet<Dim>& facet, const double* xi) {
  constexpr int p = Dim - 1;
  FacetPoint<Dim> point;
  std::array<double, max_facet_nodes * p> gradients{};
  fem::shape_values(facet.type, xi, point.N.data());
  fem::shape_gradients(facet.type, xi, gradients.data());
  for (int i = 0; i < facet.n_nodes; ++i) {
    for (int a = 0; a < p; ++a) point.dN(i, a) = gradients[static_cast<std::size_t>(i * p + a)];
  }
  point.x = facet.x * point.N;
  point.dx = facet.x * point.dN;
  return point;
}

std::array<double, 2> reference_center(CellType type) {
  switch (type) {
  case CellType::tri3:
  case CellType::tri6:
    return {1.0 / 3.0, 1.0 / 3.0};
  default:
    return {0.0, 0.0};
  }
}

std::span<const SubFacet> linear_subfacets(CellType type) {
  switch (type) {
  case CellType::tri3:
    return tri3_pieces;
  case CellType::quad4:
    return quad4_pieces;
  case CellType::tri6:
    return tri6_pieces;
  case CellType::quad8:
    return quad8_pieces;
  case CellType::quad9:
    return quad9_pieces;
  default:
    SEAM_THROW(InputError, "linear_subfacets: a ", fem::name(type), " is not a surface facet");
  }
}

geometry::CurveProjection project_onto_facet(const Facet<2>& facet, const Eigen::Vector2d& p,
                                             const Eigen::Vector2d& d, double xi0,
                                             const geometry::NewtonOptions& options) {
  const auto curve = [&facet](double xi) {
    const auto point = evaluate(facet, &xi);
    return geometry::CurvePoint{point.x, point.dx.col(0)};
  };
  return geometry::project_onto_curve(curve, p, d, xi0, options);
}

geometry::SurfaceProjection project_onto_facet(const Facet<3>& facet, const Eigen::Vector3d& p,
                                               const Eigen::Vector3d& d, const Eigen::Vector2d& xi0,
                                               const geometry::NewtonOptions& options) {
  const auto surface = [&facet](const Eigen::Vector2d& xi) {
    const auto point = evaluate(facet, xi.data());
    return geometry::SurfacePoint{point.x, point.dx};
  };
  return geometry::project_onto_surface(surface, p, d, xi0, options);
}

geometry::SurfaceProjection project_onto_facet(const Facet<3>& facet, const Eigen::Vector3d& p,
                                               const Eigen::Vector3d& d) {
  const auto center = reference_center(facet.type);
  return project_onto_facet(facet, p, d, Eigen::Vector2d(center[0], center[1]));
}

template Facet<2> gather_facet<2>(const FacetSet&, local_index);
template Facet<3> gather_facet<3>(const FacetSet&, local_index);
template FacetPoint<2> evaluate<2>(const Facet<2>&, const double*);
template FacetPoint<3> evaluate<3>(const Facet<3>&, const double*);

bool all_affine(const FacetSet& facets) {
  if (facets.dim != 3) return true;
  for (local_index f = 0; f < facets.n_facets(); ++f)
    if (facets.types[static_cast<std::size_t>(f)] == fem::CellType::quad4 &&
        !is_affine(gather_facet<3>(facets, f)))
      return false;
  return true;
}

} // namespace seam::mortar
