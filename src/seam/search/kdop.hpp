#pragma once
// Discretized orientation polytopes (k-DOPs): the bounding volumes of seam's contact search.
//
// A k-DOP is the intersection of k/2 slabs lo_s <= d_s . x <= hi_s with fixed directions d_s
// (seed paper Sect. 3.2; Yang & Laursen, Comput Mech 41 (2008) 189). seam uses the 8-DOP in
// 2D and the 18-DOP in 3D, and the AABB (k = 2 dim) for comparison; the directions are those of
// ALGORITHMS.md Sect. 6. Directions are left unnormalized (their projections are sums and
// differences of coordinates, no multiplications); a widening by a distance delta is then
// delta * |d_s|. Bounds are stored in float, rounded outwards, which halves the memory traffic
// of refit and traversal while every k-DOP still contains its exact (double) counterpart.
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace seam::search {

/// Which bounding volume a tree uses.
enum class BoundingVolume {
  kdop, ///< 8-DOP in 2D, 18-DOP in 3D (the default)
  aabb  ///< axis-aligned box, for comparison
};

/// Number of slab directions (k/2) of a bounding volume in `dim` dimensions.
constexpr int n_slabs(int dim, BoundingVolume volume) {
  if (volume == BoundingVolume::aabb) return dim;
  return dim == 2 ? 4 : 9;
}

/// A k-DOP with NS = k/2 slabs; slab s is [lo[s], hi[s]] along direction s of slab_direction().
/// The first `dim` slabs are always the coordinate axes, so (lo[0..dim), hi[0..dim)) is the
/// axis-aligned box of any k-DOP.
template <int NS> struct Kdop {
  std::array<float, NS> lo;
  std::array<float, NS> hi;

  /// The empty k-DOP (neutral element of merge).
  static Kdop empty() {
    Kdop k;
    k.lo.fill(std::numeric_limits<float>::infinity());
    k.hi.fill(-std::numeric_limits<float>::infinity());
    return k;
  }
};

/// Closed overlap test: true iff every slab pair intersects (touching counts). All slabs are
/// compared without branches, four at a time with SSE2 where available: the traversal spends
/// most of its time here, and a mispredicted early exit costs more than the remaining compares.
template <int NS> inline bool overlap(const Kdop<NS>& a, const Kdop<NS>& b) {
  int s = 0;
  bool separated = false;
#if defined(__SSE2__)
  if constexpr (NS >= 4) {
    __m128 sep = _mm_setzero_ps();
    for (; s + 4 <= NS; s += 4) {
      sep = _mm_or_ps(sep, _mm_cmpgt_ps(_mm_loadu_ps(&a.lo[s]), _mm_loadu_ps(&b.hi[s])));
      sep = _mm_or_ps(sep, _mm_cmpgt_ps(_mm_loadu_ps(&b.lo[s]), _mm_loadu_ps(&a.hi[s])));
    }
    separated = _mm_movemask_ps(sep) != 0;
  }
#endif
  for (; s < NS; ++s) separated |= (a.lo[s] > b.hi[s]) | (b.lo[s] > a.hi[s]);
  return !separated;
}

/// Smallest k-DOP containing a and b.
template <int NS> inline Kdop<NS> merge(const Kdop<NS>& a, const Kdop<NS>& b) {
  Kdop<NS> m;
  for (int s = 0; s < NS; ++s) {
    m.lo[s] = a.lo[s] < b.lo[s] ? a.lo[s] : b.lo[s];
    m.hi[s] = a.hi[s] > b.hi[s] ? a.hi[s] : b.hi[s];
  }
  return m;
}

/// Sum of the axis extents (the "margin"); used as a size measure that stays meaningful for
/// flat (zero-volume) boxes, e.g. for the rebuild criterion.
template <int Dim, int NS> inline double margin(const Kdop<NS>& k) {
  double m = 0.0;
  for (int s = 0; s < Dim; ++s) m += static_cast<double>(k.hi[s]) - static_cast<double>(k.lo[s]);
  return m;
}

/// Direction d_s of slab s (unnormalized), padded with zeros to three components.
constexpr std::array<double, 3> slab_direction(int dim, int ns, int s) {
  if (dim == 2) {
    constexpr std::array<std::array<double, 3>, 4> d2{
        {{1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {-1, 1, 0}}};
    return d2[s];
  }
  constexpr std::array<std::array<double, 3>, 9> d3{{{1, 0, 0},
                                                     {0, 1, 0},
                                                     {0, 0, 1},
                                                     {1, 1, 0},
                                                     {1, 0, 1},
                                                     {0, 1, 1},
                                                     {1, 0, -1},
                                                     {1, -1, 0},
                                                     {0, 1, -1}}};
  (void)ns;
  return d3[s];
}

/// Projections d_s . x of one point onto all slab directions; written out so that they cost
/// only additions.
template <int Dim, int NS> inline void project(const double* x, double* p) {
  static_assert((Dim == 2 && (NS == 2 || NS == 4)) || (Dim == 3 && (NS == 3 || NS == 9)));
  if constexpr (Dim == 2) {
    p[0] = x[0];
    p[1] = x[1];
    if constexpr (NS == 4) {
      p[2] = x[0] + x[1];
      p[3] = x[1] - x[0];
    }
  } else {
    p[0] = x[0];
    p[1] = x[1];
    p[2] = x[2];
    if constexpr (NS == 9) {
      p[3] = x[0] + x[1];
      p[4] = x[0] + x[2];
      p[5] = x[1] + x[2];
      p[6] = x[0] - x[2];
      p[7] = x[0] - x[1];
      p[8] = x[1] - x[2];
    }
  }
}

/// |d_s|: 1 for the axes, sqrt(2) for the diagonals.
template <int Dim, int NS> constexpr double slab_norm(int s) {
  return s < Dim ? 1.0 : 1.4142135623730951;
}

/// A float <= v, at most about 3 float ulps below it. Rounding to nearest is off by at most
/// 2^-24 |v|; stepping down by 2^-22 |v| (plus a tiny absolute amount for v near 0) first makes
/// the result a lower bound without a branch or a libm call, so that the leaf loops vectorize.
inline float round_down(double v) {
  return static_cast<float>(v - (std::abs(v) * 0x1p-22 + 0x1p-120));
}

/// A float >= v, at most about 3 float ulps above it (see round_down).
inline float round_up(double v) {
  return static_cast<float>(v + (std::abs(v) * 0x1p-22 + 0x1p-120));
}

/// Accumulates the double-precision slab intervals of a point set, then widens them by a
/// distance and rounds outwards into a float k-DOP.
template <int Dim, int NS> struct KdopBuilder {
  std::array<double, NS> lo;
  std::array<double, NS> hi;

  KdopBuilder() {
    lo.fill(std::numeric_limits<double>::infinity());
    hi.fill(-std::numeric_limits<double>::infinity());
  }

  void add_point(const double* x) {
    double p[NS];
    project<Dim, NS>(x, p);
    for (int s = 0; s < NS; ++s) {
      lo[s] = p[s] < lo[s] ? p[s] : lo[s];
      hi[s] = p[s] > hi[s] ? p[s] : hi[s];
    }
  }

  /// The k-DOP of the points grown by `inflation` in every direction: it contains every point
  /// within distance `inflation` of the convex hull of the points added.
  Kdop<NS> finish(double inflation) const {
    Kdop<NS> k;
    for (int s = 0; s < NS; ++s) {
      const double w = inflation * slab_norm<Dim, NS>(s);
      k.lo[s] = round_down(lo[s] - w);
      k.hi[s] = round_up(hi[s] + w);
    }
    return k;
  }
};

} // namespace seam::search
