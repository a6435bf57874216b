#pragma once
// Forward-mode automatic differentiation with dual numbers (Griewank & Walther, Evaluating
// Derivatives, 2nd ed. 2008, ch. 3): x = v + sum_i g_i e_i with e_i e_k = 0 carries a value v
// and its gradient g with respect to N independent variables through every arithmetic
// operation, so a kernel written once on a scalar template parameter yields exact first
// derivatives when instantiated with Dual<N> and plain values with double.
//
// The gradient has a compile-time capacity N and lives inline: no heap traffic in per-element
// kernels. Comparisons look at values only, which freezes every branch (case tables, clipping
// combinatorics) at the evaluation point — the derivative is that of the smooth branch taken.
// The Eigen traits at the end let fixed-size Eigen matrices hold dual numbers.
#include <array>
#include <cmath>
#include <limits>

#include <Eigen/Core>

namespace seam {

/// The gradient comes first and the type is 16-byte aligned, so that the gradient loops below
/// run on aligned packed vectors; every loop writes a local array or its own operand only, so
/// the compiler needs no aliasing checks to vectorize it.
template <int N> struct alignas(16) Dual {
  static_assert(N > 0, "a dual number needs at least one variable");
  static constexpr int n_variables = N;

  std::array<double, N> gradient; ///< uninitialized after default construction, see below
  double value = 0.0;

  // Like a double, a default-constructed dual number holds no defined gradient: the per-pair
  // kernels hold fixed-capacity arrays of them (polygons, nodal vectors), and zeroing every
  // unused slot would cost more than the arithmetic. Dual{}, Dual(0.0) and Zero() are zero.
  Dual() = default;
  // Implicit on purpose: constants enter dual expressions with a zero gradient.
  Dual(double v) : gradient{}, value(v) {} // NOLINT(google-explicit-constructor)

  /// The independent variable number i with value v.
  static Dual variable(double v, int i) {
    Dual x(v);
    x.gradient[static_cast<std::size_t>(i)] = 1.0;
    return x;
  }

  Dual& operator+=(const Dual& b) {
    const std::array<double, N> g = b.gradient;
    for (int i = 0; i < N; ++i) gradient[i] += g[i];
    value += b.value;
    return *this;
  }
  Dual& operator-=(const Dual& b) {
    const std::array<double, N> g = b.gradient;
    for (int i = 0; i < N; ++i) gradient[i] -= g[i];
    value -= b.value;
    return *this;
  }
  Dual& operator*=(const Dual& b) {
    const double av = value, bv = b.value;
    const std::array<double, N> g = b.gradient;
    for (int i = 0; i < N; ++i) gradient[i] = bv * gradient[i] + av * g[i];
    value = av * bv;
    return *this;
  }
  Dual& operator/=(const Dual& b) {
    const double inv = 1.0 / b.value;
    const double q = value * inv;
    const std::array<double, N> g = b.gradient;
    for (int i = 0; i < N; ++i) gradient[i] = (gradient[i] - q * g[i]) * inv;
    value = q;
    return *this;
  }
  Dual& operator+=(double b) {
    value += b;
    return *this;
  }
  Dual& operator-=(double b) {
    value -= b;
    return *this;
  }
  Dual& operator*=(double b) {
    value *= b;
    for (int i = 0; i < N; ++i) gradient[i] *= b;
    return *this;
  }
  Dual& operator/=(double b) { return *this *= 1.0 / b; }
};

template <int N> Dual<N> operator+(const Dual<N>& a) {
  return a;
}
template <int N> Dual<N> operator-(const Dual<N>& a) {
  Dual<N> r(-a.value);
  for (int i = 0; i < N; ++i) r.gradient[i] = -a.gradient[i];
  return r;
}
template <int N> Dual<N> operator+(const Dual<N>& a, const Dual<N>& b) {
  Dual<N> r(a.value + b.value);
  for (int i = 0; i < N; ++i) r.gradient[i] = a.gradient[i] + b.gradient[i];
  return r;
}
template <int N> Dual<N> operator-(const Dual<N>& a, const Dual<N>& b) {
  Dual<N> r(a.value - b.value);
  for (int i = 0; i < N; ++i) r.gradient[i] = a.gradient[i] - b.gradient[i];
  return r;
}
template <int N> Dual<N> operator*(const Dual<N>& a, const Dual<N>& b) {
  const double av = a.value, bv = b.value;
  Dual<N> r(av * bv);
  for (int i = 0; i < N; ++i) r.gradient[i] = bv * a.gradient[i] + av * b.gradient[i];
  return r;
}
template <int N> Dual<N> operator/(const Dual<N>& a, const Dual<N>& b) {
  const double inv = 1.0 / b.value;
  const double q = a.value * inv;
  Dual<N> r(q);
  for (int i = 0; i < N; ++i) r.gradient[i] = (a.gradient[i] - q * b.gradient[i]) * inv;
  return r;
}
template <int N> Dual<N> operator+(Dual<N> a, double b) {
  return a += b;
}
template <int N> Dual<N> operator+(double a, Dual<N> b) {
  return b += a;
}
template <int N> Dual<N> operator-(Dual<N> a, double b) {
  return a -= b;
}
template <int N> Dual<N> operator-(double a, const Dual<N>& b) {
  Dual<N> r = -b;
  r.value += a;
  return r;
}
template <int N> Dual<N> operator*(Dual<N> a, double b) {
  return a *= b;
}
template <int N> Dual<N> operator*(double a, Dual<N> b) {
  return b *= a;
}
template <int N> Dual<N> operator/(Dual<N> a, double b) {
  return a /= b;
}
template <int N> Dual<N> operator/(double a, const Dual<N>& b) {
  // d(a/b) = -a/b^2 db
  const double inv = 1.0 / b.value;
  Dual<N> r(a * inv);
  const double factor = -r.value * inv;
  for (int i = 0; i < N; ++i) r.gradient[i] = factor * b.gradient[i];
  return r;
}

// Comparisons see values only (branches are frozen at the evaluation point).
#define SEAM_DUAL_COMPARISON(op)                                                                   \
  template <int N> bool operator op(const Dual<N>& a, const Dual<N>& b) {                          \
    return a.value op b.value;                                                                     \
  }                                                                                                \
  template <int N> bool operator op(const Dual<N>& a, double b) {                                  \
    return a.value op b;                                                                           \
  }                                                                                                \
  template <int N> bool operator op(double a, const Dual<N>& b) {                                  \
    return a op b.value;                                                                           \
  }
SEAM_DUAL_COMPARISON(<)
SEAM_DUAL_COMPARISON(<=)
SEAM_DUAL_COMPARISON(>)
SEAM_DUAL_COMPARISON(>=)
SEAM_DUAL_COMPARISON(==)
SEAM_DUAL_COMPARISON(!=)
#undef SEAM_DUAL_COMPARISON

template <int N> Dual<N> sqrt(const Dual<N>& a) {
  Dual<N> r(std::sqrt(a.value));
  const double factor = 0.5 / r.value;
  for (int i = 0; i < N; ++i) r.gradient[i] = factor * a.gradient[i];
  return r;
}
template <int N> Dual<N> cbrt(const Dual<N>& a) {
  Dual<N> r(std::cbrt(a.value));
  const double factor = r.value / (3.0 * a.value);
  for (int i = 0; i < N; ++i) r.gradient[i] = factor * a.gradient[i];
  return r;
}
/// |a|; at a = 0 the derivative of the positive branch.
template <int N> Dual<N> abs(const Dual<N>& a) {
  return a.value < 0.0 ? -a : a;
}
template <int N> bool isfinite(const Dual<N>& a) {
  if (!std::isfinite(a.value)) return false;
  for (const double g : a.gradient)
    if (!std::isfinite(g)) return false;
  return true;
}

/// acc += a * b without temporaries (the hot operation of interpolation and quadrature sums).
inline void add_product(double& acc, double a, double b) {
  acc += a * b;
}
template <int N> void add_product(Dual<N>& acc, const Dual<N>& a, const Dual<N>& b) {
  const double av = a.value, bv = b.value;
  std::array<double, N> g;
  for (int i = 0; i < N; ++i) g[i] = av * b.gradient[i] + bv * a.gradient[i];
  for (int i = 0; i < N; ++i) acc.gradient[i] += g[i];
  acc.value += av * bv;
}
template <int N> void add_product(Dual<N>& acc, const Dual<N>& a, double b) {
  const double av = a.value;
  std::array<double, N> g;
  for (int i = 0; i < N; ++i) g[i] = b * a.gradient[i];
  for (int i = 0; i < N; ++i) acc.gradient[i] += g[i];
  acc.value += av * b;
}
template <int N> void add_product(Dual<N>& acc, double a, const Dual<N>& b) {
  add_product(acc, b, a);
}

/// The value of a plain or dual scalar, for decisions and value-only algorithms.
inline double value_of(double x) {
  return x;
}
template <int N> double value_of(const Dual<N>& x) {
  return x.value;
}

/// True for Dual<N>.
template <class S> inline constexpr bool is_dual = false;
template <int N> inline constexpr bool is_dual<Dual<N>> = true;

} // namespace seam

