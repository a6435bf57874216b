#pragma once
// Errors: user-caused problems are exceptions with a message (always on); internal
// invariants are SEAM_ASSERT (debug only). The CLI maps each type to an exit code.
#include <cassert>
#include <sstream>
#include <stdexcept>
#include <string>

namespace seam {

/// Bad input: YAML, schema, mesh, missing file. Exit code 1.
class InputError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// The nonlinear solver gave up after all step cuts. Exit code 2.
class SolverError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// Anything else that went wrong inside seam. Exit code 3.
class InternalError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

namespace detail {
template <class... Args> std::string concat(const Args&... args) {
  std::ostringstream s;
  (s << ... << args);
  return s.str();
}
} // namespace detail

} // namespace seam

/// Throw `Type` with a message assembled from the streamable arguments.
#define SEAM_THROW(Type, ...) throw Type(::seam::detail::concat(__VA_ARGS__))

/// Internal invariant, checked in debug builds only.
#define SEAM_ASSERT(cond) assert(cond)

/// Always-on check of something the caller (ultimately the user) can cause.
#define SEAM_CHECK(cond, Type, ...)                                                                \
  do {                                                                                             \
    if (!(cond)) SEAM_THROW(Type, __VA_ARGS__);                                                    \
  } while (0)
