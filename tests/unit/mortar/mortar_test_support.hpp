#pragma once
// Interface meshes for the mortar tests: structured line meshes along a parametrised curve
// (2D) and structured tri/quad grids mapped onto a surface (3D), linear or quadratic, with
// either orientation. Node positions come from analytic maps, so exact values are known.
#include <array>
#include <cmath>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "seam/mortar/interface.hpp"

namespace seam::mortar::test {

using fem::CellType;

struct Surface {
  int dim = 3;
  std::vector<double> coordinates;
  std::vector<CellType> types;
  std::vector<local_index> offsets{0};
  std::vector<local_index> nodes;

  FacetSet view() const { return {dim, coordinates, types, offsets, nodes}; }
  local_index n_nodes() const { return static_cast<local_index>(coordinates.size()) / dim; }
  Eigen::VectorXd coordinate(int a) const {
    Eigen::VectorXd x(n_nodes());
    for (local_index i = 0; i < n_nodes(); ++i)
      x(i) = coordinates[static_cast<std::size_t>(i * dim + a)];
    return x;
  }
  void add_facet(CellType type, std::initializer_list<local_index> facet_nodes) {
    types.push_back(type);
    nodes.insert(nodes.end(), facet_nodes);
    offsets.push_back(static_cast<local_index>(nodes.size()));
  }
};

/// n line facets along curve(s), s in [0, 1]; `reverse` flips each facet's direction (and so
/// its outward normal (t_y, -t_x)). line3 facets get their middle node at the parameter mean.
inline Surface line_mesh(int n, CellType type, const std::function<Eigen::Vector2d(double)>& curve,
                         bool reverse) {
  Surface s;
  s.dim = 2;
  const int per = type == CellType::line3 ? 2 : 1;
  for (int i = 0; i <= per * n; ++i) {
    const Eigen::Vector2d x = curve(static_cast<double>(i) / (per * n));
    s.coordinates.push_back(x.x());
    s.coordinates.push_back(x.y());
  }
  for (int e = 0; e < n; ++e) {
    const local_index a = per * e, b = per * (e + 1);
    const local_index first = reverse ? b : a, last = reverse ? a : b;
    if (type == CellType::line3) {
      s.add_facet(type, {first, last, a + 1});
    } else {
      s.add_facet(type, {first, last});
    }
  }
  return s;
}

/// nx x ny grid of facets over (u, v) in [0,1]^2 mapped by surface(u, v). Quadrilateral types
/// give one facet per cell, triangular types two. Nodes live on the (2nx+1) x (2ny+1) lattice
/// so quadratic facets find their mid-side and centre nodes; unused lattice nodes are simply
/// not referenced. Facets turn counter-clockwise in (u, v) unless `flip`.
inline Surface grid(int nx, int ny, CellType type,
                    const std::function<Eigen::Vector3d(double, double)>& surface, bool flip) {
  Surface s;
  s.dim = 3;
  const int NX = 2 * nx + 1, NY = 2 * ny + 1;
  for (int J = 0; J < NY; ++J) {
    for (int I = 0; I < NX; ++I) {
      const Eigen::Vector3d x =
          surface(static_cast<double>(I) / (NX - 1), static_cast<double>(J) / (NY - 1));
      for (int a = 0; a < 3; ++a) s.coordinates.push_back(x(a));
    }
  }
  using Lattice = std::array<int, 2>;
  const auto id = [NX](Lattice p) { return static_cast<local_index>(p[1] * NX + p[0]); };
  const auto mid = [](Lattice p, Lattice q) {
    return Lattice{(p[0] + q[0]) / 2, (p[1] + q[1]) / 2};
  };
  const auto add = [&](std::vector<Lattice> corners) {
    if (flip) std::reverse(corners.begin() + 1, corners.end());
    std::vector<local_index> facet;
    for (const Lattice& c : corners) facet.push_back(id(c));
    const int n = static_cast<int>(corners.size());
    const bool quadratic =
        type == CellType::tri6 || type == CellType::quad8 || type == CellType::quad9;
    if (quadratic) {
      for (int i = 0; i < n; ++i)
        facet.push_back(id(mid(corners[static_cast<std::size_t>(i)],
                               corners[static_cast<std::size_t>((i + 1) % n)])));
    }
    if (type == CellType::quad9) facet.push_back(id(mid(corners[0], corners[2])));
    s.types.push_back(type);
    s.nodes.insert(s.nodes.end(), facet.begin(), facet.end());
    s.offsets.push_back(static_cast<local_index>(s.nodes.size()));
  };
  const bool triangles = type == CellType::tri3 || type == CellType::tri6;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const Lattice a{2 * i, 2 * j}, b{2 * i + 2, 2 * j}, c{2 * i + 2, 2 * j + 2},
          d{2 * i, 2 * j + 2};
      if (triangles) {
        add({a, b, c});
        add({a, c, d});
      } else {
        add({a, b, c, d});
      }
    }
  }
  return s;
}

/// Every (slave, master) facet pair: the brute-force candidate list.
inline std::vector<CandidatePair> all_pairs(const Surface& slave, const Surface& master) {
  std::vector<CandidatePair> pairs;
  for (local_index i = 0; i < static_cast<local_index>(slave.types.size()); ++i) {
    for (local_index k = 0; k < static_cast<local_index>(master.types.size()); ++k)
      pairs.push_back({i, k});
  }
  return pairs;
}

/// Dense D (slave x slave) and M (slave x master) from triplets.
inline Eigen::MatrixXd dense(const std::vector<Triplet>& t, local_index rows, local_index cols) {
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(rows, cols);
  for (const Triplet& x : t) m(x.row, x.col) += x.value;
  return m;
}

} // namespace seam::mortar::test
