#pragma once
// Small 2- and 3-vectors over the scalar types of the weighted-gap kernels (double, Dual<N>,
// Hyper<N>): gap_blocks.cpp (2D) and gap_blocks_3d.cpp (3D).
#include "seam/common/dual_number.hpp"
#include "seam/common/hyper_dual.hpp"

#include <Eigen/Core>

#include <cmath>

namespace seam::contact::gap_vectors {

/// A 2-vector; v(0), v(1), s * v and v / s make it a vertex of the polygon clip of
/// mortar/linearization_clip.hpp.
template <class S> struct V2 {
  S x = S(0.0), y = S(0.0);
  const S& operator()(int i) const { return i == 0 ? x : y; }
};
template <class S> struct V3 { S x = S(0.0), y = S(0.0), z = S(0.0); };

template <class S> V2<S> operator+(const V2<S>& a, const V2<S>& b) {
  return {a.x + b.x, a.y + b.y};
}
template <class S> V2<S> operator-(const V2<S>& a, const V2<S>& b) {
  return {a.x - b.x, a.y - b.y};
}
template <class S, class T> V2<S> operator*(const V2<S>& a, const T& s) {
  return {a.x * s, a.y * s};
}
template <class S, class T> V2<S> operator*(const T& s, const V2<S>& a) {
  return {s * a.x, s * a.y};
}
template <class S, class T> V2<S> operator/(const V2<S>& a, const T& s) {
  return {a.x / s, a.y / s};
}
template <class S> S dot(const V2<S>& a, const V2<S>& b) {
  return a.x * b.x + a.y * b.y;
}
/// The z component of a x b.
template <class S> S cross(const V2<S>& a, const V2<S>& b) {
  return a.x * b.y - a.y * b.x;
}
template <class S> S length(const V2<S>& a) {
  using std::sqrt;
  return sqrt(dot(a, a));
}
template <class S> Eigen::Vector2d value(const V2<S>& a) {
  return {value_of(a.x), value_of(a.y)};
}

template <class S> V3<S> operator+(const V3<S>& a, const V3<S>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class S> V3<S> operator-(const V3<S>& a, const V3<S>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class S, class T> V3<S> operator*(const V3<S>& a, const T& s) {
  return {a.x * s, a.y * s, a.z * s};
}
template <class S> S dot(const V3<S>& a, const V3<S>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class S> V3<S> cross(const V3<S>& a, const V3<S>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class S> S norm(const V3<S>& a) {
  using std::sqrt;
  return sqrt(dot(a, a));
}
template <class S> Eigen::Vector3d value(const V3<S>& a) {
  return {value_of(a.x), value_of(a.y), value_of(a.z)};
}

} // namespace seam::contact::gap_vectors
