#pragma once
// Second-order forward-mode automatic differentiation as seam::Hyper (hyper_dual.hpp), with
// the symmetric Hessian stored once: its upper triangle packed row by row, N (N + 1) / 2
// numbers instead of N^2. Every operation then runs over contiguous memory (Hyper's products
// write the lower triangle by columns) and moves half the bytes: on the kernels with many
// variables (the weighted gaps of quadratic contact facets, 81 variables) the time goes into
// memory traffic, not arithmetic. Same chain rules, same values to round-off; the operations
// that follow from value, chain() and the product are hyper_dual.hpp's (SecondOrder).
#include "seam/common/hyper_dual.hpp"

#include <array>
#include <cmath>
#include <cstddef>

namespace seam {

template <int N> struct SymHyper {
  static constexpr int n_variables = N;
  static constexpr int n_packed = N * (N + 1) / 2;
  double value;
  std::array<double, N> gradient;
  std::array<double, n_packed> hessian; ///< upper triangle, row by row

  /// Index of the first entry (i, i) of row i in the packed triangle.
  static constexpr int row(int i) { return i * N - i * (i - 1) / 2; }
  /// Index of entry (i, k) for i <= k.
  static constexpr int at(int i, int k) { return row(i) + k - i; }

  SymHyper() : value(0.0), gradient{}, hessian{} {}
  SymHyper(double v) : value(v), gradient{}, hessian{} {} // NOLINT(google-explicit-constructor)
  struct Uninitialized {};
  SymHyper(double v, Uninitialized) : value(v) {}

  static SymHyper variable(double v, int i) {
    SymHyper x(v);
    x.gradient[static_cast<std::size_t>(i)] = 1.0;
    return x;
  }
  double second(int i, int k) const {
    return hessian[static_cast<std::size_t>(i <= k ? at(i, k) : at(k, i))];
  }

  /// f(this) for f with f(v) = f0, f'(v) = f1, f''(v) = f2.
  SymHyper chain(double f0, double f1, double f2) const {
    SymHyper r(f0, Uninitialized{});
    for (int i = 0; i < N; ++i) r.gradient[i] = f1 * gradient[i];
    for (int i = 0; i < N; ++i) {
      const double gi = f2 * gradient[i];
      double* out = r.hessian.data() + row(i) - i;
      const double* h = hessian.data() + row(i) - i;
      for (int k = i; k < N; ++k) out[k] = f1 * h[k] + gi * gradient[k];
    }
    return r;
  }

  SymHyper& operator+=(const SymHyper& b) {
    value += b.value;
    for (int i = 0; i < N; ++i) gradient[i] += b.gradient[i];
    for (int i = 0; i < n_packed; ++i) hessian[i] += b.hessian[i];
    return *this;
  }
  SymHyper& operator-=(const SymHyper& b) {
    value -= b.value;
    for (int i = 0; i < N; ++i) gradient[i] -= b.gradient[i];
    for (int i = 0; i < n_packed; ++i) hessian[i] -= b.hessian[i];
    return *this;
  }
  SymHyper& operator*=(double b) {
    value *= b;
    for (int i = 0; i < N; ++i) gradient[i] *= b;
    for (int i = 0; i < n_packed; ++i) hessian[i] *= b;
    return *this;
  }
};

template <int N> inline constexpr bool is_second_order<SymHyper<N>> = true;

/// The gradient and Hessian of a b (the product rule) added to acc's or, without Accumulate,
/// written over them.
template <int N, bool Accumulate>
void product_into(SymHyper<N>& acc, const SymHyper<N>& a, const SymHyper<N>& b) {
  const double av = a.value, bv = b.value;
  for (int i = 0; i < N; ++i) {
    const double g = av * b.gradient[i] + bv * a.gradient[i];
    acc.gradient[i] = Accumulate ? acc.gradient[i] + g : g;
  }
  for (int i = 0; i < N; ++i) {
    const double ai = a.gradient[i], bi = b.gradient[i];
    const std::ptrdiff_t o = SymHyper<N>::row(i) - i;
    double* out = acc.hessian.data() + o;
    const double* ah = a.hessian.data() + o;
    const double* bh = b.hessian.data() + o;
    for (int k = i; k < N; ++k) {
      const double h = av * bh[k] + bv * ah[k] + ai * b.gradient[k] + bi * a.gradient[k];
      out[k] = Accumulate ? out[k] + h : h;
    }
  }
}

template <int N> SymHyper<N> operator*(const SymHyper<N>& a, const SymHyper<N>& b) {
  SymHyper<N> r(a.value * b.value, typename SymHyper<N>::Uninitialized{});
  product_into<N, false>(r, a, b);
  return r;
}
/// acc += a b without a temporary.
template <int N> void add_product(SymHyper<N>& acc, const SymHyper<N>& a, const SymHyper<N>& b) {
  acc.value += a.value * b.value;
  product_into<N, true>(acc, a, b);
}
} // namespace seam
