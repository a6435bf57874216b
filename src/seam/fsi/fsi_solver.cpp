#include "seam/fsi/fsi_solver.hpp"

#include "seam/common/collective.hpp"
#include "seam/common/error.hpp"
#include "seam/common/timer.hpp"
#include "seam/fluid/navier_stokes.hpp"
#include "seam/fsi/fsi_system.hpp"
#include "seam/io/json.hpp"
#include "seam/io/table.hpp"
#include "seam/io/vtu.hpp"
#include "seam/mesh/cell_geometry.hpp"
#include "seam/mesh/locate.hpp"
#include "seam/meshtying/tied_interface.hpp"
#include "seam/parallel/memory_trace.hpp"
#include "seam/problem/checkpoint.hpp"
#include "seam/problem/linear_solver_choice.hpp"
#include "seam/problem/model.hpp"
#include "seam/problem/output.hpp"
#include "seam/problem/progress.hpp"
#include "seam/problem/step_control.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>

namespace seam::fsi {

using problem::Checkpoints;
using problem::find_region;
using problem::MeshIdentity;
using problem::n_rank_detail_basics;
using problem::print_step_line;
using problem::put_rank_detail_basics;
using problem::RecordWriter;
using problem::RestartFrom;
using problem::StepControl;
using problem::SystemKind;
using problem::time_left;
using problem::write_step_fields;

namespace {

// Checks what a steady fsi run needs beyond FsiSystem's checks.
void check_fsi_input(const io::Config& config) {
  const io::Interface* first = nullptr;
  for (const auto& itf : config.interfaces)
    if (itf.type == io::InterfaceType::fsi && !first) first = &itf;
  bool fluid = false, solid = false;
  for (const auto& body : config.bodies)
    (config.materials.at(body.material).is_fluid() ? fluid : solid) = true;
  if (!fluid || !solid)
    io::fail_at(first->mark, "interface '" + first->name +
                                 "' of type 'fsi' joins a fluid and a structure, but the run "
                                 "has no " +
                                 (fluid ? "solid" : "fluid") + " body");
  if (config.time.integrator == io::Integrator::energy_momentum)
    io::fail_at(config.time.mark,
                "fluid-structure interaction is integrated with 'generalized_alpha' (or solved "
                "steady with 'static'); 'energy_momentum' is a scheme for solids");
}

// The fluid force on a set of nodes: minus the fluid momentum residual there (the reaction).
std::array<double, 3> fluid_force(const FsiSystem& sys, const std::vector<double>& r,
                                  const std::vector<std::int32_t>& nodes) {
  std::array<double, 3> f{};
  for (auto n : nodes)
    for (int i = 0; i < sys.dim(); ++i) f[i] -= r[sys.f_dof(n, i)];
  return f;
}

struct Writer {
  std::filesystem::path dir;
  std::unique_ptr<io::PvdCollection> pvd;
  std::optional<io::CsvTable> forces, steps, probes, interfaces;
  std::vector<mesh::PointLocation> probe_at;
  std::vector<std::pair<std::string, std::vector<std::int32_t>>> groups;
};

// The fields of a step: each rank the piece of the cells it assembles and their nodes (the
// pressure at every node of a fluid cell: its linear interpolation from the vertices), cell
// data `rank`; results_NNNNN.vtu on one rank, else results_NNNNN.pvtu listing the pieces.
// Collective.
void write_fields(const FsiSystem& sys, const std::vector<double>& raw, int step, double t,
                  Writer& w) {
  const auto& mesh = sys.mesh();
  const int dim = mesh.dim;
  const problem::PieceGrid grid(mesh, sys.local_cells(), sys.comm().rank());
  const auto& local = grid.point_of;
  const auto nn = grid.nodes.size();
  std::vector<double> points(nn * dim), disp(nn * 3, 0.0), mdisp(nn * 3, 0.0), vel(nn * 3, 0.0),
      pres(nn, 0.0);
  for (std::size_t q = 0; q < nn; ++q) {
    const auto node = grid.nodes[q];
    for (int i = 0; i < dim; ++i) {
      points[q * dim + i] = mesh.x[static_cast<std::size_t>(node) * dim + i];
      if (sys.is_solid_node(node)) disp[q * 3 + i] = raw[sys.d_dof(node, i)];
      if (sys.is_fluid_node(node)) {
        mdisp[q * 3 + i] = raw[sys.m_dof(node, i)];
        disp[q * 3 + i] = mdisp[q * 3 + i];
        vel[q * 3 + i] = raw[sys.f_dof(node, i)];
      }
    }
  }
  for (auto c : sys.local_cells()) {
    if (!sys.is_fluid_cell(c)) continue;
    const auto nodes = mesh.cell(c);
    const auto pcell = fluid::pressure_cell(mesh.cell_type[c]);
    const auto xi = fem::reference_nodes(mesh.cell_type[c]);
    std::array<double, 8> N{};
    for (std::size_t a = 0; a < nodes.size(); ++a) {
      fem::shape_values(pcell, &xi[a * dim], N.data());
      double p = 0.0;
      for (int v = 0; v < fem::n_nodes(pcell); ++v) p += N[v] * raw[sys.f_dof(nodes[v], dim)];
      pres[local[nodes[a]]] = p;
    }
  }
  auto piece = grid.piece(dim, points, t, step);
  piece.point_data.emplace_back("displacement", 3, std::span<const double>(disp));
  piece.point_data.emplace_back("velocity", 3, std::span<const double>(vel));
  piece.point_data.emplace_back("pressure", 1, std::span<const double>(pres));
  piece.point_data.emplace_back("mesh_displacement", 3, std::span<const double>(mdisp));
  const auto file = write_step_fields(w.dir, step, piece, sys.comm());
  if (sys.comm().is_root()) w.pvd->add(t, file);
}

// interface_<name>.csv: per fluid-side node its reference position, the structure's
// displacement there (P d), and the traction the fluid exerts, t_j = -r_j / D_jj. Each rank
// the rows of the fluid nodes it owns (`r`: the raw residual summed there), gathered to rank 0,
// which writes them in the order of the node ids. Collective.
void write_interfaces(const FsiSystem& sys, const std::vector<double>& raw,
                      const std::vector<double>& r, const std::vector<double>& normals,
                      const std::filesystem::path& dir) {
  const int dim = sys.dim();
  struct Row {
    std::int64_t node = 0;
    double x[3] = {0.0, 0.0, 0.0}, u[3] = {0.0, 0.0, 0.0}, tr[3] = {0.0, 0.0, 0.0};
    double tn = 0.0, tt = 0.0;
  };
  for (const auto& cp : sys.couplings()) {
    std::vector<Row> mine;
    for (std::size_t j = 0; j < cp.fluid_nodes.size(); ++j) {
      const auto n = cp.fluid_nodes[j];
      if (!sys.owns_node(n)) continue;
      Row row;
      row.node = sys.node_gid(n);
      for (int i = 0; i < dim; ++i) {
        row.x[i] = sys.node_x(static_cast<std::size_t>(n))[i];
        row.u[i] = raw[sys.m_dof(n, i)];
        row.tr[i] = -r[sys.f_dof(n, i)] / cp.d_diagonal[j];
      }
      const double* nv = &normals[static_cast<std::size_t>(n) * 3];
      row.tn = row.tr[0] * nv[0] + row.tr[1] * nv[1] + row.tr[2] * nv[2];
      double tt = 0.0;
      for (int i = 0; i < 3; ++i) tt += (row.tr[i] - row.tn * nv[i]) * (row.tr[i] - row.tn * nv[i]);
      row.tt = std::sqrt(tt);
      mine.push_back(row);
    }
    auto rows = gather_to_root(sys.comm(), mine);
    if (!sys.comm().is_root()) continue;
    std::sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.node < b.node; });
    std::ostringstream s;
    s.precision(17);
    s << "node,x,y,z,ux,uy,uz,gap,normal_traction,tangential_traction,status,tx,ty,tz\n";
    for (const auto& row : rows)
      s << row.node << ',' << row.x[0] << ',' << row.x[1] << ',' << row.x[2] << ',' << row.u[0]
        << ',' << row.u[1] << ',' << row.u[2] << ",0," << row.tn << ',' << row.tt << ",tied,"
        << row.tr[0] << ',' << row.tr[1] << ',' << row.tr[2] << '\n';
    io::write_file_atomically(dir / ("interface_" + cp.name + ".csv"), s.str());
  }
}

