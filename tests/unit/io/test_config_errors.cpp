// Invalid inputs: each mistake a user can make is an InputError that names the file, the
// line:column (found here by searching the fixture text), the key path and what was expected.
#include "test_config_fixture.hpp"

namespace seam::io::testing {
namespace {

TEST_F(ConfigTest, BaseFixtureIsValid) {
  EXPECT_NO_THROW(load(base));
}
TEST_F(ConfigTest, Base2dFixtureIsValid) {
  EXPECT_NO_THROW(load(base_2d));
}

TEST_F(ConfigTest, BrokenYamlReportsParserMark) {
  // An unclosed flow mapping: the parser fails at the first token that cannot continue it,
  // the ':' after 'bodies' on the next line.
  const std::string yaml = replaced(base, "density: 100}", "density: 100");
  const std::string message = error_of(yaml);
  EXPECT_TRUE(contains_all(message, {"invalid YAML", location_of(yaml, ":", "bodies")}));
}

TEST_F(ConfigTest, BrokenYamlIndentation) {
  const std::string yaml = replaced(base, "  file: blocks.msh", "  file: blocks.msh\n bad: 1");
  EXPECT_TRUE(contains_all(error_of(yaml), {"invalid YAML", "case.yaml:4:"}));
}

TEST_F(ConfigTest, UnknownKeySuggestsTheClosestAllowedKey) {
  const std::string yaml = replaced(base, "young: 10000", "yung: 10000");
  EXPECT_TRUE(contains_all(error_of(yaml), {location_of(yaml, "yung"), "materials.rubber.yung",
                                            "unknown key 'yung'", "did you mean 'young'?"}));
}

TEST_F(ConfigTest, UnknownTopLevelKeySuggestsTheClosestSection) {
  const std::string yaml = replaced(base, "boundary_conditions:", "boundary_condition:");
  EXPECT_TRUE(contains_all(error_of(yaml), {location_of(yaml, "boundary_condition:"),
                                            "did you mean 'boundary_conditions'?"}));
}

TEST_F(ConfigTest, UnknownKeyFarFromAnyKeyListsTheAllowedOnes) {
  const std::string yaml = replaced(base, "  steps: 10", "  steps: 10\n  banana: 1");
  const std::string message = error_of(yaml);
  EXPECT_TRUE(contains_all(message, {location_of(yaml, "banana"), "unknown key 'banana'",
                                     "'integrator', 'rho_inf', 'end', 'steps', 'dt'"}));
  EXPECT_EQ(message.find("did you mean"), std::string::npos) << message;
}

TEST_F(ConfigTest, WrongTypeSaysWhatWasExpected) {
  const std::string yaml = replaced(base, "young: 10000", "young: abc");
  EXPECT_TRUE(contains_all(error_of(yaml), {location_of(yaml, "abc"), "materials.rubber.young",
                                            "expected a number, got 'abc'"}));
}

TEST_F(ConfigTest, FractionalStepCountIsAWrongType) {
  const std::string yaml = replaced(base, "steps: 10", "steps: 2.5");
  EXPECT_TRUE(contains_all(
      error_of(yaml), {location_of(yaml, "2.5"), "time.steps", "expected an integer, got '2.5'"}));
}

TEST_F(ConfigTest, ListWhereAMappingBelongs) {
  const std::string yaml = replaced(base, "  file: blocks.msh", "  - blocks.msh");
  EXPECT_TRUE(contains_all(error_of(yaml), {"mesh: expected a mapping (key: value), got a list"}));
}

TEST_F(ConfigTest, MissingRequiredKeyPointsAtItsMapping) {
  const std::string yaml = replaced(base, "poisson: 0.4, ", "");
  EXPECT_TRUE(contains_all(error_of(yaml), {location_of(yaml, "{model"), "materials.rubber",
                                            "missing required key 'poisson'"}));
}

TEST_F(ConfigTest, MissingSectionIsReportedAtTheTop) {
  const std::string yaml = std::string(base.substr(0, base.find("time:"))) + "output: {every: 1}\n";
  EXPECT_TRUE(contains_all(error_of(yaml), {"case.yaml:1:1:", "missing required key 'time'"}));
}

TEST_F(ConfigTest, VectorOfWrongLengthForTheDimension) {
  const std::string yaml = replaced(base, "value: [0, 0, -1]", "value: [0, -1]");
  EXPECT_TRUE(
      contains_all(error_of(yaml), {location_of(yaml, "[0, -1]"), "boundary_conditions[1].value",
                                    "expected 3 components (dimension is 3), got 2"}));
}

TEST_F(ConfigTest, TwoDimensionalVectorsHaveTwoComponents) {
  const std::string yaml =
      replaced(base_2d, "time:", "  - {region: top, type: traction, value: [0, 0, -1]}\ntime:");
  EXPECT_TRUE(contains_all(error_of(yaml), {location_of(yaml, "[0, 0, -1]"),
                                            "expected 2 components (dimension is 2), got 3"}));
}

TEST_F(ConfigTest, DirichletValuesMatchTheListedComponents) {
  const std::string yaml = replaced(base, "components: [x, y, z], value: [0, 0, 0]",
                                    "components: [x, z], value: [0, 0, 0]");
  EXPECT_TRUE(
      contains_all(error_of(yaml), {location_of(yaml, "[0, 0, 0]"), "boundary_conditions[0].value",
                                    "expected 2 values (one per entry of 'components')"}));
}

TEST_F(ConfigTest, UnknownEnumValueListsTheAllowedOnes) {
  const std::string yaml = replaced(base, "integrator: static", "integrator: newmark");
  EXPECT_TRUE(contains_all(
      error_of(yaml), {location_of(yaml, "newmark"), "time.integrator", "unknown value 'newmark'",
                       "expected one of 'static', 'generalized_alpha', 'energy_momentum'"}));
}

TEST_F(ConfigTest, MisspelledEnumValueGetsASuggestion) {
  const std::string yaml = replaced(base, "model: neo_hooke", "model: neo_hook");
  EXPECT_TRUE(contains_all(error_of(yaml), {location_of(yaml, "neo_hook"), "materials.rubber.model",
                                            "did you mean 'neo_hooke'?"}));
}

struct BadMaterial {
  const char* from;
  const char* to;
  const char* key;
  const char* expected;
};

void PrintTo(const BadMaterial& bad, std::ostream* out) {
  *out << bad.to;
}

class NonPhysicalMaterial : public ConfigTest, public ::testing::WithParamInterface<BadMaterial> {};

TEST_P(NonPhysicalMaterial, IsRejected) {
  const BadMaterial& bad = GetParam();
  const std::string yaml = replaced(base, bad.from, bad.to);
  const std::string value = std::string(bad.to).substr(std::string(bad.to).find(' ') + 1);
  EXPECT_TRUE(contains_all(
      error_of(yaml), {location_of(yaml, value, bad.key), bad.key, bad.expected, "got " + value}));
}

INSTANTIATE_TEST_SUITE_P(
    ConfigTest, NonPhysicalMaterial,
    ::testing::Values(BadMaterial{"young: 10000", "young: 0", "young", "must be > 0"},
                      BadMaterial{"young: 10000", "young: -5", "young", "must be > 0"},
                      BadMaterial{"poisson: 0.4", "poisson: 0.5", "poisson", "-1 < poisson < 0.5"},
                      BadMaterial{"poisson: 0.4", "poisson: -1", "poisson", "-1 < poisson < 0.5"},
                      BadMaterial{"poisson: 0.4", "poisson: 0.75", "poisson", "-1 < poisson < 0.5"},
                      BadMaterial{"density: 100", "density: -1", "density", "must be >= 0"}));

struct BadTime {
  const char* from;
  const char* to;
  const char* key;
  const char* expected;
};

void PrintTo(const BadTime& bad, std::ostream* out) {
  *out << bad.to;
}

class NonPositiveTime : public ConfigTest, public ::testing::WithParamInterface<BadTime> {};

TEST_P(NonPositiveTime, IsRejected) {
  const BadTime& bad = GetParam();
  const std::string yaml = replaced(base, bad.from, bad.to);
  const std::string value = std::string(bad.to).substr(std::string(bad.to).find(' ') + 1);
  EXPECT_TRUE(contains_all(
      error_of(yaml), {location_of(yaml, value, bad.to), bad.key, bad.expected, "got " + value}));
}

INSTANTIATE_TEST_SUITE_P(
    ConfigTest, NonPositiveTime,
    ::testing::Values(BadTime{"steps: 10", "steps: 0", "time.steps", "positive integer"},
                      BadTime{"steps: 10", "steps: -3", "time.steps", "positive integer"},
                      BadTime{"steps: 10", "dt: 0", "time.dt", "must be > 0"},
                      BadTime{"steps: 10", "dt: -0.1", "time.dt", "must be > 0"},
                      BadTime{"end: 1.0", "end: 0", "time.end", "must be > 0"},
                      BadTime{"end: 1.0", "end: -2", "time.end", "must be > 0"}));

TEST_F(ConfigTest, StepsAndDtTogether) {
  const std::string yaml = replaced(base, "steps: 10", "steps: 10\n  dt: 0.1");
  EXPECT_TRUE(contains_all(
      error_of(yaml), {location_of(yaml, "0.1"), "time.dt", "either 'steps' or 'dt', not both"}));
}

TEST_F(ConfigTest, NeitherStepsNorDt) {
  const std::string yaml = replaced(base, "  steps: 10\n", "");
  EXPECT_TRUE(contains_all(error_of(yaml), {location_of(yaml, "integrator"), "time",
                                            "missing required key 'steps' (or 'dt')"}));
}

TEST_F(ConfigTest, BodyWithUnknownMaterial) {
  const std::string yaml = replaced(base, "material: rubber}", "material: rubbr}");
  EXPECT_TRUE(contains_all(error_of(yaml), {location_of(yaml, "rubbr"), "bodies[0].material",
                                            "unknown material 'rubbr'", "did you mean 'rubber'?",
                                            "defined under 'materials': 'rubber'"}));
}

TEST_F(ConfigTest, BadExpressionIsLocatedAndExplained) {
  const std::string yaml = replaced(base, "value: [0, 0, -1]", "value: [0, 0, \"sin(t\"]");
  EXPECT_TRUE(contains_all(error_of(yaml),
                           {location_of(yaml, "\"sin(t\""), "boundary_conditions[1].value[2]",
                            "cannot parse expression \"sin(t\""}));
}

TEST_F(ConfigTest, MeshFileNotFoundNamesTheResolvedPath) {
  const std::string yaml = replaced(base, "file: blocks.msh", "file: meshes/missing.msh");
  const std::string resolved = (folder_ / "meshes" / "missing.msh").string();
  EXPECT_TRUE(contains_all(error_of(yaml), {location_of(yaml, "meshes/missing.msh"), "mesh.file",
                                            "file not found: " + resolved}));
}

TEST_F(ConfigTest, CondensedStrategyNeedsDualMultiplier) {
  const std::string yaml = replaced(base, "    master: upper_bottom\n",
                                    "    master: upper_bottom\n    multiplier: standard\n"
                                    "    strategy: condensed\n");
  EXPECT_TRUE(
      contains_all(error_of(yaml), {location_of(yaml, "condensed"), "interfaces[0].strategy",
                                    "strategy 'condensed' needs multiplier 'dual'"}));
}

TEST_F(ConfigTest, ComponentListedTwice) {
  const std::string yaml = replaced(base, "components: [x, y, z], value: [0, 0, 0]",
                                    "components: [x, z, x], value: [0, 0, 0]");
  EXPECT_TRUE(
      contains_all(error_of(yaml), {location_of(yaml, "x]"), "boundary_conditions[0].components[2]",
                                    "component 'x' is listed twice"}));
}

TEST_F(ConfigTest, ComponentZIn2d) {
  const std::string yaml =
      replaced(base_2d, "components: [x, y], value: [0, 0]", "components: [x, z], value: [0, 0]");
  EXPECT_TRUE(
      contains_all(error_of(yaml), {location_of(yaml, "z]"), "boundary_conditions[0].components[1]",
                                    "component 'z' does not exist in 2D"}));
}

TEST_F(ConfigTest, ProbeWithWrongNumberOfCoordinates) {
  const std::string yaml = replaced(base, "probes: [[0, 0, 2.0]]", "probes: [[0, 0, 2.0], [1, 2]]");
  EXPECT_TRUE(contains_all(error_of(yaml), {location_of(yaml, "[1, 2]"), "output.probes[1]",
                                            "expected 3 coordinates (dimension is 3), got 2"}));
}

TEST_F(ConfigTest, DuplicateInterfaceNames) {
  const std::string yaml = replaced(base, "time:",
                                    "  - {name: tie, type: contact, slave: s, "
                                    "master: m}\ntime:");
  EXPECT_TRUE(contains_all(error_of(yaml), {location_of(yaml, "tie, type"), "interfaces[1].name",
                                            "duplicate interface name 'tie' (first at line 12)"}));
}

} // namespace
} // namespace seam::io::testing
