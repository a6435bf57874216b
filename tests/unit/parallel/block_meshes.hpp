#pragma once
// Structured volume meshes built by hand (no Gmsh), identical on every rank: blocks of hex8 or
// Kuhn-split tet4 (6 per hex, conforming across hexes), 2D grids of quad4 or tri3, each block
// with its own nodes, a volume region and facet regions on its bottom and top (z or y).
#include "seam/fem/cell.hpp"
#include "seam/mesh/mesh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace seam::parallel::test {

/// The facets of `cells` whose nodes all have coordinate `axis` == value, as a facet region.
inline mesh::Region facet_region(const mesh::Mesh& m, std::span<const std::int32_t> cells, int axis,
                                 double value, const std::string& name, int tag) {
  mesh::Region r;
  r.name = name;
  r.dim = m.dim - 1;
  r.tag = tag;
  for (auto c : cells) {
    const auto nodes = m.cell(c);
    for (int f = 0; f < fem::n_facets(m.cell_type[c]); ++f) {
      const auto local = fem::facet_nodes(m.cell_type[c], f);
      const bool on = std::all_of(local.begin(), local.end(), [&](int k) {
        return std::abs(m.node(nodes[k])[axis] - value) < 1e-12;
      });
      if (!on) continue;
      r.facet_cell.push_back(c);
      r.facet_local.push_back(static_cast<std::int8_t>(f));
      for (int k : local) r.nodes.push_back(nodes[k]);
    }
  }
  std::sort(r.nodes.begin(), r.nodes.end());
  r.nodes.erase(std::unique(r.nodes.begin(), r.nodes.end()), r.nodes.end());
  return r;
}

/// Appends an n[0] x n[1] (x n[2] in 3D) block of unit cells starting at `origin`, with its
/// own nodes; regions NAME (cells), NAME_bottom and NAME_top (the faces at the lowest and
/// highest last coordinate). simplices: tri3 / tet4 instead of quad4 / hex8.
inline void add_block(mesh::Mesh& m, std::array<int, 3> n, std::array<double, 3> origin,
                      bool simplices, const std::string& name) {
  const int dim = m.dim;
  if (dim == 2) n[2] = 0;
  const auto first_node = m.n_nodes();
  const auto first_cell = m.n_cells();
  auto id = [&](int i, int j, int k) { return first_node + i + (n[0] + 1) * (j + (n[1] + 1) * k); };
  for (int k = 0; k <= n[2]; ++k)
    for (int j = 0; j <= n[1]; ++j)
      for (int i = 0; i <= n[0]; ++i) {
        const double x[3] = {origin[0] + i, origin[1] + j, origin[2] + k};
        m.x.insert(m.x.end(), x, x + dim);
      }
  for (int k = 0; k < std::max(n[2], 1); ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        if (dim == 2) {
          const std::int32_t q[4] = {id(i, j, 0), id(i + 1, j, 0), id(i + 1, j + 1, 0),
                                     id(i, j + 1, 0)};
          if (!simplices) {
            m.add_cell(fem::CellType::quad4, q);
          } else {
            const std::int32_t a[3] = {q[0], q[1], q[2]}, b[3] = {q[0], q[2], q[3]};
            m.add_cell(fem::CellType::tri3, a);
            m.add_cell(fem::CellType::tri3, b);
          }
          continue;
        }
        // Corner c of the hex: bit 0 = x, bit 1 = y, bit 2 = z.
        auto corner = [&](int c) { return id(i + (c & 1), j + ((c >> 1) & 1), k + (c >> 2)); };
        if (!simplices) {
          const std::int32_t h[8] = {corner(0), corner(1), corner(3), corner(2),
                                     corner(4), corner(5), corner(7), corner(6)};
          m.add_cell(fem::CellType::hex8, h);
          continue;
        }
        // Kuhn split: one tet per path 0 -> 7 along the axes in each order.
        const int orders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
        for (const auto& o : orders) {
          int c = 0;
          std::int32_t t[4] = {corner(0), 0, 0, 0};
          for (int s = 0; s < 3; ++s) t[s + 1] = corner(c |= 1 << o[s]);
          m.add_cell(fem::CellType::tet4, t);
        }
      }
  std::vector<std::int32_t> cells;
  for (auto c = first_cell; c < m.n_cells(); ++c) cells.push_back(c);
  const int tag = static_cast<int>(m.regions.size()) + 1;
  mesh::Region volume;
  volume.name = name;
  volume.dim = dim;
  volume.tag = tag;
  volume.cells = cells;
  for (auto c : cells)
    for (auto node : m.cell(c)) volume.nodes.push_back(node);
  std::sort(volume.nodes.begin(), volume.nodes.end());
  volume.nodes.erase(std::unique(volume.nodes.begin(), volume.nodes.end()), volume.nodes.end());
  m.regions.push_back(volume);
  const int up = dim - 1;
  m.regions.push_back(facet_region(m, cells, up, origin[up], name + "_bottom", tag + 1));
  m.regions.push_back(facet_region(m, cells, up, origin[up] + n[up], name + "_top", tag + 2));
}

/// A point region on the first node (dim 0).
inline void add_point_region(mesh::Mesh& m, const std::string& name) {
  mesh::Region r;
  r.name = name;
  r.dim = 0;
  r.tag = static_cast<int>(m.regions.size()) + 1;
  r.nodes = {0};
  m.regions.push_back(r);
}

} // namespace seam::parallel::test