// Unit normals of the fluid's interface nodes (3 per mesh node, 0 elsewhere): the mean of the
// outward normals of the fluid's interface facets at their centres, on the reference mesh
// (out of the fluid, into the structure: a positive normal force pushes on the structure).
std::vector<double> interface_normals(const io::Config& config, const FsiSystem& sys) {
  const auto& mesh = sys.mesh();
  std::vector<double> n(static_cast<std::size_t>(mesh.n_nodes()) * 3, 0.0);
  for (const auto& itf : config.interfaces) {
    const auto& region = meshtying::side_region(mesh, itf.slave);
    for (std::int32_t f = 0; f < region.n_facets(); ++f) {
      const auto c = region.facet_cell[f];
      const int local = region.facet_local[f];
      const auto type = mesh.cell_type[c];
      const auto centre = mesh::reference_centre(fem::facet_type(type, local));
      const auto normal = mesh::facet_normal(mesh, c, local, centre.data());
      const auto nodes = mesh.cell(c);
      for (int a : fem::facet_nodes(type, local))
        for (int i = 0; i < mesh.dim; ++i)
          n[static_cast<std::size_t>(nodes[a]) * 3 + i] += normal[i];
    }
  }
  for (std::size_t k = 0; k < n.size(); k += 3) {
    const double len = std::sqrt(n[k] * n[k] + n[k + 1] * n[k + 1] + n[k + 2] * n[k + 2]);
    if (len > 0.0)
      for (int i = 0; i < 3; ++i) n[k + i] /= len;
  }
  return n;
}

