#pragma once
// Second-order forward-mode automatic differentiation (Griewank & Walther, Evaluating
// Derivatives, 2nd ed. 2008, ch. 13): a number x = v + g . e + e^T H e / 2 over N independent
// variables carries its value, gradient and Hessian through every arithmetic operation, so
// a kernel written on a scalar template parameter gives exact second derivatives with
// Hyper<N> (and first derivatives with Dual<N>, values with double). Comparisons look at
// values only, which freezes every branch at the evaluation point, as with seam::Dual.
//
// The chain rule of a unary function f: value f(v), gradient f'(v) g, Hessian
// f'(v) H + f''(v) g g^T; of a product: H_ab = a H_b + b H_a + g_a g_b^T + g_b g_a^T.
#include <array>
#include <cmath>
#include <cstddef>
#include <type_traits>

namespace seam {

template <int N> struct Hyper {
  static constexpr int n_variables = N;
  double value;
  std::array<double, N> gradient;
  std::array<double, N * N> hessian; ///< row-major, symmetric

  Hyper() : value(0.0), gradient{}, hessian{} {}
  Hyper(double v) : value(v), gradient{}, hessian{} {} // NOLINT(google-explicit-constructor)
  /// A number whose gradient and Hessian the caller writes in full (no zero fill first: the
  /// products of a kernel with many variables spend their time in memory traffic).
  struct Uninitialized {};
  Hyper(double v, Uninitialized) : value(v) {} // gradient and hessian are default-initialized

  static Hyper variable(double v, int i) {
    Hyper x(v);
    x.gradient[static_cast<std::size_t>(i)] = 1.0;
    return x;
  }
  double second(int i, int k) const { return hessian[static_cast<std::size_t>(i * N + k)]; }

  /// f(this) for f with f(v) = f0, f'(v) = f1, f''(v) = f2.
  Hyper chain(double f0, double f1, double f2) const {
    Hyper r(f0, Uninitialized{});
    for (int i = 0; i < N; ++i) r.gradient[i] = f1 * gradient[i];
    for (int i = 0; i < N; ++i) {
      const double gi = f2 * gradient[i];
      for (int k = i; k < N; ++k)
        r.hessian[i * N + k] = r.hessian[k * N + i] = f1 * hessian[i * N + k] + gi * gradient[k];
    }
    return r;
  }

  Hyper& operator+=(const Hyper& b) {
    value += b.value;
    for (int i = 0; i < N; ++i) gradient[i] += b.gradient[i];
    for (int i = 0; i < N * N; ++i) hessian[i] += b.hessian[i];
    return *this;
  }
  Hyper& operator-=(const Hyper& b) {
    value -= b.value;
    for (int i = 0; i < N; ++i) gradient[i] -= b.gradient[i];
    for (int i = 0; i < N * N; ++i) hessian[i] -= b.hessian[i];
    return *this;
  }
  Hyper& operator*=(double b) {
    value *= b;
    for (int i = 0; i < N; ++i) gradient[i] *= b;
    for (int i = 0; i < N * N; ++i) hessian[i] *= b;
    return *this;
  }
};

template <int N> Hyper<N> operator*(const Hyper<N>& a, const Hyper<N>& b) {
  Hyper<N> r(a.value * b.value, typename Hyper<N>::Uninitialized{});
  for (int i = 0; i < N; ++i) r.gradient[i] = a.value * b.gradient[i] + b.value * a.gradient[i];
  // The Hessian is symmetric: the upper triangle, mirrored.
  for (int i = 0; i < N; ++i) {
    const double ai = a.gradient[i], bi = b.gradient[i];
    for (int k = i; k < N; ++k)
      r.hessian[i * N + k] = r.hessian[k * N + i] = a.value * b.hessian[i * N + k] +
                                                    b.value * a.hessian[i * N + k] +
                                                    ai * b.gradient[k] + bi * a.gradient[k];
  }
  return r;
}
/// acc += a b without a temporary (the multiply-accumulate of the kernels' sums).
template <int N> void add_product(Hyper<N>& acc, const Hyper<N>& a, const Hyper<N>& b) {
  acc.value += a.value * b.value;
  for (int i = 0; i < N; ++i) acc.gradient[i] += a.value * b.gradient[i] + b.value * a.gradient[i];
  for (int i = 0; i < N; ++i) {
    const double ai = a.gradient[i], bi = b.gradient[i];
    for (int k = i; k < N; ++k) {
      const double h = a.value * b.hessian[i * N + k] + b.value * a.hessian[i * N + k] +
                       ai * b.gradient[k] + bi * a.gradient[k];
      acc.hessian[i * N + k] += h;
      if (k != i) acc.hessian[k * N + i] += h;
    }
  }
}
/// The second-order numbers: Hyper<N> and SymHyper<N> (sym_hyper.hpp), whose sums,
/// arithmetic with doubles, inverse, quotient, sqrt and comparisons below follow from their
/// value, chain(), +=, -=, *= and product.
template <class T> inline constexpr bool is_second_order = false;
template <int N> inline constexpr bool is_second_order<Hyper<N>> = true;
template <class T>
concept SecondOrder = is_second_order<T>;

template <SecondOrder T> T operator-(T a) {
  a *= -1.0;
  return a;
}
template <SecondOrder T> T operator+(T a, const T& b) {
  return a += b;
}
template <SecondOrder T> T operator-(T a, const T& b) {
  return a -= b;
}
template <SecondOrder T> T inverse(const T& b) {
  const double q = 1.0 / b.value;
  return b.chain(q, -q * q, 2.0 * q * q * q);
}
template <SecondOrder T> T operator/(const T& a, const T& b) {
  return a * inverse(b);
}
template <SecondOrder T> T operator+(T a, double b) {
  a.value += b;
  return a;
}
template <SecondOrder T> T operator+(double a, T b) {
  b.value += a;
  return b;
}
template <SecondOrder T> T operator-(T a, double b) {
  a.value -= b;
  return a;
}
template <SecondOrder T> T operator-(double a, const T& b) {
  T r = -b;
  r.value += a;
  return r;
}
template <SecondOrder T> T operator*(T a, double b) {
  return a *= b;
}
template <SecondOrder T> T operator*(double a, T b) {
  return b *= a;
}
template <SecondOrder T> T operator/(T a, double b) {
  return a *= 1.0 / b;
}
template <SecondOrder T> T operator/(double a, const T& b) {
  return inverse(b) * a;
}
template <SecondOrder T> T sqrt(const T& a) {
  const double s = std::sqrt(a.value);
  return a.chain(s, 0.5 / s, -0.25 / (s * a.value));
}

template <SecondOrder T> bool operator<(const T& a, double b) {
  return a.value < b;
}
template <SecondOrder T> bool operator>(const T& a, double b) {
  return a.value > b;
}

template <SecondOrder T> double value_of(const T& x) {
  return x.value;
}

/// acc += a b for a number b.
template <SecondOrder T> void add_product(T& acc, const T& a, double b) {
  acc.value += a.value * b;
  for (std::size_t i = 0; i < a.gradient.size(); ++i) acc.gradient[i] += b * a.gradient[i];
  for (std::size_t i = 0; i < a.hessian.size(); ++i) acc.hessian[i] += b * a.hessian[i];
}
template <SecondOrder T> void add_product(T& acc, double a, const T& b) {
  add_product(acc, b, a);
}

/// Independent variable i of value v on the scalar type S: S::variable(v, i) for Dual<N> and
/// Hyper<N>, v itself for double (so one kernel serves values, gradients and Hessians).
template <class S> S independent_variable(double v, int i) {
  if constexpr (std::is_same_v<S, double>) {
    (void)i;
    return v;
  } else {
    return S::variable(v, i);
  }
}

} // namespace seam
