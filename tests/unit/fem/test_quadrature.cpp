// Quadrature: 1D Gauss rules against closed forms and Beta-function moments; every cell rule
// integrates all monomials up to its stated degree exactly (closed-form integrals on the
// reference domain), has positive weights summing to the reference measure and interior
// points; the cache is shared and thread-safe.
#include "fem_test_support.hpp"
#include "seam/common/error.hpp"
#include "seam/fem/cell.hpp"
#include "seam/fem/gauss.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <thread>
#include <vector>

namespace seam::fem {
namespace {

using test::all_cell_types;

double factorial(int n) {
  return std::tgamma(n + 1.0);
}

// int over the reference domain of xi^a eta^b zeta^c.
double exact_monomial_integral(CellType t, int a, int b, int c) {
  const int dim = dimension(t);
  if (dim == 0) return 1.0;
  if (test::is_simplex(t)) {
    // Dirichlet integral on the unit simplex: a! b! c! / (a + b + c + dim)!
    return factorial(a) * factorial(b) * factorial(c) / factorial(a + b + c + dim);
  }
  const auto line = [](int p) { return p % 2 == 1 ? 0.0 : 2.0 / (p + 1); };
  double v = line(a);
  if (dim >= 2) v *= line(b);
  if (dim >= 3) v *= line(c);
  return v;
}

// All moments sum_q w_q xi^a eta^b zeta^c for a, b, c <= d, indexed (c * (d+1) + b) * (d+1) + a,
// from per-point power tables (std::pow per monomial and point would dominate the test's time).
std::vector<double> moments(const QuadratureRule& q, int d) {
  const auto m = static_cast<std::size_t>(d + 1);
  std::vector<double> result(m * m * m, 0.0);
  std::vector<double> powers(3 * m);
  for (int i = 0; i < q.n_points; ++i) {
    for (std::size_t a = 0; a < 3; ++a) {
      const double x =
          static_cast<int>(a) < q.dim ? q.points[static_cast<std::size_t>(i * q.dim) + a] : 0.0;
      powers[a * m] = 1.0;
      for (std::size_t k = 1; k < m; ++k) powers[a * m + k] = powers[a * m + k - 1] * x;
    }
    const double w = q.weights[static_cast<std::size_t>(i)];
    for (std::size_t c = 0; c < m; ++c)
      for (std::size_t b = 0; b < m; ++b)
        for (std::size_t a = 0; a < m; ++a)
          result[(c * m + b) * m + a] += w * powers[a] * powers[m + b] * powers[2 * m + c];
  }
  return result;
}

TEST(Gauss, LegendreExactToDegree2nMinus1AndNoFurther) {
  for (int n = 1; n <= 40; ++n) {
    std::vector<double> x(static_cast<std::size_t>(n)), w(static_cast<std::size_t>(n));
    gauss_legendre(n, x, w);
    for (int i = 0; i < n; ++i) {
      const auto ui = static_cast<std::size_t>(i);
      EXPECT_GT(w[ui], 0.0);
      EXPECT_GT(x[ui], -1.0);
      EXPECT_LT(x[ui], 1.0);
      if (i > 0) {
        EXPECT_GT(x[ui], x[ui - 1]);
      }
      EXPECT_EQ(x[ui], -x[static_cast<std::size_t>(n - 1 - i)]);
    }
    for (int p = 0; p <= 2 * n; ++p) {
      double s = 0.0;
      for (int i = 0; i < n; ++i)
        s += w[static_cast<std::size_t>(i)] * std::pow(x[static_cast<std::size_t>(i)], p);
      const double exact = p % 2 == 1 ? 0.0 : 2.0 / (p + 1);
      if (p < 2 * n) {
        EXPECT_NEAR(s, exact, 2e-15 * (n + 1)) << "n = " << n << ", x^" << p;
      } else if (n <= 12) {
        // Sharp: the Gauss error of x^2n is 2^(2n+1) (n!)^4 / ((2n+1) ((2n)!)^2) (Abramowitz &
        // Stegun §25.4).
        const double error = std::exp((2 * n + 1) * std::log(2.0) + 4 * std::lgamma(n + 1.0) -
                                      std::log(2.0 * n + 1) - 2 * std::lgamma(2 * n + 1.0));
        EXPECT_NEAR((exact - s) / error, 1.0, 1e-6) << "n = " << n;
      }
    }
  }
}

// Gauss-Chebyshev (alpha = beta = -1/2) has closed-form points and weights.
TEST(Gauss, JacobiReducesToChebyshev) {
  for (int n = 1; n <= 30; ++n) {
    std::vector<double> x(static_cast<std::size_t>(n)), w(static_cast<std::size_t>(n));
    gauss_jacobi(n, -0.5, -0.5, x, w);
    for (int i = 0; i < n; ++i) {
      const double expected = -std::cos((2.0 * i + 1.0) * std::numbers::pi / (2.0 * n));
      EXPECT_NEAR(x[static_cast<std::size_t>(i)], expected, 1e-14) << "n = " << n;
      EXPECT_NEAR(w[static_cast<std::size_t>(i)], std::numbers::pi / n, 1e-13) << "n = " << n;
    }
  }
}

// int_{-1}^{1} (1-x)^alpha (1+x)^(beta+k) dx = 2^(alpha+beta+k+1) B(alpha+1, beta+k+1).
TEST(Gauss, JacobiMomentsExact) {
  for (const auto& [alpha, beta] : std::vector<std::pair<double, double>>{
           {1.0, 0.0}, {2.0, 0.0}, {0.5, 1.5}, {0.0, 3.0}, {-0.5, 0.25}}) {
    for (int n = 1; n <= 25; ++n) {
      std::vector<double> x(static_cast<std::size_t>(n)), w(static_cast<std::size_t>(n));
      gauss_jacobi(n, alpha, beta, x, w);
      for (int k = 0; k < 2 * n; ++k) {
        double s = 0.0;
        for (int i = 0; i < n; ++i)
          s += w[static_cast<std::size_t>(i)] * std::pow(1.0 + x[static_cast<std::size_t>(i)], k);
        const double exact =
            std::exp((alpha + beta + k + 1) * std::log(2.0) + std::lgamma(alpha + 1) +
                     std::lgamma(beta + k + 1) - std::lgamma(alpha + beta + k + 2));
        EXPECT_NEAR(s / exact, 1.0, 1e-13)
            << "alpha " << alpha << " beta " << beta << " n " << n << " k " << k;
      }
    }
  }
}

TEST(Gauss, RejectsBadArguments) {
  std::vector<double> x(2), w(2);
  EXPECT_THROW(gauss_jacobi(0, 0.0, 0.0, x, w), InputError);
  EXPECT_THROW(gauss_jacobi(2, -1.0, 0.0, x, w), InputError);
  EXPECT_THROW(gauss_jacobi(3, 0.0, 0.0, x, w), InputError);
}

int highest_tested_degree(CellType t) {
  switch (dimension(t)) {
  case 0:
    return 8;
  case 1:
    return 45;
  case 2:
    return 22;
  default:
    return test::is_simplex(t) ? 20 : 15;
  }
}

TEST(Quadrature, IntegratesMonomialsUpToStatedDegreeExactly) {
  for (CellType t : all_cell_types) {
    SCOPED_TRACE(name(t));
    const int dim = dimension(t);
    for (int degree = 0; degree <= highest_tested_degree(t); ++degree) {
      const QuadratureRule q = quadrature(t, degree);
      ASSERT_EQ(q.dim, dim);
      ASSERT_GE(q.degree, degree);
      ASSERT_EQ(q.points.size(), static_cast<std::size_t>(q.n_points * dim));
      ASSERT_EQ(q.weights.size(), static_cast<std::size_t>(q.n_points));
      double sum = 0.0;
      for (int i = 0; i < q.n_points; ++i) {
        EXPECT_GT(q.weights[static_cast<std::size_t>(i)], 0.0) << "degree " << degree;
        EXPECT_TRUE(test::inside_reference(t, q.points.data() + i * dim, -1e-12))
            << "degree " << degree << " point " << i << " not interior";
        sum += q.weights[static_cast<std::size_t>(i)];
      }
      EXPECT_NEAR(sum, test::reference_measure(t), 1e-14 * test::reference_measure(t));
      const int d = q.degree;
      const auto m = moments(q, d);
      for (int c = 0; c <= (dim >= 3 ? d : 0); ++c)
        for (int b = 0; b <= (dim >= 2 ? d : 0); ++b)
          for (int a = 0; a <= (dim >= 1 ? d : 0); ++a) {
            if (test::is_simplex(t) && a + b + c > d) continue;
            const double exact = exact_monomial_integral(t, a, b, c);
            const double got = m[static_cast<std::size_t>((c * (d + 1) + b) * (d + 1) + a)];
            EXPECT_NEAR(got, exact, 1e-14 * test::reference_measure(t) + 1e-13 * std::abs(exact))
                << "degree " << degree << " monomial " << a << " " << b << " " << c;
          }
    }
  }
}

TEST(Quadrature, CheapestRules) {
  const auto n = [](CellType t, int d) { return quadrature(t, d).n_points; };
  for (int d = 0; d <= 20; ++d) {
    EXPECT_EQ(n(CellType::line2, d), d / 2 + 1);
    EXPECT_EQ(n(CellType::quad4, d), (d / 2 + 1) * (d / 2 + 1));
    EXPECT_EQ(n(CellType::hex27, d), (d / 2 + 1) * (d / 2 + 1) * (d / 2 + 1));
  }
  const std::array<int, 7> tri{1, 1, 3, 6, 6, 7, 16};
  const std::array<int, 7> tet{1, 1, 4, 8, 14, 14, 64};
  for (int d = 0; d <= 6; ++d) {
    EXPECT_EQ(n(CellType::tri3, d), tri[static_cast<std::size_t>(d)]) << "degree " << d;
    EXPECT_EQ(n(CellType::tet10, d), tet[static_cast<std::size_t>(d)]) << "degree " << d;
  }
  EXPECT_EQ(quadrature(CellType::tri6, 3).degree, 4);
  EXPECT_EQ(quadrature(CellType::tet4, 4).degree, 5);
}

// The symmetric simplex rules are invariant under the vertex permutations: integrating a
// non-symmetric polynomial of degree <= d gives the same value as for any permuted copy, which
// the monomial test implies; here the orbit structure itself is checked on the 14-point rule.
TEST(Quadrature, SymmetricTetRuleIsInvariantUnderVertexSwap) {
  const QuadratureRule q = quadrature(CellType::tet4, 5);
  for (int i = 0; i < q.n_points; ++i) {
    const double* x = q.points.data() + 3 * i;
    bool found = false; // swap xi <-> eta must map the point set onto itself
    for (int j = 0; j < q.n_points && !found; ++j) {
      const double* y = q.points.data() + 3 * j;
      found = std::abs(x[0] - y[1]) + std::abs(x[1] - y[0]) + std::abs(x[2] - y[2]) < 1e-15 &&
              q.weights[static_cast<std::size_t>(i)] == q.weights[static_cast<std::size_t>(j)];
    }
    EXPECT_TRUE(found) << "point " << i;
  }
}

TEST(Quadrature, RejectsUnavailableDegrees) {
  for (CellType t : all_cell_types) {
    EXPECT_THROW(quadrature(t, -1), InputError);
    EXPECT_THROW(quadrature(t, max_quadrature_degree + 1), InputError);
    EXPECT_NO_THROW(quadrature(t, max_quadrature_degree));
  }
}

TEST(Quadrature, CachedAndThreadSafe) {
  // Every thread asks for every rule at once; all must see the same storage.
  std::vector<std::thread> threads;
  std::vector<std::vector<const double*>> seen(4);
  for (std::size_t k = 0; k < seen.size(); ++k)
    threads.emplace_back([&seen, k] {
      for (CellType t : all_cell_types)
        for (int d = 0; d <= 12; ++d) seen[k].push_back(quadrature(t, d).weights.data());
    });
  for (auto& th : threads) th.join();
  for (std::size_t k = 1; k < seen.size(); ++k) EXPECT_EQ(seen[k], seen[0]);
  EXPECT_EQ(quadrature(CellType::hex8, 3).points.data(),
            quadrature(CellType::hex8, 3).points.data());
}

// The default rule integrates the reference mass matrix int N_i N_j exactly: compare with a
// rule of twice the degree (exact by the monomial test above).
TEST(Quadrature, DefaultDegreeIntegratesMassMatrix) {
  for (CellType t : all_cell_types) {
    SCOPED_TRACE(name(t));
    EXPECT_EQ(default_quadrature_degree(t), 2 * order(t));
    const int n = n_nodes(t);
    const auto mass = [&](const QuadratureRule& q) {
      std::vector<double> M(static_cast<std::size_t>(n * n), 0.0);
      std::array<double, max_cell_nodes> N{};
      for (int p = 0; p < q.n_points; ++p) {
        shape_values(t, q.points.data() + p * q.dim, N.data());
        for (int i = 0; i < n; ++i)
          for (int j = 0; j < n; ++j)
            M[static_cast<std::size_t>(i * n + j)] += q.weights[static_cast<std::size_t>(p)] *
                                                      N[static_cast<std::size_t>(i)] *
                                                      N[static_cast<std::size_t>(j)];
      }
      return M;
    };
    const auto M = mass(quadrature(t, default_quadrature_degree(t)));
    const auto M_ref = mass(quadrature(t, 4 * std::max(order(t), 1) + 2));
    for (std::size_t k = 0; k < M.size(); ++k) EXPECT_NEAR(M[k], M_ref[k], 1e-14);
  }
}

} // namespace
} // namespace seam::fem