// Locates every probe: in a solid cell if one holds it (a point on the wet surface reports
// the structure), else in a fluid cell; a probe outside both is an input error. Each rank
// searches the cells it assembles; the cell the whole-mesh search would pick (inside, then
// the lowest id; else the nearest within the tolerance) wins, on the rank that assembles it
// (the others get cell -1). Collective.
void locate_probes(const io::Config& config, const FsiSystem& sys, Writer& w) {
  const auto& mesh = sys.mesh();
  const auto* part = sys.part();
  const auto comm = sys.comm();
  std::vector<std::int32_t> solid, fluid;
  for (auto c : sys.local_cells()) (sys.is_fluid_cell(c) ? fluid : solid).push_back(c);
  std::sort(solid.begin(), solid.end());
  std::sort(fluid.begin(), fluid.end());
  const mesh::PointLocator in_solid(mesh, solid), in_fluid(mesh, fluid);
  constexpr double none = std::numeric_limits<double>::infinity();
  for (const auto& probe : config.output.probes) {
    const std::span<const double> p(probe.point.data(), static_cast<std::size_t>(mesh.dim));
    mesh::PointLocation found;
    for (const auto* locator : {&in_solid, &in_fluid}) {
      const auto at = locator->locate(p, 1e-8);
      double distance = none, id = none;
      if (at) {
        // Inside to round-off counts as inside (PointLocator: then the lowest id).
        distance = mesh::reference_distance(mesh.cell_type[at->cell], at->xi.data());
        if (distance <= 1e-12) distance = 0.0;
        id = static_cast<double>(part ? part->cell_gid[at->cell] : at->cell);
      }
      const double best = comm.min(distance);
      const double best_id = comm.min(distance == best ? id : none);
      if (best == none) continue;
      if (at && distance == best && id == best_id) found = *at;
      break;
    }
    if (!comm.any(found.cell >= 0)) io::fail_at(probe.mark, "the probe lies outside the mesh");
    w.probe_at.push_back(found);
  }
}

// probes.csv: the structure's displacement (velocity 0: steady) in a solid cell; the mesh
// displacement, the velocity and the pressure in a fluid cell. Evaluated on the rank that
// located the probe, written by rank 0. Collective.
void write_probes(const FsiSystem& sys, const std::vector<double>& raw, int step, double t,
                  Writer& w) {
  const auto& mesh = sys.mesh();
  const int dim = mesh.dim;
  constexpr std::size_t width = 11; // x, u, v, p, 1 in a fluid cell
  std::vector<double> values(w.probe_at.size() * width, 0.0);
  for (std::size_t k = 0; k < w.probe_at.size(); ++k) {
    const auto& at = w.probe_at[k];
    if (at.cell < 0) continue;
    double* out = &values[k * width];
    const auto type = mesh.cell_type[at.cell];
    const auto nodes = mesh.cell(at.cell);
    std::array<double, fem::max_cell_nodes> N{};
    fem::shape_values(type, at.xi.data(), N.data());
    const bool fluid = sys.is_fluid_cell(at.cell);
    for (std::size_t a = 0; a < nodes.size(); ++a)
      for (int i = 0; i < dim; ++i) {
        out[i] += N[a] * mesh.x[static_cast<std::size_t>(nodes[a]) * dim + i];
        out[3 + i] += N[a] * raw[fluid ? sys.m_dof(nodes[a], i) : sys.d_dof(nodes[a], i)];
        if (fluid) out[6 + i] += N[a] * raw[sys.f_dof(nodes[a], i)];
      }
    if (fluid) {
      const auto pcell = fluid::pressure_cell(type);
      fem::shape_values(pcell, at.xi.data(), N.data());
      for (int a = 0; a < fem::n_nodes(pcell); ++a) out[9] += N[a] * raw[sys.f_dof(nodes[a], dim)];
      out[10] = 1.0;
    }
  }
  sys.comm().sum_in_place(values);
  if (!sys.comm().is_root()) return;
  for (std::size_t k = 0; k < w.probe_at.size(); ++k) {
    const double* v = &values[k * width];
    const io::CsvValue pressure = v[10] > 0.0 ? io::CsvValue(v[9]) : io::CsvValue("");
    w.probes->add_row({step, t, k, v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], pressure});
  }
}

} // namespace

bool has_fsi(const io::Config& config) {
  return std::any_of(config.interfaces.begin(), config.interfaces.end(),
                     [](const io::Interface& i) { return i.type == io::InterfaceType::fsi; });
}

