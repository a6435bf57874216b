#pragma once
// Second-order forward-mode automatic differentiation as seam::Hyper (hyper_dual.hpp), with
// the symmetric Hessian stored once: its upper triangle packed row by row, N (N + 1) / 2
// numbers instead of N^2. Every operation then runs over contiguous memory (Hyper's products
// write the lower triangle by columns) and moves half the bytes: on the kernels with many
// variables (the weighted gaps of quadratic contact facets, 81 variables) the time goes into
// memory traffic, not arithmetic. Same chain rules, same values to round-off.
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

template <int N> SymHyper<N> operator-(SymHyper<N> a) {
  a *= -1.0;
  return a;
}
template <int N> SymHyper<N> operator+(SymHyper<N> a, const SymHyper<N>& b) {
  return a += b;
}
template <int N> SymHyper<N> operator-(SymHyper<N> a, const SymHyper<N>& b) {
  return a -= b;
}

/// acc = alpha acc + a b over the Hessian (alpha 0: overwrite), the product rule's terms.
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
template <int N> void add_product(SymHyper<N>& acc, const SymHyper<N>& a, double b) {
  acc.value += a.value * b;
  for (int i = 0; i < N; ++i) acc.gradient[i] += b * a.gradient[i];
  for (int i = 0; i < SymHyper<N>::n_packed; ++i) acc.hessian[i] += b * a.hessian[i];
}
template <int N> void add_product(SymHyper<N>& acc, double a, const SymHyper<N>& b) {
  add_product(acc, b, a);
}

template <int N> SymHyper<N> inverse(const SymHyper<N>& b) {
  const double q = 1.0 / b.value;
  return b.chain(q, -q * q, 2.0 * q * q * q);
}
template <int N> SymHyper<N> operator/(const SymHyper<N>& a, const SymHyper<N>& b) {
  return a * inverse(b);
}
template <int N> SymHyper<N> operator+(SymHyper<N> a, double b) {
  a.value += b;
  return a;
}
template <int N> SymHyper<N> operator+(double a, SymHyper<N> b) {
  b.value += a;
  return b;
}
template <int N> SymHyper<N> operator-(SymHyper<N> a, double b) {
  a.value -= b;
  return a;
}
template <int N> SymHyper<N> operator-(double a, const SymHyper<N>& b) {
  SymHyper<N> r = -b;
  r.value += a;
  return r;
}
template <int N> SymHyper<N> operator*(SymHyper<N> a, double b) {
  return a *= b;
}
template <int N> SymHyper<N> operator*(double a, SymHyper<N> b) {
  return b *= a;
}
template <int N> SymHyper<N> operator/(SymHyper<N> a, double b) {
  return a *= 1.0 / b;
}
template <int N> SymHyper<N> operator/(double a, const SymHyper<N>& b) {
  return inverse(b) * a;
}
template <int N> SymHyper<N> sqrt(const SymHyper<N>& a) {
  const double s = std::sqrt(a.value);
  return a.chain(s, 0.5 / s, -0.25 / (s * a.value));
}

template <int N> bool operator<(const SymHyper<N>& a, double b) {
  return a.value < b;
}
template <int N> bool operator>(const SymHyper<N>& a, double b) {
  return a.value > b;
}
template <int N> double value_of(const SymHyper<N>& x) {
  return x.value;
}

} // namespace seam
