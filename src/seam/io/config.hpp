#pragma once
// The input file (CONTRACT.md, "Input file (YAML)") parsed once into typed, validated structs.
// Every later stage receives the part it needs; nothing reads YAML after load_config.
#include "seam/io/expression.hpp"

#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace seam::io {

/// Where something came from in the input, so that a later stage (e.g. the one that knows
/// the mesh's regions) can point the user at the exact spot.
struct Mark {
  std::string file;     ///< the input file as the user named it
  int line = 0;         ///< 1-based; 0 if unknown
  int column = 0;       ///< 1-based; 0 if unknown
  std::string key_path; ///< e.g. "boundary_conditions[2].region"
};

/// Throws InputError "FILE:LINE:COL: KEY.PATH: MESSAGE".
[[noreturn]] void fail_at(const Mark& mark, std::string_view message);
/// The "FILE:LINE:COL: KEY.PATH" prefix of such a message.
std::string to_string(const Mark& mark);

/// A mesh region (Gmsh physical group) named in the input, with where it was named.
struct RegionRef {
  std::string name;
  Mark mark;
};

enum class PlaneMode { strain, stress };
enum class MaterialModel { linear_elastic, saint_venant_kirchhoff, neo_hooke, newtonian_fluid };
enum class BoundaryType { dirichlet, pressure, traction, body_force, velocity, mesh_displacement };
/// How a fluid body's mesh moves (ALE): by a pseudo-elastic solve driven by the boundary's
/// `mesh_displacement` conditions, or by a displacement given everywhere.
enum class MeshMotionModel { pseudo_elastic, prescribed };
enum class Stiffening { jacobian, none };
/// fsi: a fluid-structure interface (docs/fsi.md); its `fluid` group is the slave side, its
/// `structure` group the master.
enum class InterfaceType { mesh_tying, contact, fsi };
enum class Multiplier { dual, standard };
enum class Strategy { condensed, saddle_point };
enum class FrictionModel { frictionless, coulomb, tresca };
/// `static` in the input: a sequence of equilibrium states, t is a load parameter.
enum class Integrator { quasi_static, generalized_alpha, energy_momentum };
/// `auto`: direct or iterative by the problem (problem/newton.hpp, linear_solver_kind).
enum class LinearSolverKind { direct, iterative, automatic };
/// The start of Newton's method in a static load step: the last converged state, or that state
/// extrapolated linearly in t from the last two (problem/static_solver.cpp).
enum class InitialGuess { extrapolated, previous };
/// How the slave elements of an interface are spread over the ranks.
enum class InterfaceDistribution { independent, bulk };
/// What the dynamic load balance measures per rank.
enum class WorkMeasure { time, integration_cells };

/// The spelling used in the input file.
std::string_view to_string(PlaneMode value);
std::string_view to_string(MaterialModel value);
std::string_view to_string(BoundaryType value);
std::string_view to_string(MeshMotionModel value);
std::string_view to_string(InterfaceType value);
std::string_view to_string(Multiplier value);
std::string_view to_string(Strategy value);
std::string_view to_string(FrictionModel value);
std::string_view to_string(Integrator value);
std::string_view to_string(LinearSolverKind value);
std::string_view to_string(InitialGuess value);
std::string_view to_string(InterfaceDistribution value);
std::string_view to_string(WorkMeasure value);

struct MeshConfig {
  std::filesystem::path file; ///< absolute; a .msh file, or empty if `geo` is given
  std::filesystem::path geo;  ///< absolute; a .geo file meshed at start, or empty
  std::optional<double> size; ///< geo only: characteristic mesh size
  int order = 0;              ///< geo only: 1 (linear) or 2 (quadratic); 0 = as the .geo says
  bool serendipity = false;   ///< geo only, order 2: quad8/hex20 instead of quad9/hex27
  Mark mark;
};

struct Material {
  std::string name;
  MaterialModel model = MaterialModel::linear_elastic;
  double young = 0.0;     ///< > 0
  double poisson = 0.0;   ///< in (-1, 0.5)
  double density = 0.0;   ///< >= 0; > 0 for every body in dynamics and for every fluid
  double viscosity = 0.0; ///< newtonian_fluid only: dynamic viscosity, > 0
  Mark mark;

