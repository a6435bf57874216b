// seam::Dual beyond plain arithmetic: what a constant and a value-initialized dual number
// are, and that the accumulating operations stay exact when the accumulator is also an
// operand (x += x * y written as add_product(x, x, y)), against hand-derived derivatives.
#include <gtest/gtest.h>

#include "seam/common/dual_number.hpp"

using seam::Dual;

TEST(LinearizationDual, ConstantsAndValueInitializationAreZero) {
  const Dual<5> c(2.5);
  EXPECT_EQ(c.value, 2.5);
  for (const double g : c.gradient) EXPECT_EQ(g, 0.0);
  const Dual<5> z{};
  EXPECT_EQ(z.value, 0.0);
  for (const double g : z.gradient) EXPECT_EQ(g, 0.0);
  const Eigen::Matrix<Dual<5>, 2, 2> m = Eigen::Matrix<Dual<5>, 2, 2>::Zero();
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(m(i).value, 0.0);
    for (const double g : m(i).gradient) EXPECT_EQ(g, 0.0);
  }
}

TEST(LinearizationDual, AccumulationWithAliasedOperands) {
  // x = 3 + e0, y = -2 + e1. add_product(x, x, y): x + x y = 3 - 6 = -3, gradient
  // (1 + y, x) = (-1, 3). Then x *= x: 9, gradient 2 x dx = (6, -18). Then x /= x: 1, 0.
  using D = Dual<2>;
  D x = D::variable(3.0, 0);
  const D y = D::variable(-2.0, 1);
  add_product(x, x, y);
  EXPECT_DOUBLE_EQ(x.value, -3.0);
  EXPECT_DOUBLE_EQ(x.gradient[0], -1.0);
  EXPECT_DOUBLE_EQ(x.gradient[1], 3.0);
  x *= x;
  EXPECT_DOUBLE_EQ(x.value, 9.0);
  EXPECT_DOUBLE_EQ(x.gradient[0], 6.0);
  EXPECT_DOUBLE_EQ(x.gradient[1], -18.0);
  D r = x;
  r /= r;
  EXPECT_DOUBLE_EQ(r.value, 1.0);
  EXPECT_DOUBLE_EQ(r.gradient[0], 0.0);
  EXPECT_DOUBLE_EQ(r.gradient[1], 0.0);
  // add_product(x, x, 2): x + 2 x = 27, gradient 3 (6, -18).
  add_product(x, x, 2.0);
  EXPECT_DOUBLE_EQ(x.value, 27.0);
  EXPECT_DOUBLE_EQ(x.gradient[0], 18.0);
  EXPECT_DOUBLE_EQ(x.gradient[1], -54.0);
  // x - x and x + x through the binary operators.
  const D d = x - x, s = x + x;
  EXPECT_EQ(d.value, 0.0);
  EXPECT_EQ(d.gradient[1], 0.0);
  EXPECT_DOUBLE_EQ(s.gradient[1], -108.0);
}
