// The sections of the input that name mesh regions: boundary conditions, initial conditions
// and interfaces. Each keeps the Mark of its region names for the stage that has the mesh.
#include "seam/common/error.hpp"
#include "seam/io/config_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace seam::io::detail {

namespace {

constexpr std::array<std::pair<std::string_view, int>, 3> component_names{
    {{"x", 0}, {"y", 1}, {"z", 2}}};

RegionRef region_of(const Node& node) {
  const std::string name = node.string();
  if (name.empty()) node.fail("expected a region name (a Gmsh physical group), got ''");
  return RegionRef{name, node.mark()};
}

std::vector<int> read_components(const Node& node, int dimension) {
  const auto items = node.sequence();
  if (items.empty())
    node.fail("expected at least one of 'x', 'y'" + std::string(dimension == 3 ? ", 'z'" : ""));
  std::vector<int> components;
  for (const Node& item : items) {
    const int component = item.choice(component_names);
    if (component >= dimension)
      item.fail(concat("component 'z' does not exist in 2D; expected 'x' or 'y'"));
    for (const int seen : components) {
      if (seen == component)
        item.fail(concat("component '", component_names[component].first, "' is listed twice"));
    }
    components.push_back(component);
  }
  return components;
}

BoundaryCondition read_boundary_condition(const Node& node, int dimension) {
  const Map map(node, {"region", "type", "components", "value"});
  BoundaryCondition condition;
  condition.mark = node.mark();
  condition.region = region_of(map.required("region"));
  condition.type = map.required("type").choice(boundary_names);
  map.forbid("components",
             condition.type != BoundaryType::dirichlet && condition.type != BoundaryType::velocity,
             "applies only to type 'dirichlet' (and 'velocity' for a fluid)");
  const Node value = map.required("value");
  switch (condition.type) {
  case BoundaryType::dirichlet:
  case BoundaryType::velocity: {
    const auto listed = map.get("components");
    if (listed) {
      condition.components = read_components(*listed, dimension);
    } else {
      for (int i = 0; i < dimension; ++i) condition.components.push_back(i);
    }
    const std::size_t n = condition.components.size();
    if (n == 1 && value.yaml().IsScalar()) {
      condition.value.push_back(value.expression());
    } else {
      const std::string what =
          listed ? concat("values (one per entry of 'components')")
                 : concat("values (all components, dimension is ", dimension, ")");
      for (const Node& item : value.sequence(n, what)) condition.value.push_back(item.expression());
    }
    break;
  }
  case BoundaryType::pressure:
    if (!value.yaml().IsScalar())
      value.fail(concat("expected one number or expression (a pressure is a scalar), got ",
                        value.describe()));
    condition.value.push_back(value.expression());
    break;
  case BoundaryType::traction:
  case BoundaryType::body_force:
  case BoundaryType::mesh_displacement:
    for (int i = 0; i < dimension; ++i) condition.components.push_back(i);
    condition.value = value.expressions(dimension);
    break;
  }
  return condition;
}

RigidPlane read_rigid_plane(const Node& node, int dimension) {
  const Map map(node, {"point", "normal", "motion"});
  RigidPlane plane;
  plane.mark = node.mark();
  plane.point = map.required("point").point(dimension);
  const Node normal = map.required("normal");
  plane.normal = normal.point(dimension);
  const double length = std::hypot(plane.normal[0], plane.normal[1], plane.normal[2]);
  if (!(length > 0.0)) normal.fail("the normal must not be the zero vector");
  for (double& component : plane.normal) component /= length;
  if (const auto motion = map.get("motion")) {
    plane.motion = motion->expressions(dimension);
  } else {
    plane.motion.assign(static_cast<std::size_t>(dimension), Expression(0.0));
  }
  return plane;
}

// rigid_sphere: {center, radius, motion}; rigid_cylinder: {point, axis, radius, motion} (3D).
RigidObstacle read_rigid_obstacle(const Node& node, bool cylinder, int dimension) {
  const Map map(node, {"center", "point", "axis", "radius", "motion"});
  map.forbid("center", cylinder,
             "applies only to rigid_sphere (a cylinder has 'point' and 'axis')");
  map.forbid("point", !cylinder, "applies only to rigid_cylinder (a sphere has 'center')");
  map.forbid("axis", !cylinder, "applies only to rigid_cylinder");
  RigidObstacle obstacle;
  obstacle.mark = node.mark();
  obstacle.cylinder = cylinder;
  if (cylinder && dimension != 3)
    node.fail("rigid_cylinder needs dimension 3 (in 2D a rigid_sphere is a circle)");
  obstacle.point = map.required(cylinder ? "point" : "center").point(dimension);
  if (cylinder) {
    const Node axis = map.required("axis");
    obstacle.axis = axis.point(dimension);
    const double length = std::hypot(obstacle.axis[0], obstacle.axis[1], obstacle.axis[2]);
    if (!(length > 0.0)) axis.fail("the axis must not be the zero vector");
    for (double& component : obstacle.axis) component /= length;
  }
  const Node radius = map.required("radius");
  obstacle.radius = radius.number();
  if (!(obstacle.radius > 0.0))
    radius.fail(concat("the radius must be > 0, got ", format_number(obstacle.radius)));
  if (const auto motion = map.get("motion")) {
    obstacle.motion = motion->expressions(dimension);
  } else {
    obstacle.motion.assign(static_cast<std::size_t>(dimension), Expression(0.0));
  }
  return obstacle;
}

Friction read_friction(const Node& node) {
  const Map map(node, {"model", "coefficient", "bound"});
  Friction friction;
  friction.model = map.required("model").choice(friction_names);
  map.forbid("coefficient", friction.model != FrictionModel::coulomb,
             "applies only to model 'coulomb'");
  map.forbid("bound", friction.model != FrictionModel::tresca, "applies only to model 'tresca'");
  const auto non_negative = [](const Node& value, double& to) {
    to = value.number();
    if (!(to >= 0.0)) value.fail(concat("must be >= 0, got ", format_number(to)));
  };
  if (friction.model == FrictionModel::coulomb)
    non_negative(map.required("coefficient"), friction.coefficient);
  if (friction.model == FrictionModel::tresca) non_negative(map.required("bound"), friction.bound);
  return friction;
}

// Interface names become parts of output file names (interface_<name>.csv).
void check_name(const Node& node, const std::string& name) {
  const bool valid = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
  });
  if (!valid)
    node.fail(concat("expected a name of letters, digits, '_', '-' or '.', got '", name, "'"));
}

