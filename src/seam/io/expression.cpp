#include "seam/io/expression.hpp"

#include "seam/common/error.hpp"

#include <muParser.h>

#include <array>
#include <charconv>
#include <numbers>

namespace seam::io {

// Parser and variables share one heap block: the parser holds the variables' addresses, and
// a unique_ptr move keeps the block (hence those addresses) where it is.
struct Expression::State {
  mu::Parser parser;
  double t = 0.0;
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
};

namespace {

std::string exact_text(double value) {
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return {buffer.data(), result.ptr};
}

// muparser reports a 0-based character position; show it under the text, as compilers do.
std::string describe_parser_error(const std::string& source, const mu::ParserError& error) {
  std::string message =
      seam::detail::concat("cannot parse expression \"", source, "\": ", error.GetMsg());
  const int position = error.GetPos();
  if (position >= 0 && static_cast<std::size_t>(position) <= source.size()) {
    message += seam::detail::concat(" (position ", position, ")\n    ", source, "\n    ",
                                    std::string(static_cast<std::size_t>(position), ' '), "^");
  }
  return message;
}

} // namespace

Expression::Expression() = default;

Expression::Expression(double value) : source_(exact_text(value)), constant_(value) {}

Expression::Expression(std::string_view source) : source_(source) {
  compile();
}

Expression::Expression(const Expression& other)
    : source_(other.source_), constant_(other.constant_), uses_t_(other.uses_t_),
      uses_xyz_(other.uses_xyz_) {
  if (other.state_) compile();
}

Expression& Expression::operator=(const Expression& other) {
  if (this != &other) {
    Expression copy(other);
    *this = std::move(copy);
  }
  return *this;
}

Expression::Expression(Expression&& other) noexcept = default;
Expression& Expression::operator=(Expression&& other) noexcept = default;
Expression::~Expression() = default;

void Expression::compile() {
  auto state = std::make_unique<State>();
  mu::Parser& parser = state->parser;
  try {
    parser.DefineVar("t", &state->t);
    parser.DefineVar("x", &state->x);
    parser.DefineVar("y", &state->y);
    parser.DefineVar("z", &state->z);
    // muparser 2.3's built-in _pi and _e carry only 12 decimals (an error of 8e-13 that
    // shows in sin(2*_pi*t) at t = 1); give them every digit of a double.
    parser.DefineConst("_pi", std::numbers::pi);
    parser.DefineConst("_e", std::numbers::e);
    parser.SetExpr(source_);
    // muparser parses lazily; evaluating once makes every syntax error surface here, at
    // input time, instead of in the middle of a run.
    const double value = parser.Eval();
    SEAM_CHECK(parser.GetNumResults() == 1, InputError, "expression \"", source_, "\" has ",
               parser.GetNumResults(), " comma-separated results; one scalar is expected here");
    const auto& used = parser.GetUsedVar();
    uses_t_ = used.count("t") > 0;
    uses_xyz_ = used.count("x") > 0 || used.count("y") > 0 || used.count("z") > 0;
    if (used.empty()) {
      constant_ = value;
      state_.reset();
      return;
    }
  } catch (const mu::ParserError& error) {
    throw InputError(describe_parser_error(source_, error));
  }
  state_ = std::move(state);
}

double Expression::operator()(double t, double x, double y, double z) const {
  if (!state_) return constant_;
  state_->t = t;
  state_->x = x;
  state_->y = y;
  state_->z = z;
  try {
    return state_->parser.Eval();
  } catch (const mu::ParserError& error) {
    throw InputError(describe_parser_error(source_, error));
  }
}

} // namespace seam::io
