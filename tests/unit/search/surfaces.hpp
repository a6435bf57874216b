#pragma once
// Facet surfaces for the search tests: structured, random, degenerate and self-contacting.
#include "seam/search/facets.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <numbers>
#include <random>
#include <vector>

namespace seam::search::test {

struct Mesh {
  int dim = 3;
  std::vector<double> coords;
  std::vector<local_index> offsets{0};
  std::vector<local_index> conn;

  FacetSurface view() const { return {dim, coords, offsets, conn}; }
  local_index n_nodes() const { return static_cast<local_index>(coords.size() / dim); }
  void add_facet(std::initializer_list<local_index> nodes) {
    conn.insert(conn.end(), nodes);
    offsets.push_back(static_cast<local_index>(conn.size()));
  }
};

/// Triangulated (or quad) grid over [0, 1]^2 at height z0 + a sin(2 pi x) sin(2 pi y), its
/// nodes shifted by (shift, shift) in the plane.
inline Mesh wavy_surface(int nx, int ny, double z0, double a, double shift, bool quads = false) {
  Mesh m;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double x = double(i) / nx + shift, y = double(j) / ny + shift;
      m.coords.insert(
          m.coords.end(),
          {x, y, z0 + a * std::sin(2 * std::numbers::pi * x) * std::sin(2 * std::numbers::pi * y)});
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const local_index n0 = j * (nx + 1) + i, n1 = n0 + 1, n2 = n0 + nx + 2, n3 = n0 + nx + 1;
      if (quads) {
        m.add_facet({n0, n1, n2, n3});
      } else {
        m.add_facet({n0, n1, n2});
        m.add_facet({n0, n2, n3});
      }
    }
  return m;
}

/// Open polyline y = y0 + a sin(2 pi x) over [shift, 1 + shift] with n segments.
inline Mesh wavy_polyline(int n, double y0, double a, double shift) {
  Mesh m;
  m.dim = 2;
  for (int i = 0; i <= n; ++i) {
    const double x = double(i) / n + shift;
    m.coords.insert(m.coords.end(), {x, y0 + a * std::sin(2 * std::numbers::pi * x)});
  }
  for (int i = 0; i < n; ++i) m.add_facet({i, i + 1});
  return m;
}

/// n unconnected random facets (segments in 2D, triangles in 3D) of size ~ `size` in [0, 1]^dim.
inline Mesh random_facets(int dim, int n, double size, unsigned seed) {
  Mesh m;
  m.dim = dim;
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0), e(-size, size);
  for (int f = 0; f < n; ++f) {
    double c[3] = {u(gen), u(gen), u(gen)};
    const int nv = dim == 2 ? 2 : 3;
    for (int v = 0; v < nv; ++v)
      for (int d = 0; d < dim; ++d) m.coords.push_back(c[d] + e(gen));
    if (dim == 2)
      m.add_facet({2 * f, 2 * f + 1});
    else
      m.add_facet({3 * f, 3 * f + 1, 3 * f + 2});
  }
  return m;
}

/// A strip of width w folded about the y axis: the lower leg z = -r and the upper leg z = +r
/// (x in [0, leg]) are joined by a half cylinder of radius r around the line x = leg, z = 0.
/// The facets are the strip's inner face, so its normals point into the gap: +z on the lower
/// leg, -z on the upper leg. Facets are quads (n_leg + n_bend + n_leg along, n_w across).
inline Mesh folded_strip(double leg, double r, double w, int n_leg, int n_bend, int n_w) {
  Mesh m;
  std::vector<std::array<double, 2>> line; // (x, z) along the centre line
  for (int i = 0; i <= n_leg; ++i) line.push_back({leg * i / n_leg, -r});
  for (int i = 1; i < n_bend; ++i) {
    const double t = -0.5 * std::numbers::pi + std::numbers::pi * i / n_bend;
    line.push_back({leg + r * std::cos(t), r * std::sin(t)});
  }
  for (int i = 0; i <= n_leg; ++i) line.push_back({leg - leg * i / n_leg, r});
  const int n_along = static_cast<int>(line.size());
  for (int i = 0; i < n_along; ++i)
    for (int j = 0; j <= n_w; ++j)
      m.coords.insert(m.coords.end(), {line[i][0], w * j / n_w, line[i][1]});
  for (int i = 0; i + 1 < n_along; ++i)
    for (int j = 0; j < n_w; ++j) {
      const local_index a = i * (n_w + 1) + j, b = (i + 1) * (n_w + 1) + j;
      m.add_facet({a, b, b + 1, a + 1}); // (x_b - x_a) x (x_{a+1} - x_a) points into the gap
    }
  return m;
}

/// Inner boundary of a ring whose top has buckled inwards until it nearly touches the bottom:
/// x = R cos t, y = R sin t (1 - c exp(-((t - pi/2) / w)^2)) on the upper half, a circle on the
/// lower half; the dent's lowest point (0, R (1 - c)) lies `gap` above the bottom (0, -R). As c b
/// < 2 the curve never crosses itself. Traversed clockwise, so the right-hand normal (t_y, -t_x),
/// the ring material's outward normal, points into the hole.
inline Mesh buckled_ring(double radius, double gap, double w, int n) {
  Mesh m;
  m.dim = 2;
  const double c = 2.0 - gap / radius;
  for (int i = 0; i < n; ++i) {
    const double t = -2.0 * std::numbers::pi * i / n; // clockwise
    double y = radius * std::sin(t);
    if (y > 0.0) {
      // distance of t from pi/2 modulo 2 pi
      const double dt = std::remainder(t - 0.5 * std::numbers::pi, 2.0 * std::numbers::pi);
      y *= 1.0 - c * std::exp(-(dt / w) * (dt / w));
    }
    m.coords.insert(m.coords.end(), {radius * std::cos(t), y});
  }
  for (int i = 0; i < n; ++i) m.add_facet({i, (i + 1) % n});
  return m;
}

/// Triangulated unit sphere (latitude-longitude), outward normals.
inline Mesh sphere(int n_lat, int n_lon) {
  Mesh m;
  m.coords.insert(m.coords.end(), {0.0, 0.0, 1.0});
  for (int i = 1; i < n_lat; ++i) {
    const double th = std::numbers::pi * i / n_lat;
    for (int j = 0; j < n_lon; ++j) {
      const double ph = 2.0 * std::numbers::pi * j / n_lon;
      m.coords.insert(m.coords.end(),
                      {std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)});
    }
  }
  m.coords.insert(m.coords.end(), {0.0, 0.0, -1.0});
  const local_index south = m.n_nodes() - 1;
  auto ring = [&](int i, int j) { return 1 + (i - 1) * n_lon + (j % n_lon); };
  for (int j = 0; j < n_lon; ++j) m.add_facet({0, ring(1, j), ring(1, j + 1)});
  for (int i = 1; i + 1 < n_lat; ++i)
    for (int j = 0; j < n_lon; ++j) {
      m.add_facet({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
      m.add_facet({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
    }
  for (int j = 0; j < n_lon; ++j) m.add_facet({ring(n_lat - 1, j), south, ring(n_lat - 1, j + 1)});
  return m;
}

} // namespace seam::search::test
