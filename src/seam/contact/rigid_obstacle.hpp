#pragma once
// The analytic surface of a rigid obstacle in its current position: a plane, a sphere (a circle
// in 2D) or a circular cylinder. All three are described by a signed distance g(x) that is
// positive on the slave body's side (open) and negative inside the obstacle (penetration):
//   plane:     g = n . (x - p)                      (n: unit normal towards the body)
//   sphere:    g = |x - c| - R
//   cylinder:  g = |P (x - p)| - R,   P = I - a a^T  (a: unit axis through p)
// The outward unit normal of a round obstacle at the closest point to x is m = P r / |P r|,
// r = x - c (P = I for the sphere), and its derivative dm/dx = (P - m m^T) / |P r|; the contact
// normal of a slave node (out of the slave body, towards the obstacle) is -m, or -n for the
// plane (constant). The obstacle only translates (prescribed motion), so these formulas hold
// in the current configuration with p (or c) moved.
#include <array>
#include <cmath>

namespace seam::contact {

struct Obstacle {
  enum class Shape { plane, sphere, cylinder };
  Shape shape = Shape::plane;
  std::array<double, 3> point{};     ///< plane point, sphere centre or point of the axis
  std::array<double, 3> direction{}; ///< plane: unit normal towards the body; cylinder: unit axis
  double radius = 0.0;               ///< sphere and cylinder

  bool round() const { return shape != Shape::plane; }
  const char* name() const {
    return shape == Shape::plane ? "a rigid plane"
                                 : (shape == Shape::sphere ? "a rigid sphere" : "a rigid cylinder");
  }

  /// g(x) for a point x of dimension Dim (any scalar type with +, *, sqrt).
  template <class S, int Dim, class Point> S distance(const Point& x) const {
    using std::sqrt;
    if (shape == Shape::plane) {
      S g = 0.0;
      for (int c = 0; c < Dim; ++c) g += direction[c] * (x(c) - point[c]);
      return g;
    }
    std::array<S, Dim> r;
    for (int c = 0; c < Dim; ++c) r[c] = x(c) - point[c];
    if (shape == Shape::cylinder) {
      S along = 0.0;
      for (int c = 0; c < Dim; ++c) along += direction[c] * r[c];
      for (int c = 0; c < Dim; ++c) r[c] -= along * direction[c];
    }
    S r2 = 0.0;
    for (int c = 0; c < Dim; ++c) r2 += r[c] * r[c];
    return sqrt(r2) - radius;
  }

  /// Contact normal -m at the point x (dim values) into n, and if `jacobian` is given dn/dx
  /// (row a, column b at a * dim + b; zero for the plane).
  void contact_normal(int dim, const double* x, double* n, double* jacobian) const {
    if (shape == Shape::plane) {
      for (int a = 0; a < dim; ++a) n[a] = -direction[a];
      if (jacobian)
        for (int k = 0; k < dim * dim; ++k) jacobian[k] = 0.0;
      return;
    }
    double r[3] = {0, 0, 0}, along = 0.0, length = 0.0;
    for (int c = 0; c < dim; ++c) r[c] = x[c] - point[c];
    if (shape == Shape::cylinder) {
      for (int c = 0; c < dim; ++c) along += direction[c] * r[c];
      for (int c = 0; c < dim; ++c) r[c] -= along * direction[c];
    }
    for (int c = 0; c < dim; ++c) length += r[c] * r[c];
    length = std::sqrt(length);
    // On the axis (centre) the normal is undefined; such a node is deep inside the obstacle,
    // far outside any admissible state. Any unit vector keeps the state finite.
    if (!(length > 0.0)) {
      for (int c = 0; c < dim; ++c) n[c] = c == dim - 1 ? 1.0 : 0.0;
      if (jacobian)
        for (int k = 0; k < dim * dim; ++k) jacobian[k] = 0.0;
      return;
    }
    for (int c = 0; c < dim; ++c) n[c] = -r[c] / length;
    if (!jacobian) return;
    // dn/dx = -(P - m m^T) / |P r| with m = -n.
    for (int a = 0; a < dim; ++a)
      for (int b = 0; b < dim; ++b) {
        double p = a == b ? 1.0 : 0.0;
        if (shape == Shape::cylinder) p -= direction[a] * direction[b];
        jacobian[a * dim + b] = -(p - n[a] * n[b]) / length;
      }
  }
};

} // namespace seam::contact