FsiRunInfo run_fsi(const io::Config& config, mesh::DistributedMesh& part,
                   const MeshIdentity& identity, Comm comm, const std::filesystem::path& dir,
                   bool quiet, bool check_only, const RestartFrom& restart) {
  auto& mesh = part.mesh;
  check_fsi_input(config);
  PhaseTimers timers;
  // The couplings set up distributed as mesh tying's (docs/parallel.md, "Mesh tying
  // distributed"): each rank integrates the fluid facets of its cells against the structure
  // facets ghosted to it; P's rows come from the owners of the fluid nodes.
  const auto tied =
      meshtying::setup_mesh_tying(config, part, comm.get(), timers, io::InterfaceType::fsi);
  FsiSystem sys(config, mesh, tied, comm, &part);
  const long long n_nodes = part.n_global_nodes, n_cells = part.n_global_cells;
  FsiRunInfo info;
  info.n_dofs = sys.n_unknowns();
  const int dim = sys.dim();
  Writer w;
  w.dir = dir;
  for (const auto& group : config.output.forces) {
    std::vector<std::int32_t> nodes;
    for (const auto& ref : group.regions) {
      const auto& region = find_region(mesh, ref, {dim - 1}, "a force group");
      bool off_fluid = false; // on any rank (collective)
      for (auto n : region.nodes) {
        off_fluid = off_fluid || !sys.is_fluid_node(n);
        nodes.push_back(n);
      }
      if (comm.any(off_fluid))
        io::fail_at(ref.mark, "force group '" + group.name + "': region '" + ref.name +
                                  "' is not on the fluid; forces.csv sums fluid-side groups");
    }
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    w.groups.emplace_back(group.name, std::move(nodes));
  }
  locate_probes(config, sys, w);
  if (check_only) return info;

  const bool root = comm.is_root();
  // Checkpoints hold the nodal state by global node id (each value written by the owner of
  // its node into its part file) and rank 0's scalars in state.bin.
  const Checkpoints checkpoints(config, "fluid-structure", identity, comm, sys.raw_order(),
                                restart.input, dir, restart.checkpoint);
  // A restart continues the tables (rows after its step dropped) and results.pvd; a table
  // with another header stops every rank.
  on_root_collectively(comm, [&] {
    const auto table = [&](const char* file, std::vector<std::string> columns) {
      return io::CsvTable(dir / file, std::move(columns),
                          checkpoints.restarting() ? checkpoints.table_mode(dir / file)
                                                   : io::CsvTable::Mode::truncate);
    };
    w.pvd =
        checkpoints.restarting()
            ? std::make_unique<io::PvdCollection>(dir / "results.pvd", checkpoints.pvd_entries(dir))
            : std::make_unique<io::PvdCollection>(dir / "results.pvd");
    w.forces.emplace(table("forces.csv", {"step", "time", "name", "fx", "fy", "fz"}));
    // CONTRACT.md's columns (the structure's energies; steady: no kinetic energy or
    // momentum, no contact), then the interface forces of both sides (force conservation).
    // clang-format off
    w.steps.emplace(table("steps.csv", {
        "step", "time", "newton_iterations", "residual", "active_nodes", "slip_nodes",
        "kinetic_energy", "internal_energy", "external_work", "total_energy", "momentum_x",
        "momentum_y", "momentum_z", "angular_momentum_x", "angular_momentum_y",
        "angular_momentum_z", "wall_seconds", "interface_force_fluid_x", "interface_force_fluid_y",
        "interface_force_fluid_z", "interface_force_structure_x", "interface_force_structure_y",
        "interface_force_structure_z", "fluid_kinetic_energy", "viscous_dissipation",
        "boundary_work", "interface_work_fluid", "interface_work_structure"}));
    // clang-format on
    w.interfaces.emplace(
        table("interfaces.csv", {"step", "time", "interface", "normal_force", "tangential_force",
                                 "active_nodes", "slip_nodes", "contact_area"}));
    if (!w.probe_at.empty())
      w.probes.emplace(table("probes.csv", {"step", "time", "probe", "x", "y", "z", "ux", "uy",
                                            "uz", "vx", "vy", "vz", "pressure"}));
  });
  if (root) {
    if (!quiet)
      std::printf("seam: fluid-structure interaction, %lld nodes, %lld cells, %lld unknowns, %d "
                  "rank(s); output in %s\n",
                  n_nodes, n_cells, info.n_dofs, comm.size(), dir.string().c_str());
  }
  // A Newton iteration scatters the unknowns of the held nodes (held_unknowns); nothing is
  // gathered whole.
  la::Vector xv(comm.get(), sys.n_owned());
  const la::Gather gather_held(xv, sys.held_unknowns());
  // MUMPS, or with `linear: iterative` FGMRES with the structure | fluid | mesh fieldsplit
  // (docs/fsi.md, "Linear solvers"); `auto` keeps the direct solver.
  const auto choice =
      choose_linear_solver(config.solver.linear, dim, sys.n_unknowns(), SystemKind::fsi);
  const bool iterative = choice.kind == la::SolverKind::iterative;
  if (iterative && !sys.taylor_hood())
    SEAM_THROW(InputError,
               "solver.linear: 'iterative' with an 'fsi' interface needs Taylor-Hood fluid cells "
               "(tri6, quad9, tet10, hex27): its fieldsplit finds the pressure as the zero "
               "diagonal of the fluid block; use 'direct'");
  const auto velocity_block = config.time.integrator == io::Integrator::generalized_alpha
                                  ? la::LinearSolver::VelocityBlock::ilu
                                  : la::LinearSolver::VelocityBlock::amg;
  const std::string solver_name =
      describe(choice, velocity_block == la::LinearSolver::VelocityBlock::amg
                           ? "FGMRES + structure | fluid | mesh fieldsplit: GAMG, Schur (BoomerAMG "
                             "velocity, BoomerAMG selfp), BoomerAMG"
                           : "FGMRES + structure | fluid | mesh fieldsplit: GAMG, Schur (ILU(0) "
                             "velocity, BoomerAMG selfp), BoomerAMG");
  la::LinearSolver solver(comm.get(), choice.kind);
  if (iterative) {
    std::vector<PetscInt> s_rows, f_rows, m_rows;
    sys.owned_fields(s_rows, f_rows, m_rows);
    solver.set_fsi_fields(s_rows, f_rows, m_rows, sys.structure_rigid_modes(), velocity_block);
  }
  long long linear_solves = 0, linear_iterations = 0;
  // x: the held unknowns (held_unknowns, ascending; the owned ones among them from
  // first_held on).
  std::vector<double> x(sys.held_unknowns().size(), 0.0), raw;
  const auto first_held = sys.n_owned() > 0 ? sys.held_position(sys.first_owned()) : 0;
  // The owned entries of x into xv.
  const auto set_owned = [&] {
    la::Vector::LocalView view(xv, true);
    auto v = view.values();
    for (PetscInt k = 0; k < sys.n_owned(); ++k) v[k] = x[static_cast<std::size_t>(first_held + k)];
  };
  la::Vector r, dx(comm.get(), sys.n_owned()), b(comm.get(), sys.n_owned());
  la::Matrix J;
  double reference = 0.0, work = 0.0;
  // Per raw dof of the structure nodes this rank owns: the force transferred to it and its
  // displacement at the last step (the work of the transferred force).
  std::vector<double> last_force(sys.n_raw(), 0.0), last_raw(sys.n_raw(), 0.0);
  const auto start = std::chrono::steady_clock::now();
  const auto normals = interface_normals(config, sys);
  const auto& nc = config.solver.newton;
  // Dynamics: the state at t_n (from rest) and the force groups' forces at t_n.
  const bool dynamic = config.time.integrator == io::Integrator::generalized_alpha;
  FsiSystem::History history;
  if (dynamic) {
    history = FsiSystem::History::from_rho_inf(config.time.rho_inf, config.time.dt, sys.n_raw());
    sys.set_history(&history);
  }
  std::vector<std::array<double, 3>> group_force(w.groups.size(), {0.0, 0.0, 0.0});
  // Steps as the solid runs them (docs/input.md §6.3): a failed Newton attempt restores the
  // last converged state and halves the step.
  StepControl control(config.time);
  int step = 0, newton_iterations = 0;
  const auto finish = [&](bool ok) {
    // Every rank's share (CONTRACT.md, ranks_detail; output.hpp): the cells it assembles and
    // the other cells it holds (its ghost layer), the couplings' fluid facets it integrated,
    // the structure facets ghosted to it, its pairs and integration cells, its peak memory,
    // its owned nodes, the other nodes of its cells and the nodes it holds.
    parallel::mark_memory(comm.get(), "end");
    // And the unknowns a Newton iteration brings to it (held_unknowns), of all.
    constexpr std::size_t n_detail = n_rank_detail_basics + 1;
    std::vector<double> detail(static_cast<std::size_t>(comm.size()) * n_detail, 0.0);
    {
      double* mine = &detail[static_cast<std::size_t>(comm.rank()) * n_detail];
      mine[n_rank_detail_basics] = static_cast<double>(sys.held_unknowns().size());
      mine[0] = static_cast<double>(sys.local_cells().size());
      mine[1] = static_cast<double>(mesh.n_cells()) - mine[0];
      for (const auto& t : tied) {
        mine[2] += static_cast<double>(t.local_slave_facets);
        mine[3] += static_cast<double>(t.local_master_ghosts);
        mine[4] += static_cast<double>(t.local_pairs);
        mine[5] += static_cast<double>(t.local_integration_cells);
      }
      mine[6] = parallel::peak_rss_mb();
      mine[7] = static_cast<double>(part.count(mesh::CellRole::interface));
      std::vector<char> of_cells(static_cast<std::size_t>(mesh.n_nodes()), 0);
      for (auto c : sys.local_cells())
        for (auto n : mesh.cell(c)) of_cells[n] = 1;
      for (std::int32_t n = 0; n < mesh.n_nodes(); ++n) {
        if (sys.owns_node(n))
          mine[8] += 1.0;
        else if (of_cells[n])
          mine[9] += 1.0;
      }
      mine[10] = static_cast<double>(mesh.n_nodes());
    }
    comm.sum_in_place(detail);
    if (!root) return;
    io::Json j = io::Json::object();
    j["status"] = ok ? "converged" : "failed";
    j["steps"] = step;
    j["dofs"] = static_cast<std::int64_t>(info.n_dofs);
    j["ranks"] = comm.size();
    j["wall_seconds"] =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    j["newton_iterations"] = newton_iterations;
    j["linear_solver"] = solver_name;
    j["linear_solves"] = linear_solves;
    j["linear_iterations"] = linear_iterations;
    auto& tj = j["timings"];
    for (const char* phase : {"assembly", "condensation", "linear_solve", "output"})
      tj[phase] = timers.get(phase);
    j["nodes"] = static_cast<std::int64_t>(n_nodes);
    j["cells"] = static_cast<std::int64_t>(n_cells);
    auto& ranks = j["ranks_detail"];
    ranks = io::Json::array();
    for (int rk = 0; rk < comm.size(); ++rk) {
      io::Json e = io::Json::object();
      put_rank_detail_basics(e, rk, &detail[static_cast<std::size_t>(rk) * n_detail]);
      e["held_unknowns"] =
          static_cast<std::int64_t>(detail[static_cast<std::size_t>(rk) * n_detail + n_detail - 1]);
      ranks.push_back(std::move(e));
    }
    io::write_json(dir / "summary.json", j);
  };
  // The energy budget (docs/fsi.md, "Energy budget"): the powers at t_n, the works accumulated
  // to t_n (trapezoidal rule), the fluid's reactions at t_n.
  struct Powers {
    double boundary = 0.0, dissipation = 0.0, interface_fluid = 0.0, interface_structure = 0.0;
  };
  Powers power_old, work_sum;
  std::vector<double> reaction(sys.n_raw(), 0.0);
  std::vector<char> on_interface(sys.n_raw(), 0);
  for (const auto& cp : sys.couplings())
    for (auto n : cp.fluid_nodes)
      for (int i = 0; i < dim; ++i) on_interface[sys.f_dof(n, i)] = 1;
  // The state carried from step to step: the unknowns, the history of the time integration,
  // the residual scale, the reactions and powers at t_n and the works to t_n, the forces of
  // the force groups, step control and the output counters. Rank 0's copy is written (the
  // records of the tables' columns are kept on rank 0 only): x in the canonical numbering of
  // the unknowns and the reactions summed, so that any number of ranks continues.
  const auto flat = [](const auto& groups) {
    std::vector<double> out;
    for (const auto& g : groups) out.insert(out.end(), g.begin(), g.end());
    return out;
  };
  const auto powers = [](const Powers& p) {
    return std::array<double, 4>{p.boundary, p.dissipation, p.interface_fluid,
                                 p.interface_structure};
  };
  // The nodal state (the converged raw values, the reactions, the time integration's history)
  // as raw nodal vectors, each value written by the owner of its node into its part file.
  la::Vector nodal = sys.make_raw_vector();
  const auto write_checkpoint = [&] {
    const auto c = control.state();
    RecordWriter cw = checkpoints.begin(step, c.t);
    cw.put_real("control.dt", c.dt);
    cw.put_integer("control.cuts", c.cuts);
    cw.put_integer("newton.iterations", newton_iterations);
    cw.put_real("newton.reference", reference);
    const auto put_nodal = [&](const char* name, std::span<const double> values) {
      sys.raw_to_vector(values, nodal);
      checkpoints.put_vector(cw, name, nodal);
    };
    put_nodal("raw", raw);
    put_nodal("reaction", reaction);
    cw.put("power", powers(power_old));
    cw.put("work", powers(work_sum));
    cw.put_real("structure_work", work);
    put_nodal("transferred_force", last_force);
    cw.put("group_force", flat(group_force));
    if (dynamic) {
      put_nodal("history.old", history.old);
      put_nodal("history.rate", history.rate);
      put_nodal("history.accel", history.accel);
    }
    put_pvd(cw, w.pvd.get());
    checkpoints.commit(cw, step);
  };
  if (checkpoints.restarting()) {
    const auto& r = checkpoints.restart();
    // Checkpoints of fluid-structure runs before the interface sides were held in part kept
    // the transferred force per wet node in state.bin (read the same on every rank).
    if (r.has("last_force"))
      SEAM_THROW(InputError,
                 "the checkpoint was written by an earlier version of seam (its fluid-structure "
                 "state holds the interface force per wet node, 'last_force', where this version "
                 "reads the nodal 'transferred_force'): run the input from the start");
    step = checkpoints.restart_step();
    control.set_state({checkpoints.restart_time(), r.real("control.dt"),
                       static_cast<int>(r.integer("control.cuts"))});
    newton_iterations = static_cast<int>(r.integer("newton.iterations"));
    reference = r.real("newton.reference");
    const auto n_raw = sys.n_raw();
    const auto get_nodal = [&](const char* name, std::vector<double>& values) {
      checkpoints.get_vector(name, nodal);
      sys.vector_to_raw(nodal, values);
    };
    std::vector<double> state;
    get_nodal("raw", state);
    sys.unknowns_from_raw(state, x);
    // The reactions live on the owners of their nodes (FsiSystem::Result::raw_residual).
    get_nodal("reaction", reaction);
    for (std::size_t a = 0; a < n_raw; ++a)
      if (!sys.owns_raw(a)) reaction[a] = 0.0;
    const auto p = r.reals("power", 4), s = r.reals("work", 4);
    power_old = {p[0], p[1], p[2], p[3]};
    work_sum = {s[0], s[1], s[2], s[3]};
    work = r.real("structure_work");
    get_nodal("transferred_force", last_force);
    last_raw = state; // the displacement of the step written
    const auto f = r.reals("group_force", group_force.size() * 3);
    for (std::size_t k = 0; k < group_force.size(); ++k)
      for (int i = 0; i < 3; ++i) group_force[k][i] = f[k * 3 + i];
    if (dynamic) {
      get_nodal("history.old", history.old);
      get_nodal("history.rate", history.rate);
      get_nodal("history.accel", history.accel);
    }
    if (root && !quiet)
      std::printf("  restarting from %s: step %d, t = %.17g\n", restart.checkpoint.c_str(), step,
                  control.time());
  }
  set_owned();
  std::vector<double> x_converged = x;
  const double progress_wall = wall_seconds(), progress_time = control.time();
  while (control.running()) {
    const double t_old = control.time();
    const double t = control.next();
    if (dynamic) history.dt = t - control.time();
    const auto g = sys.prescribed(t);
    FsiSystem::Result res;
    double rn = 0.0;
    int it = 0;
    const char* failure = "";
    for (;; ++it) {
      sys.expand(x, g, raw);
      // The first iteration of a step assembles the Jacobian with the residual (it is rarely
      // converged); later ones assemble the residual, and the Jacobian only if it is needed.
      // The residual alone costs a fraction of the Jacobian (no shape derivatives).
      const auto evaluate = [&](la::Matrix* jacobian) {
        res = sys.assemble(raw, t, r, jacobian, {});
        timers.add("assembly", comm.max(res.assembly_seconds));
        timers.add("condensation", comm.max(res.condensation_seconds));
      };
      const bool with_jacobian = it == 0 && it < nc.max_iterations;
      evaluate(with_jacobian ? &J : nullptr);
      if (res.inverted) {
        failure = "a fluid or solid cell is inverted";
        break;
      }
      rn = r.norm();
      if (!std::isfinite(rn)) {
        failure = "the residual is not finite";
        break;
      }
      // The scale: the largest first residual so far, the reactions' level and the force level
      // of the system (the magnitudes of the element contributions), so that a state that
      // already solves the equations is not iterated at round-off.
      double level = 0.0;
      for (std::int32_t n = 0; n < mesh.n_nodes(); ++n)
        if (sys.is_fluid_node(n))
          for (int i = 0; i < dim; ++i)
            level += res.raw_residual[sys.f_dof(n, i)] * res.raw_residual[sys.f_dof(n, i)];
      level = comm.sum(level); // each rank's owned nodes
      reference = std::max({reference, it == 0 ? rn : 0.0, std::sqrt(level), res.level});
      if (root && !quiet)
        std::printf("  step %d t = %g  iteration %d  |r| = %.3e (relative %.3e)\n", step + 1, t, it,
                    rn, reference > 0 ? rn / reference : 0.0);
      if (rn <= nc.tolerance * reference || rn == 0.0) break;
      if (it >= nc.max_iterations) {
        failure = "Newton's method did not converge";
        break;
      }
      if (!with_jacobian) evaluate(&J);
      b.copy_from(r);
      b.scale(-1.0);
      bool solved = false;
      // Inexact Newton (Dembo, Eisenstat & Steihaug 1982), as for fluids: the forcing term
      // min(1e-2, |r| / |r_ref|) keeps the convergence quadratic.
      if (iterative)
        solver.set_relative_tolerance(
            std::clamp(reference > 0.0 ? rn / reference : 1e-2, 1e-10, 1e-2));
      dx.zero();
      {
        ScopedTimer timer(timers, "linear_solve");
        solved = solver.solve(J, b, dx);
      }
      ++linear_solves;
      linear_iterations += solver.last_iterations();
      if (!solved) {
        failure = iterative ? "the linear solver failed (FGMRES + fieldsplit)"
                            : "the linear solver failed (MUMPS)";
        break;
      }
      xv.axpy(1.0, dx);
      gather_held(xv, x);
    }
    newton_iterations += it;
    if (*failure != '\0') {
      x = x_converged;
      set_owned();
      if (control.cut(failure, t, comm)) continue;
      finish(false);
      SEAM_THROW(SolverError, failure, " at t = ", t, " after ", control.cuts(), " step cuts; the ",
                 step, " converged steps are written in ", dir.string());
    }
    sys.expand(x, g, raw);
    x_converged = x;
    control.accept(t);
    ++step;
    if (dynamic) {
      // The rates of the converged state become the history of the next step.
      std::vector<double> rate, accel;
      sys.rates(raw, rate, accel);
      history.old = raw;
      history.rate = std::move(rate);
      history.accel = std::move(accel);
    }
    // The powers at t_{n+1}. The fluid's reactions (the residual rows of its velocity: the force
    // of the walls, the inflow and the structure on the fluid) at t_{n+1} from the residual at
    // t_{n+alpha_f}, as for forces.csv; their power on the fluid's velocity; the power of the
    // transferred force P^T f on the structure's velocity; the dissipation and the kinetic
    // energy carried through the boundary (- convection + mesh transport, fluid::EnergyIntegrals).
    // The reactions are those of each rank's owned nodes, the powers their sums over ranks.
    Powers power;
    for (std::int32_t n = 0; n < mesh.n_nodes(); ++n)
      if (sys.is_fluid_node(n))
        for (int i = 0; i < dim; ++i) {
          const auto a = sys.f_dof(n, i);
          const double ra = res.raw_residual[a];
          reaction[a] = dynamic ? (ra - (1 - history.f_af) * reaction[a]) / history.f_af : ra;
          if (on_interface[a])
            power.interface_fluid += raw[a] * reaction[a];
          else if (sys.is_prescribed(a))
            power.boundary += raw[a] * reaction[a];
        }
    if (dynamic)
      for (const auto& cp : sys.couplings())
        for (std::size_t j = 0; j < cp.fluid_nodes.size(); ++j)
          for (int i = 0; i < dim; ++i) {
            const double f = -reaction[sys.f_dof(cp.fluid_nodes[j], i)];
            for (auto q = cp.offsets[j]; q < cp.offsets[j + 1]; ++q)
              power.interface_structure +=
                  cp.weights[q] * f * history.rate[sys.d_dof(cp.structure_nodes[q], i)];
          }
    {
      std::array<double, 3> partial{power.interface_fluid, power.boundary,
                                    power.interface_structure};
      comm.sum_in_place(partial);
      power.interface_fluid = partial[0];
      power.boundary = partial[1];
      power.interface_structure = partial[2];
    }
    const auto fluid_energy = sys.fluid_energy(raw, dynamic ? std::span<const double>(history.rate)
                                                            : std::span<const double>());
    power.boundary += fluid_energy.mesh_transport - fluid_energy.convection;
    power.dissipation = fluid_energy.dissipation;
    if (dynamic) {
      const double h = 0.5 * (t - t_old);
      work_sum.boundary += h * (power_old.boundary + power.boundary);
      work_sum.dissipation += h * (power_old.dissipation + power.dissipation);
      work_sum.interface_fluid += h * (power_old.interface_fluid + power.interface_fluid);
      work_sum.interface_structure +=
          h * (power_old.interface_structure + power.interface_structure);
    }
    power_old = power;
    // The force groups: each rank's sums over its owned nodes, summed over ranks.
    std::vector<double> group_sums;
    for (const auto& group : w.groups) {
      const auto f = fluid_force(sys, res.raw_residual, group.second);
      group_sums.insert(group_sums.end(), f.begin(), f.end());
    }
    comm.sum_in_place(group_sums);
    // The interface forces from the rows of the fluid nodes this rank owns (the raw residual is
    // summed there), summed over ranks: per coupling the normal force and the tangential force
    // vector, then the fluid's force and the one the structure receives through P^T (equal,
    // since the rows of P sum to one). The transferred force P^T f is summed on the owners of
    // the structure nodes, which take the work increment of their nodes (the trapezoidal rule
    // over the steps).
    const auto& couplings = sys.couplings();
    const std::size_t n_cp = couplings.size();
    std::vector<double> sums(n_cp * 4 + 6, 0.0);
    std::vector<double> transferred(sys.n_nodes() * dim, 0.0);
    for (std::size_t c = 0; c < n_cp; ++c) {
      const auto& cp = couplings[c];
      for (std::size_t j = 0; j < cp.fluid_nodes.size(); ++j) {
        const auto n = cp.fluid_nodes[j];
        if (!sys.owns_node(n)) continue;
        const double* nv = &normals[static_cast<std::size_t>(n) * 3];
        double fn = 0.0;
        std::array<double, 3> f{};
        for (int i = 0; i < dim; ++i) {
          f[i] = -res.raw_residual[sys.f_dof(n, i)];
          fn += f[i] * nv[i];
          sums[n_cp * 4 + i] += f[i];
          for (auto q = cp.offsets[j]; q < cp.offsets[j + 1]; ++q) {
            sums[n_cp * 4 + 3 + i] += cp.weights[q] * f[i];
            transferred[static_cast<std::size_t>(cp.structure_nodes[q]) * dim + i] +=
                cp.weights[q] * f[i];
          }
        }
        sums[c * 4] += fn;
        for (int i = 0; i < dim; ++i) sums[c * 4 + 1 + i] += f[i] - fn * nv[i];
      }
    }
    comm.sum_in_place(sums);
    transferred = sys.share(transferred, dim);
    {
      double increment = 0.0;
      for (std::size_t n = 0; n < sys.n_nodes(); ++n) {
        const auto node = static_cast<std::int32_t>(n);
        if (!sys.owns_node(node) || !sys.is_solid_node(node)) continue;
        for (int i = 0; i < dim; ++i) {
          const auto a = sys.d_dof(node, i);
          const double f = transferred[n * dim + i];
          if (f != 0.0 || last_force[a] != 0.0)
            increment += 0.5 * (f + last_force[a]) * (raw[a] - last_raw[a]);
          last_force[a] = f;
          last_raw[a] = raw[a];
        }
      }
      work += comm.sum(increment);
    }
    if (root) {
      for (std::size_t k = 0; k < w.groups.size(); ++k) {
        std::array<double, 3> f{group_sums[k * 3], group_sums[k * 3 + 1], group_sums[k * 3 + 2]};
        // Dynamics: the residual holds the force at t_{n+alpha_f}; at t_{n+1} it is
        // F_{n+1} = (F_{n+alpha_f} - (1 - alpha_f) F_n) / alpha_f (as the fluid runs).
        if (dynamic)
          for (int i = 0; i < 3; ++i)
            f[i] = (f[i] - (1 - history.f_af) * group_force[k][i]) / history.f_af;
        group_force[k] = f;
        w.forces->add_row({step, t, w.groups[k].first, f[0], f[1], f[2]});
      }
      for (std::size_t c = 0; c < n_cp; ++c) {
        const double* tv = &sums[c * 4 + 1];
        w.interfaces->add_row({step, t, couplings[c].name, sums[c * 4],
                               std::sqrt(tv[0] * tv[0] + tv[1] * tv[1] + tv[2] * tv[2]), 0, 0,
                               couplings[c].d_total});
      }
      const double* ff = &sums[n_cp * 4];
      const double* fs = &sums[n_cp * 4 + 3];
      const double wall =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      // clang-format off
      w.steps->add_row({step, t, it, rn, 0, 0, res.kinetic_energy, res.strain_energy, work,
                        res.kinetic_energy + res.strain_energy, 0, 0, 0, 0, 0, 0, wall,
                        ff[0], ff[1], ff[2], fs[0], fs[1], fs[2], fluid_energy.kinetic,
                        work_sum.dissipation, work_sum.boundary, work_sum.interface_fluid,
                        work_sum.interface_structure});
      // clang-format on
      if (!quiet)
        print_step_line(
            step, t, it, rn / std::max(reference, 1e-300), wall,
            time_left(wall_seconds() - progress_wall, t - progress_time, config.time.end - t));
    }
    {
      ScopedTimer timer(timers, "output");
      if (!w.probe_at.empty()) write_probes(sys, raw, step, t, w);
      // Fields and the interface rows every `output.every` steps and at the end.
      if (step % config.output.every == 0 || !control.running()) {
        write_interfaces(sys, raw, res.raw_residual, normals, dir);
        write_fields(sys, raw, step, t, w);
      }
    }
    if (checkpoints.due(step)) write_checkpoint();
  }
  finish(true);
  if (root && !quiet)
    std::printf("seam: %d steps, %d Newton iterations; wall time in assembly %.3g s, "
                "condensation %.3g s, linear solves %.3g s, output %.3g s\n",
                step, newton_iterations, timers.get("assembly"), timers.get("condensation"),
                timers.get("linear_solve"), timers.get("output"));
  return info;
}

} // namespace seam::fsi