namespace Eigen {

// The traits of a number type built on double (forward-mode AD: Dual<N> here, Hyper<N> where
// a kernel uses it in Eigen), with the cost of reading, adding and multiplying one.
template <class S, int Read, int Add, int Mul> struct AdNumTraits : GenericNumTraits<double> {
  using Real = S;
  using NonInteger = S;
  using Nested = S;
  using Literal = S;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = Read,
    AddCost = Add,
    MulCost = Mul
  };
  static Real epsilon() { return Real(std::numeric_limits<double>::epsilon()); }
  static Real dummy_precision() { return Real(1e-12); }
  static Real highest() { return Real(std::numeric_limits<double>::max()); }
  static Real lowest() { return Real(std::numeric_limits<double>::lowest()); }
  static int digits10() { return std::numeric_limits<double>::digits10; }
};

template <int N>
struct NumTraits<seam::Dual<N>> : AdNumTraits<seam::Dual<N>, N + 1, N + 1, 2 * N + 1> {};

template <int N, class BinaryOp> struct ScalarBinaryOpTraits<seam::Dual<N>, double, BinaryOp> {
  using ReturnType = seam::Dual<N>;
};
template <int N, class BinaryOp> struct ScalarBinaryOpTraits<double, seam::Dual<N>, BinaryOp> {
  using ReturnType = seam::Dual<N>;
};

} // namespace Eigen
