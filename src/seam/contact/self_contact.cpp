#include "seam/contact/self_contact.hpp"

#include "seam/meshtying/tied_interface.hpp"
#include "seam/search/interface_search.hpp"
#include "seam/search/normal_cone.hpp"
#include "seam/search/traversal.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace seam::contact {

std::array<double, 3> facet_normal(const meshtying::InterfaceSide& side, local_index f) {
  const int dim = side.dim;
  const auto* nodes = &side.nodes[static_cast<std::size_t>(side.offsets[f])];
  const auto x = [&](int i, int c) {
    return side.coordinates[static_cast<std::size_t>(nodes[i]) * dim + c];
  };
  if (dim == 2) return {x(1, 1) - x(0, 1), -(x(1, 0) - x(0, 0)), 0.0};
  const int n = fem::n_vertices(side.types[static_cast<std::size_t>(f)]);
  // Diagonals of a quadrilateral, two edges of a triangle.
  const int a0 = 0, a1 = n == 4 ? 2 : 1, b0 = n == 4 ? 1 : 0, b1 = n == 4 ? 3 : 2;
  const double u[3] = {x(a1, 0) - x(a0, 0), x(a1, 1) - x(a0, 1), x(a1, 2) - x(a0, 2)};
  const double v[3] = {x(b1, 0) - x(b0, 0), x(b1, 1) - x(b0, 1), x(b1, 2) - x(b0, 2)};
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}

mesh::Region surface_region(const mesh::Mesh& mesh, std::span<const io::RegionRef> groups,
                            bool part) {
  // One region with the facets of every group, each (cell, local facet) once.
  mesh::Region all;
  all.name = groups.front().name;
  all.dim = mesh.dim - 1;
  for (const auto& group : groups) {
    const auto& region = meshtying::side_region(mesh, group);
    if (region.n_facets() == 0 && !part)
      io::fail_at(group.mark, "the surface group '" + group.name + "' has no facets");
    all.facet_cell.insert(all.facet_cell.end(), region.facet_cell.begin(), region.facet_cell.end());
    all.facet_local.insert(all.facet_local.end(), region.facet_local.begin(),
                           region.facet_local.end());
  }
  all.sort_facets();
  return all;
}

meshtying::InterfaceSide extract_surface(const mesh::Mesh& mesh,
                                         std::span<const io::RegionRef> groups, bool part) {
  return meshtying::extract_side(mesh, surface_region(mesh, groups, part));
}

search::Tree self_contact_tree(const search::FacetSurface& surface, double inflation) {
  search::TreeOptions options;
  options.inflation = inflation;
  options.normal_cones = true;
  return search::Tree(surface, options);
}