  [[nodiscard]] bool is_fluid() const { return model == MaterialModel::newtonian_fluid; }
};

/// `mesh_motion` of a fluid body (docs/fluid.md, "Moving meshes").
struct MeshMotion {
  MeshMotionModel model = MeshMotionModel::pseudo_elastic;
  /// pseudo_elastic: jacobian = cells stiffer the smaller they are, E ~ (V_min / V)^power
  /// (Stein, Tezduyar & Benney 2003); none = uniform.
  Stiffening stiffening = Stiffening::jacobian;
  double stiffening_power = 1.0; ///< chi >= 0
  /// prescribed: `dimension` expressions in (t, x, y, z) of the reference coordinates.
  std::vector<Expression> displacement;
  Mark mark;
};

struct Body {
  RegionRef region;                      ///< physical group of the mesh's highest dimension
  std::string material;                  ///< a key of Config::materials
  std::optional<MeshMotion> mesh_motion; ///< fluid bodies only; unset = the mesh is fixed
  Mark mark;
};

/// One entry of `boundary_conditions`. Values are functions of (t, x, y, z) with x, y, z the
/// reference coordinates: prescribed displacement (dirichlet), follower pressure on the
/// current surface (pressure), dead load per reference area (traction), force per reference
/// volume (body_force, on a body region).
struct BoundaryCondition {
  RegionRef region;
  BoundaryType type = BoundaryType::dirichlet;
  /// dirichlet, velocity (a fluid's velocity): the listed components (0 = x, 1 = y, 2 = z),
  /// all if omitted; mesh_displacement (a fluid mesh's boundary motion): all;
  /// traction, body_force: 0 .. dimension-1; pressure: empty.
  std::vector<int> components;
  /// one expression per entry of `components`; pressure: exactly one.
  std::vector<Expression> value;
  Mark mark;
};

struct InitialCondition {
  RegionRef region;
  std::vector<Expression> velocity; ///< `dimension` entries
  Mark mark;
};

struct RigidPlane {
  std::array<double, 3> point{};  ///< a point of the plane in the reference state (z = 0 in 2D)
  std::array<double, 3> normal{}; ///< unit normal, as given then normalized
  /// `dimension` expressions in t: displacement of the plane (default: at rest)
  std::vector<Expression> motion;
  Mark mark;
};

/// `rigid_sphere` (a circle in 2D) or `rigid_cylinder` (3D): a round rigid obstacle.
struct RigidObstacle {
  bool cylinder = false;
  std::array<double, 3> point{}; ///< sphere: centre; cylinder: a point of the axis (reference)
  std::array<double, 3> axis{};  ///< cylinder only: unit axis, as given then normalized
  double radius = 0.0;           ///< > 0
  /// `dimension` expressions in t: displacement of the obstacle (default: at rest)
  std::vector<Expression> motion;
  Mark mark;
};

struct Friction {
  FrictionModel model = FrictionModel::frictionless;
  double coefficient = 0.0; ///< Coulomb coefficient mu, >= 0
  double bound = 0.0;       ///< Tresca: the slip bound of the tangential traction, >= 0
};

struct Interface {
  std::string name; ///< unique; used in output file names
  InterfaceType type = InterfaceType::mesh_tying;
  RegionRef slave;                 ///< self/multi-body contact: the first group of `surface`
  std::optional<RegionRef> master; ///< exactly one of master and rigid_plane
  /// Self and multi-body contact (`surface: [groups...]`, contact only): the boundary groups
  /// of one interface whose slave and master facets are chosen at every search; then there is
  /// neither master nor rigid_plane.
  std::vector<RegionRef> surface;
  std::optional<RigidPlane> rigid_plane; ///< contact only
  /// Contact only: rigid_sphere or rigid_cylinder (exclusive with master and rigid_plane).
  std::optional<RigidObstacle> rigid_obstacle;
  Multiplier multiplier = Multiplier::dual;
  /// default condensed with dual multipliers, saddle_point with standard ones (a standard
  /// multiplier's D matrix is not diagonal, so it cannot be condensed cheaply).
  Strategy strategy = Strategy::condensed;
  Friction friction; ///< contact only
  /// Contact only: the complementarity parameter of C = lambda_n - max(0, lambda_n - c_n g)
  /// (pressure per length); unset = chosen from the stiffness and the mesh size.
  std::optional<double> c_n;
  /// Contact with friction only: the complementarity parameter of the stick/slip condition
  /// (same units as c_n); unset = c_n.
  std::optional<double> c_t;
  Mark mark;
};

