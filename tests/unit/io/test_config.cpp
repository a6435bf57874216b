// Valid inputs: every key of CONTRACT.md's input file parses to the values written, defaults
// are the documented ones, and region names keep the line and column they were written at.
#include "test_config_fixture.hpp"

#include <cmath>
#include <numbers>

namespace seam::io::testing {
namespace {

constexpr double pi = std::numbers::pi;

// Every key of the contract's example, plus the extensions (body_force, rigid_plane,
// max_step_cuts), in 3D.
constexpr std::string_view full_3d = R"yaml(title: Tied blocks with a non-matching interface
dimension: 3
mesh:
  file: blocks.msh
materials:
  rubber: {model: neo_hooke, young: 10000, poisson: 0.4, density: 100}
  steel: {model: saint_venant_kirchhoff, young: 2.1e5, poisson: 0.3, density: 7.85e-9}
  foam: {model: linear_elastic, young: 1, poisson: -0.5, density: 1}
bodies:
  - {region: block, material: rubber}
  - {region: sphere, material: steel}
  - {region: pad, material: foam}
boundary_conditions:
  - {region: bottom, type: dirichlet, components: [x, y, z], value: [0, 0, 0]}
  - {region: top, type: dirichlet, components: [z], value: ["-0.1*t"]}
  - {region: left, type: pressure, value: "2000*sin(2*_pi*t)*(t<=0.5)"}
  - {region: right, type: traction, value: [0, 0, -1]}
  - {region: block, type: body_force, value: [0, "x*y", "-9.81*z"]}
  - {region: front, type: dirichlet, components: [z, x], value: ["t*x", 2.5]}
  - {region: back, type: dirichlet, value: [1, 2, 3]}
initial_conditions:
  - {region: block, velocity: ["-0.5*y", "0.5*x", "0"]}
interfaces:
  - name: tie
    type: mesh_tying
    slave: lower_top
    master: upper_bottom
    multiplier: dual
    strategy: condensed
  - name: contact
    type: contact
    slave: sphere_surface
    master: block_top
    multiplier: dual
    friction: {model: coulomb, coefficient: 0.3}
  - name: floor
    type: contact
    slave: sphere_surface
    rigid_plane: {point: [0, 0, -1], normal: [0, 0, 2], motion: [0, "0", "0.01*t"]}
    multiplier: standard
    strategy: saddle_point
time:
  integrator: generalized_alpha
  rho_inf: 0.5
  end: 2.0
  steps: 8
  max_step_cuts: 3
solver:
  newton: {tolerance: 1.0e-8, max_iterations: 30}
  linear: iterative
output:
  every: 2
  probes: [[0, 0, 2.0], [1.2, 0, -3]]
)yaml";

TEST_F(ConfigTest, FullInputParsesEveryKey) {
  const Config config = load(full_3d);

  EXPECT_EQ(config.title, "Tied blocks with a non-matching interface");
  EXPECT_EQ(config.dimension, 3);
  EXPECT_EQ(config.plane, PlaneMode::strain);
  EXPECT_EQ(config.source, folder_ / "case.yaml");
  EXPECT_TRUE(config.source.is_absolute());
  EXPECT_EQ(config.mesh.file, folder_ / "blocks.msh");
  EXPECT_TRUE(config.mesh.geo.empty());

  ASSERT_EQ(config.materials.size(), 3u);
  const Material& rubber = config.materials.at("rubber");
  EXPECT_EQ(rubber.name, "rubber");
  EXPECT_EQ(rubber.model, MaterialModel::neo_hooke);
  EXPECT_EQ(rubber.young, 10000.0);
  EXPECT_EQ(rubber.poisson, 0.4);
  EXPECT_EQ(rubber.density, 100.0);
  const Material& steel = config.materials.at("steel");
  EXPECT_EQ(steel.model, MaterialModel::saint_venant_kirchhoff);
  EXPECT_EQ(steel.young, 2.1e5);
  EXPECT_EQ(steel.density, 7.85e-9);
  EXPECT_EQ(config.materials.at("foam").model, MaterialModel::linear_elastic);
  EXPECT_EQ(config.materials.at("foam").poisson, -0.5);

  ASSERT_EQ(config.bodies.size(), 3u);
  EXPECT_EQ(config.bodies[0].region.name, "block");
  EXPECT_EQ(config.bodies[0].material, "rubber");
  EXPECT_EQ(config.bodies[1].region.name, "sphere");
  EXPECT_EQ(config.bodies[1].material, "steel");

  const auto& bcs = config.boundary_conditions;
  ASSERT_EQ(bcs.size(), 7u);
  EXPECT_EQ(bcs[0].region.name, "bottom");
  EXPECT_EQ(bcs[0].type, BoundaryType::dirichlet);
  EXPECT_EQ(bcs[0].components, (std::vector<int>{0, 1, 2}));
  ASSERT_EQ(bcs[0].value.size(), 3u);
  for (const auto& value : bcs[0].value) {
    EXPECT_TRUE(value.is_constant());
    EXPECT_EQ(value(0.3, 1, 2, 3), 0.0);
  }
  EXPECT_EQ(bcs[1].components, (std::vector<int>{2}));
  ASSERT_EQ(bcs[1].value.size(), 1u);
  EXPECT_DOUBLE_EQ(bcs[1].value[0](0.7, 5, 5, 5), -0.07);
  EXPECT_TRUE(bcs[1].value[0].uses_time());

  EXPECT_EQ(bcs[2].type, BoundaryType::pressure);
  EXPECT_TRUE(bcs[2].components.empty());
  ASSERT_EQ(bcs[2].value.size(), 1u);
  // 2000 sin(2 pi t) while t <= 0.5, then 0.
  EXPECT_NEAR(bcs[2].value[0](0.125, 0, 0, 0), 2000.0 * std::sqrt(0.5), 1e-9);
  EXPECT_NEAR(bcs[2].value[0](0.25, 0, 0, 0), 2000.0, 1e-9);
  EXPECT_EQ(bcs[2].value[0](0.75, 0, 0, 0), 0.0);

  EXPECT_EQ(bcs[3].type, BoundaryType::traction);
  EXPECT_EQ(bcs[3].components, (std::vector<int>{0, 1, 2}));
  ASSERT_EQ(bcs[3].value.size(), 3u);
  EXPECT_EQ(bcs[3].value[2](0, 0, 0, 0), -1.0);

  EXPECT_EQ(bcs[4].type, BoundaryType::body_force);
  EXPECT_EQ(bcs[4].region.name, "block");
  ASSERT_EQ(bcs[4].value.size(), 3u);
  EXPECT_DOUBLE_EQ(bcs[4].value[1](0, 1.5, -4, 0), -6.0);
  EXPECT_DOUBLE_EQ(bcs[4].value[2](0, 0, 0, 2), -19.62);
  EXPECT_TRUE(bcs[4].value[2].uses_space());
  EXPECT_FALSE(bcs[4].value[2].uses_time());

  // Components keep the order written, values follow them.
  EXPECT_EQ(bcs[5].components, (std::vector<int>{2, 0}));
  EXPECT_DOUBLE_EQ(bcs[5].value[0](0.5, 3, 0, 0), 1.5);
  EXPECT_EQ(bcs[5].value[1](0.5, 3, 0, 0), 2.5);
  // Omitted components mean all of them.
  EXPECT_EQ(bcs[6].components, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(bcs[6].value[1](0, 0, 0, 0), 2.0);

  ASSERT_EQ(config.initial_conditions.size(), 1u);
  const auto& velocity = config.initial_conditions[0].velocity;
  ASSERT_EQ(velocity.size(), 3u);
  // Rigid rotation about z with angular velocity 0.5: v = 0.5 e_z x X at X = (2, 4, 1).
  EXPECT_DOUBLE_EQ(velocity[0](0, 2, 4, 1), -2.0);
  EXPECT_DOUBLE_EQ(velocity[1](0, 2, 4, 1), 1.0);
  EXPECT_EQ(velocity[2](0, 2, 4, 1), 0.0);

  ASSERT_EQ(config.interfaces.size(), 3u);
  const Interface& tie = config.interfaces[0];
  EXPECT_EQ(tie.name, "tie");
  EXPECT_EQ(tie.type, InterfaceType::mesh_tying);
  EXPECT_EQ(tie.slave.name, "lower_top");
  ASSERT_TRUE(tie.master.has_value());
  EXPECT_EQ(tie.master->name, "upper_bottom");
  EXPECT_FALSE(tie.rigid_plane.has_value());
  EXPECT_EQ(tie.multiplier, Multiplier::dual);
  EXPECT_EQ(tie.strategy, Strategy::condensed);
  EXPECT_EQ(tie.friction.model, FrictionModel::frictionless);

  const Interface& contact = config.interfaces[1];
  EXPECT_EQ(contact.type, InterfaceType::contact);
  EXPECT_EQ(contact.master->name, "block_top");
  EXPECT_EQ(contact.strategy, Strategy::condensed);
  EXPECT_EQ(contact.friction.model, FrictionModel::coulomb);
  EXPECT_EQ(contact.friction.coefficient, 0.3);

  const Interface& floor = config.interfaces[2];
  EXPECT_FALSE(floor.master.has_value());
  ASSERT_TRUE(floor.rigid_plane.has_value());
  EXPECT_EQ(floor.rigid_plane->point, (std::array<double, 3>{0, 0, -1}));
  EXPECT_EQ(floor.rigid_plane->normal, (std::array<double, 3>{0, 0, 1})); // normalized
  ASSERT_EQ(floor.rigid_plane->motion.size(), 3u);
  EXPECT_DOUBLE_EQ(floor.rigid_plane->motion[2](3.0, 0, 0, 0), 0.03);
  EXPECT_EQ(floor.multiplier, Multiplier::standard);
  EXPECT_EQ(floor.strategy, Strategy::saddle_point);

  EXPECT_EQ(config.time.integrator, Integrator::generalized_alpha);
  EXPECT_TRUE(config.time.is_dynamic());
  EXPECT_EQ(config.time.rho_inf, 0.5);
  EXPECT_EQ(config.time.end, 2.0);
  EXPECT_EQ(config.time.n_steps, 8);
  EXPECT_EQ(config.time.dt, 0.25);
  EXPECT_EQ(config.time.max_step_cuts, 3);
  EXPECT_EQ(config.time.time_at(0), 0.0);
  EXPECT_EQ(config.time.time_at(3), 0.75);
  EXPECT_EQ(config.time.time_at(8), 2.0);

  EXPECT_EQ(config.solver.newton.tolerance, 1e-8);
  EXPECT_EQ(config.solver.newton.max_iterations, 30);
  EXPECT_EQ(config.solver.linear, LinearSolverKind::iterative);

  EXPECT_EQ(config.output.every, 2);
  ASSERT_EQ(config.output.probes.size(), 2u);
  EXPECT_EQ(config.output.probes[0].point, (std::array<double, 3>{0, 0, 2}));
  EXPECT_EQ(config.output.probes[1].point, (std::array<double, 3>{1.2, 0, -3}));
}

// A minimal 2D input: plane stress, a .geo mesh in a subfolder, dt instead of steps, and the
// documented defaults for everything omitted.
constexpr std::string_view minimal_2d = R"yaml(dimension: 2
plane: stress
mesh: {geo: geometry/ring.geo, size: 0.05, order: 2}
materials:
  steel: {model: linear_elastic, young: 210, poisson: 0.3}
bodies:
  - {region: ring, material: steel}
boundary_conditions:
  - {region: base, type: dirichlet, components: [y], value: 0}
  - {region: rim, type: traction, value: ["cos(_pi*y)", "t"]}
interfaces:
  - name: floor
    type: contact
    slave: rim
    rigid_plane: {point: [0, -1], normal: [3, 4]}
  - name: glue
    type: mesh_tying
    slave: a
    master: b
    multiplier: standard
time:
  end: 1.0
  dt: 0.1
output:
  probes: [[0.5, 0.25]]
)yaml";

TEST_F(ConfigTest, Minimal2dInputTakesDefaults) {
  write("geometry/ring.geo", "// geometry");
  const Config config = load(minimal_2d);

  EXPECT_EQ(config.dimension, 2);
  EXPECT_EQ(config.plane, PlaneMode::stress);
  EXPECT_TRUE(config.title.empty());
  EXPECT_TRUE(config.mesh.file.empty());
  EXPECT_EQ(config.mesh.geo, folder_ / "geometry" / "ring.geo");
  ASSERT_TRUE(config.mesh.size.has_value());
  EXPECT_EQ(*config.mesh.size, 0.05);
  EXPECT_EQ(config.mesh.order, 2);
  EXPECT_EQ(config.materials.at("steel").density, 0.0);

  const auto& bcs = config.boundary_conditions;
  ASSERT_EQ(bcs.size(), 2u);
  EXPECT_EQ(bcs[0].components, (std::vector<int>{1}));
  ASSERT_EQ(bcs[0].value.size(), 1u); // a bare number for a single component
  EXPECT_EQ(bcs[1].components, (std::vector<int>{0, 1}));
  ASSERT_EQ(bcs[1].value.size(), 2u);
  EXPECT_NEAR(bcs[1].value[0](0, 0, 1.0 / 3.0, 0), 0.5, 1e-14);
  EXPECT_EQ(bcs[1].value[1](0.4, 0, 0, 0), 0.4);

  const Interface& floor = config.interfaces[0];
  ASSERT_TRUE(floor.rigid_plane.has_value());
  EXPECT_EQ(floor.rigid_plane->point, (std::array<double, 3>{0, -1, 0}));
  EXPECT_NEAR(floor.rigid_plane->normal[0], 0.6, 1e-15);
  EXPECT_NEAR(floor.rigid_plane->normal[1], 0.8, 1e-15);
  EXPECT_EQ(floor.rigid_plane->normal[2], 0.0);
  ASSERT_EQ(floor.rigid_plane->motion.size(), 2u); // at rest unless `motion` is given
  EXPECT_EQ(floor.rigid_plane->motion[1](7.0, 1, 1, 1), 0.0);
  EXPECT_EQ(floor.multiplier, Multiplier::dual);
  EXPECT_EQ(floor.strategy, Strategy::condensed);
  EXPECT_EQ(floor.friction.model, FrictionModel::frictionless);
  // A standard multiplier cannot be condensed, so its default strategy is the saddle point.
  EXPECT_EQ(config.interfaces[1].strategy, Strategy::saddle_point);

  EXPECT_EQ(config.time.integrator, Integrator::quasi_static);
  EXPECT_FALSE(config.time.is_dynamic());
  EXPECT_EQ(config.time.rho_inf, 0.8);
  EXPECT_EQ(config.time.dt, 0.1);
  EXPECT_EQ(config.time.n_steps, 10); // 1.0 / 0.1 = 9.999999999999998 is ten steps
  EXPECT_EQ(config.time.time_at(10), 1.0);
  EXPECT_EQ(config.time.max_step_cuts, 5);
  EXPECT_EQ(config.solver.newton.tolerance, 1e-10);
  EXPECT_EQ(config.solver.newton.max_iterations, 25);
  EXPECT_TRUE(config.solver.newton.line_search);
  EXPECT_EQ(config.solver.linear, LinearSolverKind::automatic);
  EXPECT_EQ(config.output.every, 1);
  ASSERT_EQ(config.output.probes.size(), 1u);
  EXPECT_EQ(config.output.probes[0].point, (std::array<double, 3>{0.5, 0.25, 0}));
}

TEST_F(ConfigTest, DtThatDoesNotDivideEndRoundsStepsUpAndEndsAtEnd) {
  const Config config = load(R"yaml(dimension: 3
mesh: {file: blocks.msh}
materials: {m: {model: linear_elastic, young: 1, poisson: 0}}
bodies: [{region: b, material: m}]
time: {end: 1.0, dt: 0.3}
)yaml");
  EXPECT_EQ(config.time.n_steps, 4); // 0.3, 0.6, 0.9, 1.0
  EXPECT_DOUBLE_EQ(config.time.time_at(3), 0.9);
  EXPECT_EQ(config.time.time_at(4), 1.0);
}

TEST_F(ConfigTest, NewtonLineSearchIsReadAsABoolean) {
  constexpr std::string_view head = R"yaml(dimension: 3
mesh: {file: blocks.msh}
materials: {m: {model: linear_elastic, young: 1, poisson: 0}}
bodies: [{region: b, material: m}]
time: {end: 1.0, steps: 1}
)yaml";
  for (const bool value : {false, true}) {
    const Config config =
        load(std::string(head) + "solver: {newton: {line_search: " + (value ? "true" : "false") +
             "}}\n");
    EXPECT_EQ(config.solver.newton.line_search, value);
    EXPECT_EQ(config.solver.newton.max_iterations, 25); // the other keys keep their defaults
  }
}

