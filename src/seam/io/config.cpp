// load_config: the top level, mesh, materials, bodies, time, solver and output sections.
// Boundary conditions, initial conditions and interfaces are in config_conditions.cpp.
#include "seam/io/config.hpp"

#include "seam/common/error.hpp"
#include "seam/io/config_reader.hpp"

#include <algorithm>
#include <cmath>
#include <system_error>

namespace seam::io {

namespace {

namespace fs = std::filesystem;
using detail::concat;
using detail::format_number;
using detail::Map;
using detail::Node;

template <class Enum, std::size_t N>
std::string_view name_of(Enum value,
                         const std::array<std::pair<std::string_view, Enum>, N>& names) {
  for (const auto& [name, enumerator] : names)
    if (enumerator == value) return name;
  SEAM_ASSERT(false);
  return "?";
}

// A path in the input is relative to the input file's folder, so that a case directory can
// be moved or run from anywhere.
fs::path resolve(const Node& node, const fs::path& folder) {
  const std::string text = node.string();
  if (text.empty()) node.fail("expected a file name, got ''");
  fs::path path(text);
  if (path.is_relative()) path = folder / path;
  path = path.lexically_normal();
  std::error_code error;
  if (!fs::is_regular_file(path, error)) node.fail(concat("file not found: ", path.string()));
  return path;
}

MeshConfig read_mesh(const Node& node, const fs::path& folder) {
  const Map map(node, {"file", "geo", "size", "order", "serendipity"});
  MeshConfig mesh;
  mesh.mark = node.mark();
  const auto file = map.get("file");
  const auto geo = map.get("geo");
  if (file && geo)
    geo->fail("give either 'file' (a .msh mesh) or 'geo' (meshed at start), not both");
  if (!file && !geo)
    node.fail("missing required key 'file' (a .msh mesh) or 'geo' (a .geo geometry)");
  if (file) {
    if (fs::path(file->string()).extension() == ".geo")
      file->fail(
          "a .geo geometry goes under 'geo:' (it is meshed at start); 'file:' takes a .msh mesh");
    mesh.file = resolve(*file, folder);
  } else {
    mesh.geo = resolve(*geo, folder);
  }
  map.forbid("size", !geo, "applies only to a 'geo' geometry (a .msh file is already meshed)");
  map.forbid("order", !geo, "applies only to a 'geo' geometry (a .msh file is already meshed)");
  map.forbid("serendipity", !geo,
             "applies only to a 'geo' geometry (a .msh file is already meshed)");
  if (const auto serendipity = map.get("serendipity")) mesh.serendipity = serendipity->boolean();
  if (const auto size = map.get("size")) {
    mesh.size = size->number();
    if (*mesh.size <= 0.0) size->fail(concat("must be > 0, got ", format_number(*mesh.size)));
  }
  if (const auto order = map.get("order")) {
    mesh.order = order->integer();
    if (mesh.order != 1 && mesh.order != 2)
      order->fail(concat("expected 1 (linear) or 2 (quadratic), got ", mesh.order));
  }
  return mesh;
}

// An incompressible Newtonian fluid: density and dynamic viscosity, both required.
Material read_fluid(const Map& map, Material material) {
  map.forbid("young", true, "applies only to solid materials (a newtonian_fluid has 'viscosity')");
  map.forbid("poisson", true,
             "applies only to solid materials (a newtonian_fluid is incompressible)");
  for (const char* key : {"density", "viscosity"}) {
    const auto value = map.get(key);
    if (!value)
      map.node().fail(concat("missing required key '", key,
                             "': a newtonian_fluid needs "
                             "'density' (mass per volume) and 'viscosity' (dynamic viscosity)"));
    const double number = value->number();
    if (!(number > 0.0)) value->fail(concat("must be > 0, got ", format_number(number)));
    (key[0] == 'd' ? material.density : material.viscosity) = number;
  }
  return material;
}

Material read_material(const std::string& name, const Node& node) {
  const Map map(node, {"model", "young", "poisson", "density", "viscosity"});
  Material material;
  material.name = name;
  material.mark = node.mark();
  material.model = map.required("model").choice(detail::material_names);
  if (material.is_fluid()) return read_fluid(map, std::move(material));
  map.forbid("viscosity", true, "applies only to model 'newtonian_fluid'");
  // Positive definiteness of the isotropic elasticity tensor: mu > 0 and 3 lambda + 2 mu > 0,
  // i.e. young > 0 and -1 < poisson < 0.5 (0.5 is incompressible, needing a mixed method).
  const Node young = map.required("young");
  material.young = young.number();
  if (material.young <= 0.0) young.fail(concat("must be > 0, got ", format_number(material.young)));
  const Node poisson = map.required("poisson");
  material.poisson = poisson.number();
  if (material.poisson <= -1.0 || material.poisson >= 0.5)
    poisson.fail(concat("must satisfy -1 < poisson < 0.5, got ", format_number(material.poisson)));
  if (const auto density = map.get("density")) {
    material.density = density->number();
    if (material.density < 0.0)
      density->fail(concat("must be >= 0, got ", format_number(material.density)));
  }
  return material;
}

std::map<std::string, Material> read_materials(const Node& node) {
  const Map map(node);
  if (map.entries().empty())
    node.fail("expected at least one material, e.g. 'steel: {model: ...}'");
  std::map<std::string, Material> materials;
  for (const auto& [name, value] : map.entries())
    materials.emplace(name, read_material(name, value));
  return materials;
}

MeshMotion read_mesh_motion(const Node& node, int dimension) {
  const Map map(node, {"model", "stiffening", "stiffening_power", "displacement"});
  MeshMotion motion;
  motion.mark = node.mark();
  motion.model = map.required("model").choice(detail::mesh_motion_names);
  const bool elastic = motion.model == MeshMotionModel::pseudo_elastic;
  map.forbid("stiffening", !elastic, "applies only to model 'pseudo_elastic'");
  map.forbid("stiffening_power", !elastic, "applies only to model 'pseudo_elastic'");
  map.forbid("displacement", elastic,
             "applies only to model 'prescribed' (a pseudo-elastic mesh is driven by "
             "'mesh_displacement' boundary conditions)");
  if (const auto stiffening = map.get("stiffening"))
    motion.stiffening = stiffening->choice(detail::stiffening_names);
  if (const auto power = map.get("stiffening_power")) {
    motion.stiffening_power = power->number();
    if (!(motion.stiffening_power >= 0.0))
      power->fail(concat("must be >= 0, got ", format_number(motion.stiffening_power)));
  }
  if (!elastic) motion.displacement = map.required("displacement").expressions(dimension);
  return motion;
}

std::vector<Body> read_bodies(const Node& node, const std::map<std::string, Material>& materials,
                              int dimension) {
  const auto items = node.sequence();
  if (items.empty())
    node.fail("expected at least one body, e.g. '- {region: block, material: steel}'");
  std::vector<std::string_view> material_names;
  for (const auto& entry : materials) material_names.push_back(entry.first);
  std::vector<Body> bodies;
  for (const Node& item : items) {
    const Map map(item, {"region", "material", "mesh_motion"});
    Body body;
    body.mark = item.mark();
    const Node region = map.required("region");
    body.region = RegionRef{region.string(), region.mark()};
    for (const Body& other : bodies) {
      if (other.region.name == body.region.name)
        region.fail(concat("region '", body.region.name, "' is already a body (line ",
                           other.region.mark.line, ")"));
    }
    const Node material = map.required("material");
    body.material = material.string();
    if (!materials.contains(body.material)) {
      material.fail(concat("unknown material '", body.material, "'",
                           detail::did_you_mean(body.material, material_names),
                           "; defined under 'materials': ", detail::quoted_list(material_names)));
    }
    map.forbid("mesh_motion", !materials.at(body.material).is_fluid(),
               "applies only to a body of a fluid material (the mesh of a solid moves with "
               "the solid)");
    if (const auto motion = map.get("mesh_motion"))
      body.mesh_motion = read_mesh_motion(*motion, dimension);
    bodies.push_back(std::move(body));
  }
  return bodies;
}

// With dt given, n_steps rounds end/dt up, except when end/dt is an integer up to rounding
// (end = 1, dt = 0.1 gives 9.999999999999998).
int count_steps(const Node& node, double end, double dt) {
  const double ratio = end / dt;
  if (ratio > 1e9) node.fail(concat("end / dt = ", format_number(ratio), " steps is too many"));
  const double nearest = std::round(ratio);
  const double n = std::abs(ratio - nearest) <= 1e-9 * ratio ? nearest : std::ceil(ratio);
  return std::max(1, static_cast<int>(n));
}

TimeConfig read_time(const Node& node) {
  const Map map(node, {"integrator", "rho_inf", "end", "steps", "dt", "max_step_cuts"});
  TimeConfig time;
  time.mark = node.mark();
  if (const auto integrator = map.get("integrator"))
    time.integrator = integrator->choice(detail::integrator_names);
  map.forbid("rho_inf", time.integrator != Integrator::generalized_alpha,
             "applies only to integrator 'generalized_alpha'");
  if (const auto rho_inf = map.get("rho_inf")) {
    time.rho_inf = rho_inf->number();
    if (time.rho_inf < 0.0 || time.rho_inf > 1.0)
      rho_inf->fail(concat("must be in [0, 1], got ", format_number(time.rho_inf)));
  }
  const Node end = map.required("end");
  time.end = end.number();
  if (time.end <= 0.0) end.fail(concat("must be > 0, got ", format_number(time.end)));
  const auto steps = map.get("steps");
  const auto dt = map.get("dt");
  if (steps && dt) dt->fail("give either 'steps' or 'dt', not both");
  if (!steps && !dt) node.fail("missing required key 'steps' (or 'dt')");
  if (steps) {
    time.n_steps = steps->integer();
    if (time.n_steps <= 0) steps->fail(concat("must be a positive integer, got ", time.n_steps));
    time.dt = time.end / time.n_steps;
  } else {
    time.dt = dt->number();
    if (time.dt <= 0.0) dt->fail(concat("must be > 0, got ", format_number(time.dt)));
    time.n_steps = count_steps(*dt, time.end, time.dt);
  }
  if (const auto cuts = map.get("max_step_cuts")) {
    time.max_step_cuts = cuts->integer();
    if (time.max_step_cuts < 0) cuts->fail(concat("must be >= 0, got ", time.max_step_cuts));
  }
  return time;
}

SolverConfig read_solver(const Node& node) {
  const Map map(node, {"newton", "linear"});
  SolverConfig solver;
  if (const auto newton_node = map.get("newton")) {
    const Map newton(*newton_node, {"tolerance", "max_iterations", "initial_guess", "line_search"});
    if (const auto tolerance = newton.get("tolerance")) {
      solver.newton.tolerance = tolerance->number();
      if (solver.newton.tolerance <= 0.0)
        tolerance->fail(concat("must be > 0, got ", format_number(solver.newton.tolerance)));
    }
    if (const auto iterations = newton.get("max_iterations")) {
      solver.newton.max_iterations = iterations->integer();
      if (solver.newton.max_iterations < 1)
        iterations->fail(concat("must be >= 1, got ", solver.newton.max_iterations));
    }
    if (const auto guess = newton.get("initial_guess"))
      solver.newton.initial_guess = guess->choice(detail::initial_guess_names);
    if (const auto search = newton.get("line_search"))
      solver.newton.line_search = search->boolean();
  }
  if (const auto linear = map.get("linear")) solver.linear = linear->choice(detail::linear_names);
  return solver;
}

ParallelConfig read_parallel(const Node& node) {
  const Map map(node, {"interface_distribution", "rebalance_tolerance", "work"});
  ParallelConfig parallel;
  if (const auto d = map.get("interface_distribution"))
    parallel.interface_distribution = d->choice(detail::distribution_names);
  if (const auto tolerance = map.get("rebalance_tolerance")) {
    parallel.rebalance_tolerance = tolerance->number();
    if (!(parallel.rebalance_tolerance >= 1.0))
      tolerance->fail(concat("must be >= 1 (a ratio max/min of per-rank work), got ",
                             format_number(parallel.rebalance_tolerance)));
  }
  if (const auto work = map.get("work")) parallel.work = work->choice(detail::work_names);
  return parallel;
}

// output.forces: [{name, regions: [...]}, ...]; names are unique (they are forces.csv keys).
std::vector<ForceGroup> read_forces(const Node& node) {
  std::vector<ForceGroup> groups;
  for (const Node& item : node.sequence()) {
    const Map map(item, {"name", "regions"});
    ForceGroup group;
    group.mark = item.mark();
    const Node name = map.required("name");
    group.name = name.string();
    if (group.name.empty()) name.fail("expected a name, got ''");
    for (const auto& other : groups)
      if (other.name == group.name)
        name.fail(concat("duplicate force name '", group.name, "' (first at line ", other.mark.line,
                         ")"));
    const Node regions = map.required("regions");
    for (const Node& region : regions.sequence()) {
      const std::string text = region.string();
      if (text.empty()) region.fail("expected a region name (a Gmsh physical group), got ''");
      group.regions.push_back(RegionRef{text, region.mark()});
    }
    if (group.regions.empty()) regions.fail("expected at least one boundary region");
    groups.push_back(std::move(group));
  }
  return groups;
}

OutputConfig read_output(const Node& node, int dimension) {
  const Map map(node, {"every", "probes", "exact_displacement", "forces", "exact_velocity",
                       "exact_pressure", "checkpoint_every"});
  OutputConfig output;
  if (const auto every = map.get("every")) {
    output.every = every->integer();
    if (output.every < 1) every->fail(concat("must be >= 1, got ", output.every));
  }
  if (const auto checkpoint = map.get("checkpoint_every")) {
    output.checkpoint_every = checkpoint->integer();
    if (output.checkpoint_every < 1)
      checkpoint->fail(
          concat("must be >= 1 (omit the key for no checkpoints), got ", output.checkpoint_every));
  }
  if (const auto probes = map.get("probes")) {
    for (const Node& probe : probes->sequence())
      output.probes.push_back(Probe{probe.point(dimension), probe.mark()});
  }
  if (const auto exact = map.get("exact_displacement"))
    output.exact_displacement = exact->expressions(dimension);
  if (const auto forces = map.get("forces")) output.forces = read_forces(*forces);
  if (const auto exact = map.get("exact_velocity"))
    output.exact_velocity = exact->expressions(dimension);
  if (const auto exact = map.get("exact_pressure")) {
    if (!exact->yaml().IsScalar())
      exact->fail(
          concat("expected one expression (a pressure is a scalar), got ", exact->describe()));
    output.exact_pressure.push_back(exact->expression());
  }
  return output;
}

// Dynamics needs mass: a body without density has a singular mass matrix.
void check_densities(const Config& config, const Node& time_node) {
  if (!config.time.is_dynamic()) return;
  for (const Body& body : config.bodies) {
    const Material& material = config.materials.at(body.material);
    if (material.density <= 0.0) {
      fail_at(material.mark,
              concat("density must be > 0 for time.integrator '", to_string(config.time.integrator),
                     "' (body '", body.region.name, "' uses material '", material.name,
                     "'; time is set at line ", time_node.mark().line, ")"));
    }
  }
}

} // namespace

double TimeConfig::time_at(int step) const {
  if (step >= n_steps) return end;
  // end * step / n_steps is correctly rounded (3.3, not 3.3000000000000003) when the steps
  // divide the interval evenly.
  const double t = std::abs(n_steps * dt - end) <= 1e-12 * end ? end * step / n_steps : step * dt;
  return std::min(end, t);
}

std::string_view to_string(PlaneMode value) {
  return name_of(value, detail::plane_names);
}
std::string_view to_string(MaterialModel value) {
  return name_of(value, detail::material_names);
}
std::string_view to_string(BoundaryType value) {
  return name_of(value, detail::boundary_names);
}
std::string_view to_string(MeshMotionModel value) {
  return name_of(value, detail::mesh_motion_names);
}
std::string_view to_string(InterfaceType value) {
  return name_of(value, detail::interface_names);
}
std::string_view to_string(Multiplier value) {
  return name_of(value, detail::multiplier_names);
}
std::string_view to_string(Strategy value) {
  return name_of(value, detail::strategy_names);
}
std::string_view to_string(FrictionModel value) {
  return name_of(value, detail::friction_names);
}
std::string_view to_string(Integrator value) {
  return name_of(value, detail::integrator_names);
}
std::string_view to_string(LinearSolverKind value) {
  return name_of(value, detail::linear_names);
}
std::string_view to_string(InitialGuess value) {
  return name_of(value, detail::initial_guess_names);
}
std::string_view to_string(InterfaceDistribution value) {
  return name_of(value, detail::distribution_names);
}
std::string_view to_string(WorkMeasure value) {
  return name_of(value, detail::work_names);
}

Config load_config(const std::filesystem::path& yaml) {
  const std::string file = yaml.string();
  std::error_code error;
  if (!fs::is_regular_file(yaml, error))
    SEAM_THROW(InputError, file, ": input file not found (looked for ",
               fs::absolute(yaml, error).lexically_normal().string(), ")");

  YAML::Node root;
  try {
    root = YAML::LoadFile(file);
  } catch (const YAML::ParserException& e) {
    fail_at(Mark{file, e.mark.line + 1, e.mark.column + 1, ""}, concat("invalid YAML: ", e.msg));
  } catch (const YAML::Exception& e) {
    SEAM_THROW(InputError, file, ": cannot read the input file: ", e.what());
  }

  const Node top(root, file, "");
  if (!root.IsDefined() || root.IsNull())
    SEAM_THROW(InputError, file,
               ": the input file is empty; expected 'dimension', 'mesh', "
               "'materials', 'bodies' and 'time'");
  const Map map(top, {"title", "dimension", "plane", "mesh", "materials", "bodies",
                      "boundary_conditions", "initial_conditions", "interfaces", "time", "solver",
                      "output", "parallel"});

  Config config;
  config.source = fs::absolute(yaml).lexically_normal();
  const fs::path folder = config.source.parent_path();

  if (const auto title = map.get("title")) config.title = title->string();
  const Node dimension = map.required("dimension");
  config.dimension = dimension.integer();
  if (config.dimension != 2 && config.dimension != 3)
    dimension.fail(concat("expected 2 or 3, got ", config.dimension));
  map.forbid("plane", config.dimension != 2, "applies only to dimension 2");
  if (const auto plane = map.get("plane")) config.plane = plane->choice(detail::plane_names);

  config.mesh = read_mesh(map.required("mesh"), folder);
  config.materials = read_materials(map.required("materials"));
  config.bodies = read_bodies(map.required("bodies"), config.materials, config.dimension);
  const Node time = map.required("time");
  config.time = read_time(time);
  if (const auto conditions = map.get("boundary_conditions"))
    config.boundary_conditions = detail::read_boundary_conditions(*conditions, config.dimension);
  map.forbid("initial_conditions", !config.time.is_dynamic(),
             "apply only to dynamics (time.integrator is 'static')");
  if (const auto conditions = map.get("initial_conditions"))
    config.initial_conditions = detail::read_initial_conditions(*conditions, config.dimension);
  if (const auto interfaces = map.get("interfaces"))
    config.interfaces = detail::read_interfaces(*interfaces, config.dimension);
  if (const auto solver = map.get("solver")) config.solver = read_solver(*solver);
  if (const auto output = map.get("output")) config.output = read_output(*output, config.dimension);
  if (const auto parallel = map.get("parallel")) config.parallel = read_parallel(*parallel);
  check_densities(config, time);
  return config;
}

} // namespace seam::io