struct TimeConfig {
  Integrator integrator = Integrator::quasi_static;
  /// Spectral radius at infinite frequency (Chung & Hulbert 1993). The default 0.8 damps the
  /// unresolved high-frequency modes that contact impacts excite, at second-order accuracy;
  /// 1.0 gives the undamped trapezoidal rule.
  double rho_inf = 0.8;
  double end = 1.0; ///< > 0
  int n_steps = 1;  ///< `steps`, or ceil(end / dt) if `dt` was given
  double dt = 1.0;  ///< `dt`, or end / steps if `steps` was given
  int max_step_cuts = 5;
  Mark mark;

  [[nodiscard]] bool is_dynamic() const { return integrator != Integrator::quasi_static; }
  /// Time at the end of step `step` (0 = start); the last step ends exactly at `end`.
  [[nodiscard]] double time_at(int step) const;
};

struct NewtonConfig {
  double tolerance = 1e-10; ///< on the relative residual norm
  int max_iterations = 25;
  InitialGuess initial_guess = InitialGuess::previous; ///< static load steps only
  /// Backtracking of condensed contact corrections that do not reduce the residual.
  bool line_search = true;
};

struct SolverConfig {
  NewtonConfig newton;
  LinearSolverKind linear = LinearSolverKind::automatic;
};

/// `parallel:` (CONTRACT.md, "Parallel runs").
struct ParallelConfig {
  InterfaceDistribution interface_distribution = InterfaceDistribution::independent;
  /// A contact interface is redistributed when max/min of its per-rank work exceeds this.
  double rebalance_tolerance = 1.2;
  /// time: the CPU time of each rank's interface evaluation (the seed's eq. 21);
  /// integration_cells: the count of integration cells, deterministic (shared machines).
  WorkMeasure work = WorkMeasure::time;
};

struct Probe {
  std::array<double, 3> point{}; ///< reference coordinates, z = 0 in 2D
  Mark mark;
};

/// One entry of `output.forces`: the force the fluid exerts on the union of `regions`.
struct ForceGroup {
  std::string name;
  std::vector<RegionRef> regions; ///< fluid-side boundary groups
  Mark mark;
};

struct OutputConfig {
  int every = 1;            ///< write every n-th step
  int checkpoint_every = 0; ///< a checkpoint every n-th converged step; 0: never
  std::vector<Probe> probes;
  /// Optional exact displacement (`dimension` expressions): the L2 and H1 errors of every
  /// written step go to errors.csv (method of manufactured solutions).
  std::vector<Expression> exact_displacement;
  /// forces.csv (fluids).
  std::vector<ForceGroup> forces;
  /// Optional exact fluid velocity (`dimension` expressions) and pressure (one): their L2
  /// errors go to errors.csv.
  std::vector<Expression> exact_velocity;
  std::vector<Expression> exact_pressure;
};

struct Config {
  std::filesystem::path source; ///< absolute path of the input file
  std::string title;
  int dimension = 3;
  PlaneMode plane = PlaneMode::strain; ///< 2D only
  MeshConfig mesh;
  std::map<std::string, Material> materials;
  std::vector<Body> bodies;
  std::vector<BoundaryCondition> boundary_conditions;
  std::vector<InitialCondition> initial_conditions;
  std::vector<Interface> interfaces;
  TimeConfig time;
  SolverConfig solver;
  OutputConfig output;
  ParallelConfig parallel;
};

/// Reads and validates an input file. Paths inside it become absolute, relative to the
/// file's folder. Throws InputError "FILE:LINE:COL: KEY.PATH: what was expected".
Config load_config(const std::filesystem::path& yaml);

} // namespace seam::io