TEST_F(ConfigTest, AbsoluteMeshPathIsKept) {
  const auto mesh = write("elsewhere/far.msh", "");
  const Config config = load("dimension: 3\nmesh: {file: " + mesh.string() + R"yaml(}
materials: {m: {model: linear_elastic, young: 1, poisson: 0}}
bodies: [{region: b, material: m}]
time: {end: 1, steps: 1}
)yaml");
  EXPECT_EQ(config.mesh.file, mesh);
}

TEST_F(ConfigTest, RegionNamesKeepTheirLineAndColumn) {
  const Config config = load(full_3d);
  // Lines and columns counted by hand in full_3d (1-based).
  const Mark& bc = config.boundary_conditions[2].region.mark;
  EXPECT_EQ(bc.line, 16);
  EXPECT_EQ(bc.column, 14);
  EXPECT_EQ(bc.key_path, "boundary_conditions[2].region");
  EXPECT_EQ(bc.file, (folder_ / "case.yaml").string());

  const Mark& body = config.bodies[1].region.mark;
  EXPECT_EQ(body.line, 11);
  EXPECT_EQ(body.column, 14);
  EXPECT_EQ(body.key_path, "bodies[1].region");

  EXPECT_EQ(config.initial_conditions[0].region.mark.line, 22);
  EXPECT_EQ(config.initial_conditions[0].region.mark.key_path, "initial_conditions[0].region");

  const Interface& contact = config.interfaces[1];
  EXPECT_EQ(contact.slave.mark.line, 32);
  EXPECT_EQ(contact.slave.mark.column, 12);
  EXPECT_EQ(contact.slave.mark.key_path, "interfaces[1].slave");
  EXPECT_EQ(contact.master->mark.line, 33);
  EXPECT_EQ(contact.master->mark.key_path, "interfaces[1].master");
  EXPECT_EQ(config.output.probes[1].mark.key_path, "output.probes[1]");
}

