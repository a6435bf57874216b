// Further input checks, one table row each: the fixture edit, where the message must point
// (the first `token` at or after `after` in the edited text), and what it must say.
#include "test_config_fixture.hpp"

namespace seam::io::testing {
namespace {

struct Check {
  const char* name;
  bool two_d; // edit base_2d instead of base
  const char* from;
  const char* to;
  const char* token;
  const char* after;
  const char* key;
  const char* expected;
  const char* from2 = nullptr; // an optional second edit
  const char* to2 = nullptr;
};

void PrintTo(const Check& check, std::ostream* out) {
  *out << check.name;
}

class InputCheck : public ConfigTest, public ::testing::WithParamInterface<Check> {};

TEST_P(InputCheck, IsAnInputErrorAtTheRightPlace) {
  const Check& check = GetParam();
  std::string yaml = replaced(check.two_d ? base_2d : base, check.from, check.to);
  if (check.from2 != nullptr) yaml = replaced(yaml, check.from2, check.to2);
  EXPECT_TRUE(contains_all(
      error_of(yaml), {location_of(yaml, check.token, check.after), check.key, check.expected}));
}

constexpr const char* ig = "integrator: static";
constexpr const char* tie_master = "    master: upper_bottom\n";

INSTANTIATE_TEST_SUITE_P(
    ConfigTest, InputCheck,
    ::testing::Values(
        Check{"dimension_4", false, "dimension: 3", "dimension: 4", "4", "dimension", "dimension",
              "expected 2 or 3, got 4"},
        Check{"plane_in_3d", false, "dimension: 3", "dimension: 3\nplane: stress", "stress", "",
              "plane", "applies only to dimension 2"},
        Check{"plane_unknown", true, "dimension: 2", "dimension: 2\nplane: strian", "strian", "",
              "plane", "did you mean 'strain'?"},
        Check{"duplicate_yaml_key", false, "  steps: 10", "  steps: 10\n  steps: 3", "steps: 3", "",
              "time.steps", "key 'steps' given twice (first at line 19)"},
        Check{"mesh_file_and_geo", false, "  file: blocks.msh", "  file: blocks.msh\n  geo: b.geo",
              "b.geo", "", "mesh.geo", "either 'file'"},
        Check{"mesh_geo_under_file", false, "file: blocks.msh", "file: blocks.geo", "blocks.geo",
              "", "mesh.file", "goes under 'geo:'"},
        Check{"mesh_order_without_geo", false, "  file: blocks.msh",
              "  file: blocks.msh\n  order: 2", "2", "order", "mesh.order",
              "applies only to a 'geo' geometry"},
        Check{"no_materials", false,
              "  rubber: {model: neo_hooke, young: 10000, poisson: 0.4, "
              "density: 100}\n",
              "", "materials", "", "materials", "expected at least one material"},
        Check{"duplicate_body_region", false, "  - {region: block, material: rubber}\n",
              "  - {region: block, material: rubber}\n  - {region: block, material: rubber}\n",
              "block", "rubber}\n  - {region: ", "bodies[1].region",
              "region 'block' is already a body (line 7)"},
        Check{"bc_type_unknown", false, "type: traction", "type: tractoin", "tractoin", "",
              "boundary_conditions[1].type", "did you mean 'traction'?"},
        Check{"bc_components_on_traction", false, "type: traction,",
              "type: traction, components: [x],", "[x]", "traction",
              "boundary_conditions[1].components", "applies only to type 'dirichlet'"},
        Check{"bc_pressure_with_list", false, "type: traction", "type: pressure", "[0, 0, -1]", "",
              "boundary_conditions[1].value", "a pressure is a scalar"},
        Check{"bc_missing_value", false, ", value: [0, 0, -1]", "", "{region: right", "",
              "boundary_conditions[1]", "missing required key 'value'"},
        Check{"bc_value_null", false, "value: [0, 0, -1]", "value: [0, ~, -1]", "~", "", "value[1]",
              "expected a number or an expression, got nothing"},
        Check{"bc_value_multiple_results", false, "value: [0, 0, -1]", "value: [0, \"1, t\", -1]",
              "\"1, t\"", "", "boundary_conditions[1].value[1]", "one scalar"},
        Check{"bc_components_empty", false, "components: [x, y, z], value: [0, 0, 0]",
              "components: [], value: []", "[]", "", "boundary_conditions[0].components",
              "expected at least one of 'x', 'y', 'z'"},
        Check{"initial_conditions_in_statics", false,
              "time:", "initial_conditions:\n  - {region: block, velocity: [1, 0, 0]}\ntime:", "-",
              "initial", "initial_conditions", "apply only to dynamics"},
        Check{"density_zero_in_dynamics", true, "time: {", "time: {integrator: energy_momentum, ",
              "{model", "", "materials.steel",
              "density must be > 0 for time.integrator 'energy_momentum'"},
        Check{"rho_inf_with_static", false, ig, "integrator: static\n  rho_inf: 0.5", "0.5", "rho",
              "time.rho_inf", "applies only to integrator 'generalized_alpha'"},
        Check{"rho_inf_out_of_range", false, ig, "integrator: generalized_alpha\n  rho_inf: 1.5",
              "1.5", "", "time.rho_inf", "must be in [0, 1], got 1.5"},
        Check{"max_step_cuts_negative", false, "  steps: 10", "  steps: 10\n  max_step_cuts: -1",
              "-1", "cuts", "time.max_step_cuts", "must be >= 0"},
        Check{"newton_tolerance_zero", false,
              "output:", "solver: {newton: {tolerance: 0}}\noutput:", "0}", "tolerance",
              "solver.newton.tolerance", "must be > 0"},
        Check{"newton_iterations_zero", false,
              "output:", "solver: {newton: {max_iterations: 0}}\noutput:", "0}", "max_iterations",
              "solver.newton.max_iterations", "must be >= 1"},
        Check{"newton_line_search_not_boolean", false,
              "output:", "solver: {newton: {line_search: yes}}\noutput:", "yes", "line_search",
              "solver.newton.line_search", "expected true or false, got 'yes'"},
        Check{"newton_line_search_list", false,
              "output:", "solver: {newton: {line_search: [true]}}\noutput:", "[true]",
              "line_search", "solver.newton.line_search", "expected true or false, got a list"},
        Check{"newton_line_search_unknown_key", false,
              "output:", "solver: {newton: {linesearch: false}}\noutput:", "linesearch", "",
              "solver.newton.linesearch", "did you mean 'line_search'?"},
        Check{"linear_unknown", false, "output:", "solver: {linear: mumps}\noutput:", "mumps", "",
              "solver.linear", "expected one of 'direct', 'iterative', 'auto'"},
        Check{"output_every_zero", false, "probes:", "every: 0\n  probes:", "0", "every",
              "output.every", "must be >= 1"},
        Check{"interface_type_unknown", false, "type: mesh_tying", "type: tying", "tying", "",
              "interfaces[0].type", "expected one of 'mesh_tying', 'contact', 'fsi'"},
        Check{"fsi_with_slave", false, "type: mesh_tying", "type: fsi", "lower_top", "type: fsi",
              "interfaces[0].slave", "names its sides 'fluid' and 'structure'"},
        Check{"fsi_without_structure", false, "type: mesh_tying\n    slave: lower_top\n",
              "type: fsi\n    fluid: lower_top\n", "name", "", "interfaces[0]",
              "missing required key 'structure'", tie_master, ""},
        Check{"fsi_same_groups", false, "type: mesh_tying\n    slave: lower_top\n",
              "type: fsi\n    fluid: lower_top\n", "lower_top",
              "structure:", "interfaces[0].structure", "two different groups", tie_master,
              "    structure: lower_top\n"},
        Check{"fluid_on_mesh_tying", false, tie_master, "    master: upper_bottom\n    fluid: a\n",
              "a", "fluid:", "interfaces[0].fluid", "applies only to type 'fsi'"},
        Check{"interface_bad_name", false, "name: tie", "name: my tie", "my tie", "",
              "interfaces[0].name", "letters, digits"},
        Check{"interface_without_master", false, tie_master, "", "name", "", "interfaces[0]",
              "missing required key 'master'"},
        Check{"tying_same_region", false, "master: upper_bottom", "master: lower_top", "lower_top",
              "master", "interfaces[0].master", "two different regions"},
        Check{"tying_rigid_plane", false, tie_master,
              "    rigid_plane: {point: [0, 0, 0], normal: [0, 0, 1]}\n", "{point", "",
              "interfaces[0].rigid_plane", "applies only to type 'contact'"},
        Check{"contact_master_and_plane", false,
              "type: mesh_tying\n    slave: lower_top\n"
              "    master: upper_bottom\n",
              "type: contact\n    slave: lower_top\n    master: upper_bottom\n"
              "    rigid_plane: {point: [0, 0, 0], normal: [0, 0, 1]}\n",
              "{point", "", "interfaces[0].rigid_plane", "either 'master' or 'rigid_plane'"},
        Check{"contact_plane_zero_normal", false,
              "type: mesh_tying\n    slave: lower_top\n"
              "    master: upper_bottom\n",
              "type: contact\n    slave: lower_top\n"
              "    rigid_plane: {point: [0, 0, 0], normal: [0, 0, 0]}\n",
              "[0, 0, 0]}", "normal", "interfaces[0].rigid_plane.normal", "zero vector"},
        Check{"contact_plane_point_2_coords", false,
              "type: mesh_tying\n    slave: lower_top\n"
              "    master: upper_bottom\n",
              "type: contact\n    slave: lower_top\n"
              "    rigid_plane: {point: [0, 0], normal: [0, 0, 1]}\n",
              "[0, 0]", "", "interfaces[0].rigid_plane.point",
              "expected 3 coordinates (dimension is 3), got 2"},
        Check{"friction_on_tying", false, tie_master,
              "    master: upper_bottom\n    friction: {model: coulomb, coefficient: 0.1}\n",
              "{model", "friction", "interfaces[0].friction", "applies only to type 'contact'"},
        Check{"friction_negative", false,
              "type: mesh_tying\n    slave: lower_top\n"
              "    master: upper_bottom\n",
              "type: contact\n    slave: lower_top\n    master: upper_bottom\n"
              "    friction: {model: coulomb, coefficient: -0.1}\n",
              "-0.1", "", "interfaces[0].friction.coefficient", "must be >= 0"},
        Check{"friction_missing_coefficient", false,
              "type: mesh_tying\n    slave: lower_top\n"
              "    master: upper_bottom\n",
              "type: contact\n    slave: lower_top\n    master: upper_bottom\n"
              "    friction: {model: coulomb}\n",
              "{model", "friction", "interfaces[0].friction", "missing required key 'coefficient'"},
        Check{"velocity_2_components_in_3d", false, "time:",
              "initial_conditions:\n  - {region: block, velocity: [1, 0]}\ntime:", "[1, 0]", "",
              "initial_conditions[0].velocity", "expected 3 components", ig,
              "integrator: generalized_alpha"},
        Check{"probe_3_coords_in_2d", true,
              "time:", "output: {probes: [[0, 1, 2]]}\ntime:", "[0, 1, 2]", "", "output.probes[0]",
              "expected 2 coordinates (dimension is 2), got 3"},
        Check{"region_not_a_name", false, "region: right", "region: [right]", "[right]", "",
              "boundary_conditions[1].region", "expected a name, got a list"}),
    [](const ::testing::TestParamInfo<Check>& info) { return std::string(info.param.name); });

TEST_F(ConfigTest, EmptyInputFile) {
  const std::string message = error_of("");
  EXPECT_TRUE(contains_all(message, {"case.yaml", "the input file is empty"}));
}

TEST_F(ConfigTest, MissingInputFileNamesTheAbsolutePath) {
  const auto path = folder_ / "nowhere.yaml";
  try {
    load_config(path);
    FAIL() << "loaded a missing file";
  } catch (const InputError& error) {
    EXPECT_TRUE(contains_all(error.what(), {"input file not found", path.string()}));
  }
}

} // namespace
} // namespace seam::io::testing
