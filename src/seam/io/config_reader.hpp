#pragma once
// Internal to the input reader: a YAML node that knows where it is (file, line, column, key
// path), typed accessors that fail with a located message, and a mapping reader that
// rejects keys it does not know. A new input key is one more name in a Map's key list and
// one more get()/required() call.
#include "seam/common/error.hpp"
#include "seam/io/config.hpp"

#include <yaml-cpp/yaml.h>

#include <array>
#include <cstddef>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace seam::io::detail {

using seam::detail::concat;

/// Levenshtein distance (insert, delete, substitute, each cost 1).
std::size_t edit_distance(std::string_view a, std::string_view b);
/// " (did you mean 'X'?)" for the closest candidate if it is close enough, else "".
std::string did_you_mean(std::string_view word, std::span<const std::string_view> candidates);
/// "'a', 'b', 'c'"
std::string quoted_list(std::span<const std::string_view> words);
/// Shortest text that reads back as the same double ("got 0.5", never a rounded 0.4999999).
std::string format_number(double value);

class Node {
public:
  Node(YAML::Node yaml, std::string file, std::string path);
  /// A node reported at `at` instead of its own mark: an absent value (`key:` alone) has
  /// no position of its own, so it is reported at its key.
  Node(YAML::Node yaml, std::string file, std::string path, YAML::Mark at);

  [[nodiscard]] const YAML::Node& yaml() const { return yaml_; }
  [[nodiscard]] const std::string& path() const { return path_; }
  [[nodiscard]] const std::string& file() const { return file_; }
  [[nodiscard]] Mark mark() const;
  [[noreturn]] void fail(std::string_view message) const;

  /// What the user wrote, for "expected X, got Y": "'abc'", "a list", "a mapping", "nothing".
  [[nodiscard]] std::string describe() const;

  [[nodiscard]] std::string string() const;
  [[nodiscard]] double number() const;
  [[nodiscard]] int integer() const;
  /// `true` or `false`.
  [[nodiscard]] bool boolean() const;
  [[nodiscard]] Expression expression() const;
  /// Items of a sequence, with paths "path[i]".
  [[nodiscard]] std::vector<Node> sequence() const;
  /// A sequence of exactly `length` items; `what` names them in the message.
  [[nodiscard]] std::vector<Node> sequence(std::size_t length, std::string_view what) const;
  /// A point or direction: `dimension` numbers, padded with zeros to three.
  [[nodiscard]] std::array<double, 3> point(int dimension) const;
  /// `dimension` expressions (a vector-valued function of t, x, y, z).
  [[nodiscard]] std::vector<Expression> expressions(int dimension) const;

  /// One of `names` (the input's spelling); unknown values list the allowed ones.
  template <class Enum, std::size_t N>
  [[nodiscard]] Enum choice(const std::array<std::pair<std::string_view, Enum>, N>& names) const {
    const std::string word = string();
    std::array<std::string_view, N> allowed{};
    for (std::size_t i = 0; i < N; ++i) {
      if (names[i].first == word) return names[i].second;
      allowed[i] = names[i].first;
    }
    fail_unknown_value(word, allowed);
  }

private:
  [[noreturn]] void fail_unknown_value(std::string_view word,
                                       std::span<const std::string_view> allowed) const;

  YAML::Node yaml_;
  std::string file_;
  std::string path_;
  std::optional<YAML::Mark> at_;
};

/// A YAML mapping whose keys must all be among `allowed`. Duplicate keys are rejected too
/// (yaml-cpp keeps both silently). An absent value (`solver:` alone) reads as empty.
class Map {
public:
  Map(const Node& node, std::initializer_list<std::string_view> allowed);
  /// A mapping with keys chosen by the user (e.g. material names).
  explicit Map(const Node& node);

  [[nodiscard]] const std::vector<std::pair<std::string, Node>>& entries() const {
    return entries_;
  }

  [[nodiscard]] const Node& node() const { return node_; }
  [[nodiscard]] bool has(std::string_view key) const;
  [[nodiscard]] std::optional<Node> get(std::string_view key) const;
  [[nodiscard]] Node required(std::string_view key) const;
  /// Fails at `key` unless the condition holds: for keys that only some variants accept.
  void forbid(std::string_view key, bool forbidden, std::string_view reason) const;

private:
  void read(std::span<const std::string_view> allowed, bool any_key);

