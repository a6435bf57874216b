#pragma once
// Shared by the input-file tests: each test writes its YAML into its own temporary folder
// next to an empty mesh file (load_config only checks that the mesh exists).
#include "seam/common/error.hpp"
#include "seam/io/config.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>
#include <string_view>
#include <unistd.h>

namespace seam::io::testing {

class ConfigTest : public ::testing::Test {
protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "_" + info->name();
    for (char& c : name)
      if (c == '/') c = '_';
    folder_ = std::filesystem::temp_directory_path() /
              ("seam_config_" + std::to_string(::getpid()) + "_" + name);
    std::filesystem::remove_all(folder_);
    std::filesystem::create_directories(folder_);
    write("blocks.msh", "");
  }
  void TearDown() override { std::filesystem::remove_all(folder_); }

  std::filesystem::path write(const std::string& name, std::string_view text) const {
    const auto path = folder_ / name;
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path) << text;
    return path;
  }

  Config load(std::string_view yaml) const { return load_config(write("case.yaml", yaml)); }

  /// The message of the InputError that loading `yaml` must throw ("" and a test failure if
  /// it loads or throws something else).
  std::string error_of(std::string_view yaml) const {
    try {
      load(yaml);
    } catch (const InputError& error) {
      return error.what();
    } catch (const std::exception& error) {
      ADD_FAILURE() << "expected InputError, got: " << error.what();
      return {};
    }
    ADD_FAILURE() << "expected InputError, but the input loaded";
    return {};
  }

  /// "case.yaml:LINE:COL:" of the first occurrence of `token` in `text` at or after the
  /// first occurrence of `after`: where the message should point, found by plain search.
  static std::string location_of(std::string_view text, std::string_view token,
                                 std::string_view after = {}) {
    const std::size_t start = after.empty() ? 0 : text.find(after);
    const std::size_t at = text.find(token, start == std::string_view::npos ? 0 : start);
    EXPECT_NE(at, std::string_view::npos) << "fixture has no '" << token << "'";
    const std::size_t line_start = text.rfind('\n', at);
    const std::size_t column = line_start == std::string_view::npos ? at + 1 : at - line_start;
    std::size_t line = 1;
    for (std::size_t i = 0; i < at; ++i) line += text[i] == '\n' ? 1 : 0;
    return "case.yaml:" + std::to_string(line) + ":" + std::to_string(column) + ":";
  }

  std::filesystem::path folder_;
};

// A valid 3D input; each test changes one thing in it.
inline constexpr std::string_view base = R"yaml(dimension: 3
mesh:
  file: blocks.msh
materials:
  rubber: {model: neo_hooke, young: 10000, poisson: 0.4, density: 100}
bodies:
  - {region: block, material: rubber}
boundary_conditions:
  - {region: bottom, type: dirichlet, components: [x, y, z], value: [0, 0, 0]}
  - {region: right, type: traction, value: [0, 0, -1]}
interfaces:
  - name: tie
    type: mesh_tying
    slave: lower_top
    master: upper_bottom
time:
  integrator: static
  end: 1.0
  steps: 10
output:
  probes: [[0, 0, 2.0]]
)yaml";

inline constexpr std::string_view base_2d = R"yaml(dimension: 2
mesh: {file: blocks.msh}
materials: {steel: {model: linear_elastic, young: 210, poisson: 0.3}}
bodies: [{region: plate, material: steel}]
boundary_conditions:
  - {region: left, type: dirichlet, components: [x, y], value: [0, 0]}
time: {end: 1, steps: 2}
)yaml";

inline std::string replaced(std::string_view text, std::string_view from, std::string_view to) {
  std::string result(text);
  const std::size_t at = result.find(from);
  EXPECT_NE(at, std::string::npos) << "fixture has no '" << from << "'";
  if (at != std::string::npos) result.replace(at, from.size(), to);
  return result;
}

inline ::testing::AssertionResult contains_all(const std::string& message,
                                               std::initializer_list<std::string> parts) {
  for (const std::string& part : parts) {
    if (message.find(part) == std::string::npos)
      return ::testing::AssertionFailure() << "message\n  " << message << "\nlacks\n  " << part;
  }
  return ::testing::AssertionSuccess();
}

} // namespace seam::io::testing