TEST_F(ConfigTest, FailAtFormatsFileLineColumnKeyPathMessage) {
  const Mark mark{"blocks.yaml", 14, 13, "boundary_conditions[2].region"};
  try {
    fail_at(mark, "no region 'topp' in mesh blocks.msh; available: top, bottom");
    FAIL() << "fail_at returned";
  } catch (const InputError& error) {
    EXPECT_STREQ(error.what(), "blocks.yaml:14:13: boundary_conditions[2].region: no region "
                               "'topp' in mesh blocks.msh; available: top, bottom");
  }
  // A later stage reports against a parsed region the same way.
  const Config config = load(full_3d);
  try {
    fail_at(config.boundary_conditions[2].region.mark, "no region 'left'");
    FAIL() << "fail_at returned";
  } catch (const InputError& error) {
    const std::string expected = "case.yaml:16:14: boundary_conditions[2].region: no region 'left'";
    EXPECT_NE(std::string(error.what()).find(expected), std::string::npos) << error.what();
  }
}

TEST_F(ConfigTest, EnumsPrintTheInputSpelling) {
  EXPECT_EQ(to_string(Integrator::quasi_static), "static");
  EXPECT_EQ(to_string(Integrator::energy_momentum), "energy_momentum");
  EXPECT_EQ(to_string(MaterialModel::saint_venant_kirchhoff), "saint_venant_kirchhoff");
  EXPECT_EQ(to_string(BoundaryType::body_force), "body_force");
  EXPECT_EQ(to_string(Strategy::saddle_point), "saddle_point");
  EXPECT_EQ(to_string(Multiplier::standard), "standard");
  EXPECT_EQ(to_string(InterfaceType::mesh_tying), "mesh_tying");
  EXPECT_EQ(to_string(FrictionModel::coulomb), "coulomb");
  EXPECT_EQ(to_string(LinearSolverKind::iterative), "iterative");
  EXPECT_EQ(to_string(PlaneMode::stress), "stress");
}

} // namespace
} // namespace seam::io::testing