namespace {

std::array<double, 3> centroid(const meshtying::InterfaceSide& side, local_index f) {
  std::array<double, 3> c{};
  const auto begin = side.offsets[f], end = side.offsets[f + 1];
  for (auto i = begin; i < end; ++i)
    for (int a = 0; a < side.dim; ++a)
      c[static_cast<std::size_t>(a)] +=
          side.coordinates[static_cast<std::size_t>(side.nodes[static_cast<std::size_t>(i)]) *
                               side.dim +
                           a];
  for (auto& v : c) v /= static_cast<double>(end - begin);
  return c;
}

double dot(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

} // namespace

void self_contact_pairs(search::Tree& tree, const meshtying::InterfaceSide& side,
                        std::vector<mortar::CandidatePair>& out) {
  tree.update(side.coordinates);
  std::vector<search::CandidatePair> found, facing;
  search::find_self_pairs(tree, found);
  keep_facing_pairs(side, tree.inflation(), found, facing);
  orient_pairs(side, facing, out);
}

void keep_facing_pairs(const meshtying::InterfaceSide& side, double inflation,
                       std::span<const search::CandidatePair> found,
                       std::vector<search::CandidatePair>& out) {
  const double behind = 0.5 * inflation;
  for (const auto& p : found) {
    auto na = facet_normal(side, p.slave), nb = facet_normal(side, p.master);
    if (dot(na, nb) >= 0.0) continue;
    const double la = std::sqrt(dot(na, na)), lb = std::sqrt(dot(nb, nb));
    if (la == 0.0 || lb == 0.0) continue;
    const auto ca = centroid(side, p.slave), cb = centroid(side, p.master);
    const std::array<double, 3> d{cb[0] - ca[0], cb[1] - ca[1], cb[2] - ca[2]};
    if (dot(d, na) / la < -behind || -dot(d, nb) / lb < -behind) continue;
    out.push_back(p);
  }
}

void with_axes(const meshtying::InterfaceSide& side, std::span<const search::CandidatePair> pairs,
               std::vector<FacingPair>& out) {
  const auto surface = side.surface();
  // The axis of a facet's normal cone, as the self-contact tree has it.
  const auto axis = [&](local_index f) {
    const auto begin = static_cast<std::size_t>(surface.offsets[f]);
    const auto end = static_cast<std::size_t>(surface.offsets[f + 1]);
    return search::facet_normal_cone(side.dim, surface.coords,
                                     surface.connectivity.subspan(begin, end - begin))
        .axis;
  };
  out.clear();
  out.reserve(pairs.size());
  for (const auto& p : pairs) out.push_back({p, axis(p.slave), axis(p.master)});
}

void orient_pairs(const meshtying::InterfaceSide& side,
                  std::span<const search::CandidatePair> pairs,
                  std::vector<mortar::CandidatePair>& out) {
  std::vector<FacingPair> facing;
  with_axes(side, pairs, facing);
  orient_pairs(side.n_facets(), facing, out);
}

void orient_pairs(local_index n_facets, std::span<const FacingPair> pairs,
                  std::vector<mortar::CandidatePair>& out, std::span<search::Role> roles) {
  std::vector<search::CandidatePair> sorted;
  sorted.reserve(pairs.size());
  std::vector<std::array<double, 3>> axis(static_cast<std::size_t>(n_facets));
  for (const auto& p : pairs) {
    const auto [a, b] = p.pair;
    sorted.push_back({std::min(a, b), std::max(a, b)});
    axis[static_cast<std::size_t>(a)] = p.slave_axis;
    axis[static_cast<std::size_t>(b)] = p.master_axis;
  }
  std::sort(sorted.begin(), sorted.end());
  const auto oriented = roles.empty() ? search::assign_roles(axis, sorted)
                                      : search::assign_roles(axis, sorted, roles);
  out.clear();
  for (const auto& p : oriented) out.push_back({p.slave, p.master});
  std::sort(out.begin(), out.end(), [](const auto& x, const auto& y) {
    return x.slave != y.slave ? x.slave < y.slave : x.master < y.master;
  });
}

void build_slave_patch(const meshtying::InterfaceSide& side,
                       std::span<const mortar::CandidatePair> pairs, SlavePatch& out) {
  out.index.assign(static_cast<std::size_t>(side.n_facets()), -1);
  for (const auto& p : pairs) out.index[static_cast<std::size_t>(p.slave)] = 0;
  out.types.clear();
  out.offsets.assign(1, 0);
  out.nodes.clear();
  for (local_index f = 0; f < side.n_facets(); ++f) {
    auto& k = out.index[static_cast<std::size_t>(f)];
    if (k < 0) continue;
    k = static_cast<local_index>(out.types.size());
    out.types.push_back(side.types[static_cast<std::size_t>(f)]);
    const auto nodes = side.facet_set().facet_nodes(f);
    out.nodes.insert(out.nodes.end(), nodes.begin(), nodes.end());
    out.offsets.push_back(static_cast<local_index>(out.nodes.size()));
  }
  out.adjacency = mortar::node_facets(out.facet_set(side));
}

} // namespace seam::contact