// `surface: [groups...]`: one or more distinct boundary groups.
std::vector<RegionRef> read_surface(const Node& node) {
  std::vector<RegionRef> groups;
  for (const Node& item : node.sequence()) {
    groups.push_back(region_of(item));
    for (std::size_t i = 0; i + 1 < groups.size(); ++i)
      if (groups[i].name == groups.back().name)
        item.fail(concat("group '", groups.back().name, "' is listed twice"));
  }
  if (groups.empty()) node.fail("expected a list of one or more boundary groups");
  return groups;
}

Interface read_interface(const Node& node, int dimension, std::span<const Interface> previous) {
  const Map map(node, {"name", "type", "slave", "master", "rigid_plane", "rigid_sphere",
                       "rigid_cylinder", "surface", "multiplier", "strategy", "friction", "c_n",
                       "c_t", "fluid", "structure"});
  Interface interface;
  interface.mark = node.mark();
  const Node name = map.required("name");
  interface.name = name.string();
  check_name(name, interface.name);
  for (const Interface& other : previous) {
    if (other.name == interface.name)
      name.fail(concat("duplicate interface name '", interface.name, "' (first at line ",
                       other.mark.line, ")"));
  }
  interface.type = map.required("type").choice(interface_names);
  const bool contact = interface.type == InterfaceType::contact;
  const bool fsi = interface.type == InterfaceType::fsi;
  map.forbid("fluid", !fsi, "applies only to type 'fsi'");
  map.forbid("structure", !fsi, "applies only to type 'fsi'");
  if (fsi) {
    // The fluid side carries the multiplier (slave), the structure is the master (4C's fluid
    // split; docs/fsi.md).
    for (const char* key : {"slave", "master", "surface"})
      map.forbid(key, true,
                 "does not apply to type 'fsi': an 'fsi' interface names its sides 'fluid' "
                 "and 'structure'");
    for (const char* key :
         {"rigid_plane", "rigid_sphere", "rigid_cylinder", "friction", "c_n", "c_t"})
      map.forbid(key, true, "applies only to type 'contact'");
    interface.slave = region_of(map.required("fluid"));
    interface.master = region_of(map.required("structure"));
    if (interface.master->name == interface.slave.name)
      map.required("structure")
          .fail(concat("the fluid and the structure side need two different groups; 'fluid' is "
                       "also '",
                       interface.slave.name, "'"));
    if (const auto multiplier = map.get("multiplier")) {
      interface.multiplier = multiplier->choice(multiplier_names);
      if (interface.multiplier != Multiplier::dual)
        multiplier->fail("an 'fsi' interface is condensed with dual multipliers; give "
                         "'multiplier: dual' or leave it out");
    }
    map.forbid("strategy",
               map.has("strategy") &&
                   map.required("strategy").choice(strategy_names) != Strategy::condensed,
               "an 'fsi' interface is condensed ('strategy: condensed')");
    return interface;
  }
  const auto master = map.get("master");
  const auto rigid_plane = map.get("rigid_plane");
  if (const auto surface = map.get("surface")) {
    map.forbid("surface", !contact, "applies only to type 'contact'");
    for (const char* key : {"slave", "master", "rigid_plane", "rigid_sphere", "rigid_cylinder"})
      map.forbid(key, true,
                 "cannot be combined with 'surface' (whose slave and master facets are assigned "
                 "at every search)");
    interface.surface = read_surface(*surface);
    interface.slave = interface.surface.front();
  } else {
    if (contact && !map.has("slave")) node.fail("missing required key 'slave' (or 'surface')");
    interface.slave = region_of(map.required("slave"));
  }
  map.forbid("rigid_plane", !contact, "applies only to type 'contact'");
  if (master && rigid_plane) rigid_plane->fail("give either 'master' or 'rigid_plane', not both");
  // The round obstacles: one master side of any kind per interface.
  for (const char* key : {"rigid_sphere", "rigid_cylinder"}) {
    const auto obstacle = map.get(key);
    if (!obstacle) continue;
    map.forbid(key, !contact, "applies only to type 'contact'");
    if (master || rigid_plane || interface.rigid_obstacle || !interface.surface.empty())
      obstacle->fail(concat("give only one of 'master', 'rigid_plane', 'rigid_sphere', "
                            "'rigid_cylinder' and 'surface'; '",
                            key, "' comes with another"));
    interface.rigid_obstacle =
        read_rigid_obstacle(*obstacle, std::string_view(key) == "rigid_cylinder", dimension);
  }
  if (!master && !rigid_plane && !interface.rigid_obstacle && interface.surface.empty()) {
    node.fail(contact ? "missing required key 'master' (or 'rigid_plane', 'rigid_sphere', "
                        "'rigid_cylinder')"
                      : "missing required key 'master'");
  }
  if (master) {
    interface.master = region_of(*master);
    if (!contact && interface.master->name == interface.slave.name)
      master->fail(concat("a mesh tying interface needs two different regions; slave is also '",
                          interface.slave.name, "'"));
  } else if (rigid_plane) {
    interface.rigid_plane = read_rigid_plane(*rigid_plane, dimension);
  }

  if (const auto multiplier = map.get("multiplier"))
    interface.multiplier = multiplier->choice(multiplier_names);
  interface.strategy =
      interface.multiplier == Multiplier::dual ? Strategy::condensed : Strategy::saddle_point;
  if (const auto strategy = map.get("strategy")) {
    interface.strategy = strategy->choice(strategy_names);
    // Condensation inverts the slave mortar matrix D, which only the dual basis keeps
    // diagonal (Wohlmuth 2000; Popp et al. 2010, sec. 3).
    if (interface.strategy == Strategy::condensed && interface.multiplier == Multiplier::standard)
      strategy->fail("strategy 'condensed' needs multiplier 'dual'; with multiplier 'standard' "
                     "use strategy 'saddle_point'");
  }

  map.forbid("friction", !contact, "applies only to type 'contact'");
  if (const auto friction = map.get("friction")) interface.friction = read_friction(*friction);
  const auto c_n = map.get("c_n");
  map.forbid("c_n", !contact, "applies only to type 'contact'");
  if (c_n) {
    interface.c_n = c_n->number();
    if (!(*interface.c_n > 0.0))
      c_n->fail(concat("must be > 0, got ", format_number(*interface.c_n)));
  }
  if (const auto c_t = map.get("c_t")) {
    if (interface.friction.model == FrictionModel::frictionless)
      c_t->fail("applies only to a contact interface with friction");
    interface.c_t = c_t->number();
    if (!(*interface.c_t > 0.0))
      c_t->fail(concat("must be > 0, got ", format_number(*interface.c_t)));
  }
  return interface;
}

} // namespace

std::vector<BoundaryCondition> read_boundary_conditions(const Node& node, int dimension) {
  std::vector<BoundaryCondition> conditions;
  if (node.yaml().IsNull()) return conditions;
  for (const Node& item : node.sequence())
    conditions.push_back(read_boundary_condition(item, dimension));
  return conditions;
}

std::vector<InitialCondition> read_initial_conditions(const Node& node, int dimension) {
  std::vector<InitialCondition> conditions;
  if (node.yaml().IsNull()) return conditions;
  for (const Node& item : node.sequence()) {
    const Map map(item, {"region", "velocity"});
    InitialCondition condition;
    condition.mark = item.mark();
    condition.region = region_of(map.required("region"));
    condition.velocity = map.required("velocity").expressions(dimension);
    conditions.push_back(std::move(condition));
  }
  return conditions;
}

std::vector<Interface> read_interfaces(const Node& node, int dimension) {
  std::vector<Interface> interfaces;
  if (node.yaml().IsNull()) return interfaces;
  for (const Node& item : node.sequence())
    interfaces.push_back(read_interface(item, dimension, interfaces));
  return interfaces;
}

} // namespace seam::io::detail
