#pragma once
// Fixed quadrature rules of the mortar integration cells: the 5-point Gauss–Legendre rule
// per 2D segment (ALGORITHMS.md §1) and the 7-point degree-5 rule per 3D triangle cell
// (ALGORITHMS.md §2, step 6; Strang & Fix 1973, table 4.1, after Radon 1948). They are
// compile-time tables so the per-cell loops stay allocation-free and inlined.
#include <array>

namespace seam::geometry {

/// Gauss–Legendre rule on [-1, 1], exact for polynomials of degree <= 9; weights sum to 2.
struct LineRule5 {
  static constexpr int n_points = 5;
  static constexpr std::array<double, 5> points = {
      -0.906179845938663992797626878299, -0.538469310105683091036314420700, 0.0,
      0.538469310105683091036314420700, 0.906179845938663992797626878299};
  static constexpr std::array<double, 5> weights = {
      0.236926885056189087514264040720, 0.478628670499366468041291514836,
      0.568888888888888888888888888889, 0.478628670499366468041291514836,
      0.236926885056189087514264040720};
};

/// Triangle rule exact for polynomials of total degree <= 5, in barycentric coordinates;
/// weights sum to 1, so an integral is area * sum_q w_q f(x_q).
struct TriangleRule7 {
  static constexpr int n_points = 7;
  static constexpr double a1 = 0.101286507323456338800987361915;
  static constexpr double b1 = 0.797426985353087322398025276170;
  static constexpr double a2 = 0.470142064105115089770441209513;
  static constexpr double b2 = 0.059715871789769820459117580973;
  static constexpr double w0 = 0.225;
  static constexpr double w1 = 0.125939180544827152595683945500;
  static constexpr double w2 = 0.132394152788506180737649387833;
  static constexpr std::array<std::array<double, 3>, 7> barycentric = {{
      {1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0},
      {a1, a1, b1},
      {a1, b1, a1},
      {b1, a1, a1},
      {a2, a2, b2},
      {a2, b2, a2},
      {b2, a2, a2},
  }};
  static constexpr std::array<double, 7> weights = {w0, w1, w1, w1, w2, w2, w2};
};

} // namespace seam::geometry
