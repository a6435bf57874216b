#pragma once
// A scalar function f(t, x, y, z) given in the input as a number or as a muparser string,
// e.g. "2000*sin(2*_pi*t)*(t<=0.5)". Loads, prescribed displacements, initial velocities and
// rigid-body motions are all of this form.
#include <memory>
#include <string>
#include <string_view>

namespace seam::io {

class Expression {
public:
  /// The constant 0.
  Expression();
  /// A constant; no parser is built, evaluation is a load.
  Expression(double value); // implicit on purpose: a number is an expression
  /// Compiles `source` in the variables t, x, y, z (muparser syntax; `_pi` and `_e` are
  /// built in). Throws InputError with muparser's message and the position of the error.
  explicit Expression(std::string_view source);

  // muparser binds variables by address, so a copy compiles its own parser bound to its own
  // variables. A move hands over the heap block that holds parser and variables together,
  // so the bound addresses stay valid and nothing is recompiled.
  Expression(const Expression& other);
  Expression& operator=(const Expression& other);
  Expression(Expression&& other) noexcept;
  Expression& operator=(Expression&& other) noexcept;
  ~Expression();

  /// Evaluates at time t and point (x, y, z). Not safe to call concurrently on the same
  /// object (the variables live inside it); copies are independent of each other.
  double operator()(double t, double x = 0.0, double y = 0.0, double z = 0.0) const;

  /// True if the expression uses none of t, x, y, z (a number, or e.g. "2*_pi").
  [[nodiscard]] bool is_constant() const { return !state_; }
  /// True if the value changes with t (a time-dependent load or motion).
  [[nodiscard]] bool uses_time() const { return uses_t_; }
  /// True if the value changes with x, y or z.
  [[nodiscard]] bool uses_space() const { return uses_xyz_; }
  /// The text the expression was compiled from (a number is printed exactly).
  [[nodiscard]] const std::string& source() const { return source_; }

private:
  struct State; // muparser parser + the variables it is bound to
  void compile();

  std::string source_ = "0";
  double constant_ = 0.0;
  bool uses_t_ = false;
  bool uses_xyz_ = false;
  std::unique_ptr<State> state_; // null for constants
};

} // namespace seam::io