  Node node_;
  std::vector<std::pair<std::string, Node>> entries_;
};

/// The input's spelling of every enumerator, in one place for parsing and printing.
inline constexpr std::array<std::pair<std::string_view, PlaneMode>, 2> plane_names{
    {{"strain", PlaneMode::strain}, {"stress", PlaneMode::stress}}};
inline constexpr std::array<std::pair<std::string_view, MaterialModel>, 4> material_names{
    {{"linear_elastic", MaterialModel::linear_elastic},
     {"saint_venant_kirchhoff", MaterialModel::saint_venant_kirchhoff},
     {"neo_hooke", MaterialModel::neo_hooke},
     {"newtonian_fluid", MaterialModel::newtonian_fluid}}};
inline constexpr std::array<std::pair<std::string_view, BoundaryType>, 6> boundary_names{
    {{"dirichlet", BoundaryType::dirichlet},
     {"pressure", BoundaryType::pressure},
     {"traction", BoundaryType::traction},
     {"body_force", BoundaryType::body_force},
     {"velocity", BoundaryType::velocity},
     {"mesh_displacement", BoundaryType::mesh_displacement}}};
inline constexpr std::array<std::pair<std::string_view, MeshMotionModel>, 2> mesh_motion_names{
    {{"pseudo_elastic", MeshMotionModel::pseudo_elastic},
     {"prescribed", MeshMotionModel::prescribed}}};
inline constexpr std::array<std::pair<std::string_view, Stiffening>, 2> stiffening_names{
    {{"jacobian", Stiffening::jacobian}, {"none", Stiffening::none}}};
inline constexpr std::array<std::pair<std::string_view, InterfaceType>, 3> interface_names{
    {{"mesh_tying", InterfaceType::mesh_tying},
     {"contact", InterfaceType::contact},
     {"fsi", InterfaceType::fsi}}};
inline constexpr std::array<std::pair<std::string_view, Multiplier>, 2> multiplier_names{
    {{"dual", Multiplier::dual}, {"standard", Multiplier::standard}}};
inline constexpr std::array<std::pair<std::string_view, Strategy>, 2> strategy_names{
    {{"condensed", Strategy::condensed}, {"saddle_point", Strategy::saddle_point}}};
inline constexpr std::array<std::pair<std::string_view, FrictionModel>, 3> friction_names{
    {{"frictionless", FrictionModel::frictionless},
     {"coulomb", FrictionModel::coulomb},
     {"tresca", FrictionModel::tresca}}};
inline constexpr std::array<std::pair<std::string_view, Integrator>, 3> integrator_names{
    {{"static", Integrator::quasi_static},
     {"generalized_alpha", Integrator::generalized_alpha},
     {"energy_momentum", Integrator::energy_momentum}}};
inline constexpr std::array<std::pair<std::string_view, LinearSolverKind>, 3> linear_names{
    {{"direct", LinearSolverKind::direct},
     {"iterative", LinearSolverKind::iterative},
     {"auto", LinearSolverKind::automatic}}};
inline constexpr std::array<std::pair<std::string_view, InitialGuess>, 2> initial_guess_names{
    {{"extrapolated", InitialGuess::extrapolated}, {"previous", InitialGuess::previous}}};
inline constexpr std::array<std::pair<std::string_view, InterfaceDistribution>, 2>
    distribution_names{{{"independent", InterfaceDistribution::independent},
                        {"bulk", InterfaceDistribution::bulk}}};
inline constexpr std::array<std::pair<std::string_view, WorkMeasure>, 2> work_names{
    {{"time", WorkMeasure::time}, {"integration_cells", WorkMeasure::integration_cells}}};

/// Sections read in config_conditions.cpp (they need the dimension and the time settings).
std::vector<BoundaryCondition> read_boundary_conditions(const Node& node, int dimension);
std::vector<InitialCondition> read_initial_conditions(const Node& node, int dimension);
std::vector<Interface> read_interfaces(const Node& node, int dimension);

} // namespace seam::io::detail
