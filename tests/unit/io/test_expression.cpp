// Expression: values against hand-computed ones, the constant/time/space flags, copies that
// stay bound to their own variables, and syntax errors that say what and where.
#include "seam/common/error.hpp"
#include "seam/io/expression.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

namespace seam::io {
namespace {

constexpr double pi = std::numbers::pi;

std::string error_of(const std::string& source) {
  try {
    Expression expression(source);
  } catch (const InputError& error) {
    return error.what();
  }
  ADD_FAILURE() << "'" << source << "' compiled";
  return {};
}

TEST(Expression, NumberIsAConstant) {
  const Expression e(0.1);
  EXPECT_TRUE(e.is_constant());
  EXPECT_FALSE(e.uses_time());
  EXPECT_FALSE(e.uses_space());
  EXPECT_EQ(e(5.0, 1.0, 2.0, 3.0), 0.1);
  EXPECT_EQ(e.source(), "0.1"); // exact, not "0.100000"
  EXPECT_EQ(Expression()(1.0), 0.0);
  EXPECT_EQ(Expression(-2.5e-300)(0.0), -2.5e-300);
}

TEST(Expression, ConstantStringIsFoldedAndKnowsPi) {
  const Expression e("2*_pi + 1");
  EXPECT_TRUE(e.is_constant());
  EXPECT_DOUBLE_EQ(e(0.0), 2.0 * pi + 1.0);
  EXPECT_EQ(e.source(), "2*_pi + 1");
  // Full double precision, not muparser's 12-decimal built-ins.
  EXPECT_EQ(Expression("_pi")(0.0), pi);
  EXPECT_EQ(Expression("_e")(0.0), std::numbers::e);
  EXPECT_NEAR(Expression("sin(_pi*t)")(1.0), 0.0, 1e-15);
}

TEST(Expression, LoadCurveFromTheContract) {
  const Expression e("2000*sin(2*_pi*t)*(t<=0.5)");
  EXPECT_FALSE(e.is_constant());
  EXPECT_TRUE(e.uses_time());
  EXPECT_FALSE(e.uses_space());
  EXPECT_NEAR(e(0.125), 2000.0 * std::sqrt(0.5), 1e-9);
  EXPECT_NEAR(e(0.25), 2000.0, 1e-9);
  EXPECT_NEAR(e(0.375), 2000.0 * std::sqrt(0.5), 1e-9);
  EXPECT_EQ(e(0.5000001), 0.0);
  EXPECT_EQ(e(0.75), 0.0);
}

TEST(Expression, AllFourVariables) {
  const Expression e("x^2 + 2*y - z/4 + 10*t");
  EXPECT_TRUE(e.uses_time());
  EXPECT_TRUE(e.uses_space());
  // 2.25 - 4 - 2 + 1 = -2.75
  EXPECT_DOUBLE_EQ(e(0.1, 1.5, -2.0, 8.0), -2.75);
  EXPECT_DOUBLE_EQ(e(0.0, 0.0, 0.0, 0.0), 0.0);
  const Expression space_only("sqrt(x*x + y*y + z*z)");
  EXPECT_FALSE(space_only.uses_time());
  EXPECT_TRUE(space_only.uses_space());
  EXPECT_DOUBLE_EQ(space_only(9.0, 2.0, 3.0, 6.0), 7.0);
}

TEST(Expression, DefaultCoordinatesAreZero) {
  const Expression e("t + x + y + z + 1");
  EXPECT_EQ(e(2.0), 3.0);
}

// If a copy were bound to the original's variables (muparser's own copy semantics), it would
// read the original's last x instead of its own.
TEST(Expression, CopyIsBoundToItsOwnVariables) {
  const Expression original("x");
  EXPECT_EQ(original(0.0, 1.0), 1.0);
  const Expression copy(original);
  EXPECT_EQ(copy(0.0, 5.0), 5.0);
  EXPECT_EQ(original(0.0, 2.0), 2.0);
  EXPECT_EQ(copy(0.0, 7.0), 7.0);
  EXPECT_FALSE(copy.is_constant());
  EXPECT_EQ(copy.source(), "x");

  Expression assigned(3.0);
  assigned = original;
  EXPECT_EQ(assigned(0.0, 11.0), 11.0);
  EXPECT_EQ(original(0.0, -1.0), -1.0);
  EXPECT_TRUE(assigned.uses_space());
}

TEST(Expression, CopyOutlivesOriginal) {
  std::vector<Expression> copies;
  {
    const Expression original("t*y");
    copies.assign(3, original);
  }
  for (int i = 0; i < 3; ++i) EXPECT_EQ(copies[i](2.0, 0.0, 1.5 * i), 3.0 * i);
}

TEST(Expression, MovesKeepTheBindingThroughReallocation) {
  std::vector<Expression> expressions;
  for (int i = 0; i < 50; ++i) expressions.emplace_back(std::to_string(i) + " + t*x");
  for (int i = 0; i < 50; ++i) EXPECT_EQ(expressions[i](2.0, 3.0), i + 6.0);

  Expression moved(std::move(expressions[7]));
  EXPECT_EQ(moved(1.0, 1.0), 8.0);
  Expression target("y");
  target = std::move(moved);
  EXPECT_EQ(target(1.0, 2.0), 9.0);
  EXPECT_TRUE(target.uses_time());
}

TEST(Expression, SelfAssignmentIsHarmless) {
  Expression e("z");
  const Expression& alias = e;
  e = alias;
  EXPECT_EQ(e(0, 0, 0, 4.0), 4.0);
}

TEST(Expression, SyntaxErrorGivesParserMessageAndPosition) {
  const std::string message = error_of("1 + x*/2");
  EXPECT_NE(message.find("1 + x*/2"), std::string::npos) << message;
  EXPECT_NE(message.find("position 6"), std::string::npos) << message;
  EXPECT_NE(message.find("Unexpected"), std::string::npos) << message;
  // The caret sits under the offending character.
  EXPECT_NE(message.find("\n    1 + x*/2\n          ^"), std::string::npos) << message;
}

TEST(Expression, UnknownVariableIsAnError) {
  const std::string message = error_of("2*w + t");
  EXPECT_NE(message.find("\"w\""), std::string::npos) << message;
  EXPECT_NE(message.find("position 2"), std::string::npos) << message;
}

TEST(Expression, UnbalancedParenthesisIsAnError) {
  const std::string message = error_of("sin(2*t");
  EXPECT_NE(message.find("sin(2*t"), std::string::npos) << message;
  EXPECT_NE(message.find("arenthes"), std::string::npos) << message;
}

TEST(Expression, EmptyAndMultipleResultsAreErrors) {
  EXPECT_THROW(Expression(""), InputError);
  const std::string message = error_of("t, x");
  EXPECT_NE(message.find("one scalar"), std::string::npos) << message;
}

} // namespace
} // namespace seam::io
