// Gauss-Jacobi rules: the Golub-Welsch eigenvalues of the Jacobi matrix (Golub & Welsch,
// Math. Comp. 23, 1969) give starting points, Newton on the three-term recurrence of
// P_n^(alpha,beta) polishes them to full precision, and the weights come from the closed form
// w_i = 2^(a+b+1) G(n+a+1) G(n+b+1) / (G(n+a+b+1) n!) / ((1 - x_i^2) P_n'(x_i)^2)
// (Abramowitz & Stegun 25.4.33). Built once per rule and cached by the callers, so the small
// dense eigenproblem is not on any hot path.
#include "seam/fem/gauss.hpp"

#include "seam/common/error.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace seam::fem {

namespace {

struct JacobiValue {
  double p;  // P_n(x)
  double dp; // P_n'(x)
};

// Three-term recurrence (A&S 22.7.1) and the derivative identity (A&S 22.8.1):
// (2n+a+b)(1-x^2) P_n' = n [(a-b) - (2n+a+b) x] P_n + 2 (n+a)(n+b) P_{n-1}.
JacobiValue jacobi(int n, double a, double b, double x) {
  double p_prev = 1.0;
  double p = 0.5 * (a - b + (a + b + 2.0) * x);
  for (int k = 2; k <= n; ++k) {
    const double c = 2.0 * k + a + b;
    const double a1 = 2.0 * k * (k + a + b) * (c - 2.0);
    const double a2 = (c - 1.0) * (a * a - b * b);
    const double a3 = (c - 2.0) * (c - 1.0) * c;
    const double a4 = 2.0 * (k + a - 1.0) * (k + b - 1.0) * c;
    const double p_next = ((a2 + a3 * x) * p - a4 * p_prev) / a1;
    p_prev = p;
    p = p_next;
  }
  const double c = 2.0 * n + a + b;
  const double dp =
      (n * ((a - b) - c * x) * p + 2.0 * (n + a) * (n + b) * p_prev) / (c * (1.0 - x * x));
  return {p, dp};
}

} // namespace

void gauss_jacobi(int n, double alpha, double beta, std::span<double> points,
                  std::span<double> weights) {
  SEAM_CHECK(n >= 1, InputError, "a Gauss rule needs at least one point, got n = ", n);
  SEAM_CHECK(alpha > -1.0 && beta > -1.0, InputError,
             "Gauss-Jacobi weights need alpha, beta > -1, got alpha = ", alpha, ", beta = ", beta);
  SEAM_CHECK(points.size() == static_cast<std::size_t>(n) &&
                 weights.size() == static_cast<std::size_t>(n),
             InputError, "Gauss-Jacobi output buffers must hold n = ", n, " values");
  const double a = alpha;
  const double b = beta;

  // Jacobi matrix of the orthonormal recurrence; its eigenvalues are the Gauss points.
  Eigen::VectorXd diag(n);
  Eigen::VectorXd sub(std::max(n - 1, 1));
  diag(0) = (b - a) / (a + b + 2.0);
  for (int k = 1; k < n; ++k) {
    const double c = 2.0 * k + a + b;
    diag(k) = (b * b - a * a) / (c * (c + 2.0));
  }
  for (int k = 1; k < n; ++k) {
    const double c = 2.0 * k + a + b;
    // k = 1 is written with (k + a + b) / (c - 1) = 1 cancelled, which is 0/0 when a + b = -1.
    const double num =
        k == 1 ? 4.0 * (1.0 + a) * (1.0 + b) : 4.0 * k * (k + a) * (k + b) * (k + a + b);
    const double den = k == 1 ? c * c * (c + 1.0) : c * c * (c + 1.0) * (c - 1.0);
    sub(k - 1) = std::sqrt(num / den);
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver;
  solver.computeFromTridiagonal(diag, sub.head(n - 1), Eigen::EigenvaluesOnly);
  SEAM_CHECK(solver.info() == Eigen::Success, InternalError,
             "Gauss-Jacobi eigenproblem failed for n = ", n);

  const double log_c = (a + b + 1.0) * std::log(2.0) + std::lgamma(n + a + 1.0) +
                       std::lgamma(n + b + 1.0) - std::lgamma(n + a + b + 1.0) -
                       std::lgamma(n + 1.0);
  const double c = std::exp(log_c);
  for (int i = 0; i < n; ++i) {
    double x = solver.eigenvalues()(i);
    for (int it = 0; it < 10; ++it) {
      const JacobiValue v = jacobi(n, a, b, x);
      const double dx = v.p / v.dp;
      x -= dx;
      if (std::abs(dx) <= 1e-16 * std::max(1.0, std::abs(x))) break;
    }
    const double dp = jacobi(n, a, b, x).dp;
    points[static_cast<std::size_t>(i)] = x;
    weights[static_cast<std::size_t>(i)] = c / ((1.0 - x * x) * dp * dp);
  }
}

void gauss_legendre(int n, std::span<double> points, std::span<double> weights) {
  gauss_jacobi(n, 0.0, 0.0, points, weights);
  // Exact symmetry, so that odd functions integrate to zero to the last bit.
  for (int i = 0; i < n / 2; ++i) {
    const auto lo = static_cast<std::size_t>(i);
    const auto hi = static_cast<std::size_t>(n - 1 - i);
    const double x = 0.5 * (points[hi] - points[lo]);
    const double w = 0.5 * (weights[hi] + weights[lo]);
    points[lo] = -x;
    points[hi] = x;
    weights[lo] = w;
    weights[hi] = w;
  }
  if (n % 2 == 1) points[static_cast<std::size_t>(n / 2)] = 0.0;
}

} // namespace seam::fem
