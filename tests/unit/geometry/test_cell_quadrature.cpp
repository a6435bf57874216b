// The fixed cell rules integrate monomials exactly up to their stated degree, and not beyond.
#include <cmath>

#include <gtest/gtest.h>

#include "seam/geometry/cell_quadrature.hpp"

namespace {
double factorial(int n) {
  return n <= 1 ? 1.0 : n * factorial(n - 1);
}
} // namespace

TEST(CellQuadrature, LineRuleExactToDegreeNine) {
  using Rule = seam::geometry::LineRule5;
  for (int k = 0; k <= 10; ++k) {
    double sum = 0.0;
    for (int q = 0; q < Rule::n_points; ++q) sum += Rule::weights[q] * std::pow(Rule::points[q], k);
    const double exact = k % 2 == 1 ? 0.0 : 2.0 / (k + 1);
    if (k <= 9) {
      EXPECT_NEAR(sum, exact, 1e-15) << k;
    } else {
      EXPECT_GT(std::abs(sum - exact), 1e-4) << "degree 10 should not be exact";
    }
  }
}

TEST(CellQuadrature, TriangleRuleExactToDegreeFive) {
  // Unit reference triangle (0,0), (1,0), (0,1) of area 1/2: int x^a y^b = a! b! / (a+b+2)!.
  using Rule = seam::geometry::TriangleRule7;
  double weight_sum = 0.0;
  for (double w : Rule::weights) weight_sum += w;
  EXPECT_NEAR(weight_sum, 1.0, 1e-15);
  bool some_degree6_inexact = false;
  for (int a = 0; a <= 6; ++a) {
    for (int b = 0; a + b <= 6; ++b) {
      double sum = 0.0;
      for (int q = 0; q < Rule::n_points; ++q) {
        const double x = Rule::barycentric[q][1], y = Rule::barycentric[q][2];
        sum += 0.5 * Rule::weights[q] * std::pow(x, a) * std::pow(y, b);
      }
      const double exact = factorial(a) * factorial(b) / factorial(a + b + 2);
      if (a + b <= 5) {
        EXPECT_NEAR(sum, exact, 1e-16) << a << " " << b;
      } else if (std::abs(sum - exact) > 1e-8) {
        some_degree6_inexact = true;
      }
    }
  }
  EXPECT_TRUE(some_degree6_inexact);
}
