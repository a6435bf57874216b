#include "seam/flow/fluid_output.hpp"

#include "seam/common/collective.hpp"
#include "seam/problem/checkpoint.hpp"

#include "seam/fluid/navier_stokes.hpp"
#include "seam/io/json.hpp"
#include "seam/mesh/locate.hpp"
#include "seam/parallel/memory_trace.hpp"
#include "seam/problem/output.hpp"
#include "seam/problem/progress.hpp"

#include <cstdio>

namespace seam::flow {

using problem::Checkpoints;
using problem::locate_probe;
using problem::n_rank_detail_basics;
using problem::print_step_line;
using problem::put_rank_detail_basics;
using problem::RecordWriter;
using problem::time_left;
using problem::write_step_fields;

FluidOutput::FluidOutput(const io::Config& config, const FluidLayout& layout,
                         const FluidModel& model, std::filesystem::path dir, bool quiet,
                         const Checkpoints* restart)
    : config_(config), layout_(layout), model_(model), dir_(std::move(dir)), quiet_(quiet),
      start_wall_(wall_seconds()), start_time_(restart ? restart->restart_time() : 0.0) {
  // A restart's tables may refuse to continue (another header): every rank stops.
  on_root_collectively(layout.comm(), [&] {
    // A restart continues the tables (rows after its step dropped).
    const auto mode = [&](const char* file) {
      return restart ? restart->table_mode(dir_ / file) : io::CsvTable::Mode::truncate;
    };
    // steps.csv keeps the solid's columns (energies and momenta are those of a structure,
    // none here).
    steps_ = std::make_unique<io::CsvTable>(
        dir_ / "steps.csv",
        std::vector<std::string>{"step", "time", "newton_iterations", "residual", "active_nodes",
                                 "slip_nodes", "kinetic_energy", "internal_energy", "external_work",
                                 "total_energy", "momentum_x", "momentum_y", "momentum_z",
                                 "angular_momentum_x", "angular_momentum_y", "angular_momentum_z",
                                 "wall_seconds"},
        mode("steps.csv"));
    newton_ =
        std::make_unique<io::CsvTable>(dir_ / "newton.csv",
                                       std::vector<std::string>{"step", "iteration", "residual",
                                                                "increment", "active_set_changes"},
                                       mode("newton.csv"));
    forces_ = std::make_unique<io::CsvTable>(
        dir_ / "forces.csv", std::vector<std::string>{"step", "time", "name", "fx", "fy", "fz"},
        mode("forces.csv"));
    if (!config.output.exact_velocity.empty() || !config.output.exact_pressure.empty())
      errors_ = std::make_unique<io::CsvTable>(
          dir_ / "errors.csv",
          std::vector<std::string>{"step", "time", "velocity_l2_error", "pressure_l2_error"},
          mode("errors.csv"));
    probes_ = std::make_unique<io::CsvTable>(dir_ / "probes.csv",
                                             std::vector<std::string>{"step", "time", "probe", "x",
                                                                      "y", "z", "ux", "uy", "uz",
                                                                      "vx", "vy", "vz", "pressure"},
                                             mode("probes.csv"));
    pvd_ = std::make_unique<io::PvdCollection>(dir_ / "results.pvd",
                                               restart ? restart->pvd_entries(dir_)
                                                       : std::vector<io::PvdCollection::Entry>{});
  });
  // The piece of this rank: its cells over the nodes they touch (owned or ghost here).
  const auto& cells_mesh = layout.mesh();
  grid_.emplace(cells_mesh, layout.local_cells(), layout.comm().rank());
  // Probes: the rank whose cell the whole-mesh search would pick evaluates each (output.hpp).
  for (const auto& p : config.output.probes) {
    const auto loc = locate_probe(
        cells_mesh, layout.local_cells(), [&](std::int32_t c) { return layout.cell_gid(c); }, p,
        layout.comm());
    located_.push_back({p.point, loc.cell, loc.xi});
  }
}

FluidOutput::~FluidOutput() = default;

namespace {

// Velocity (3 values) and pressure at reference point xi of cell c (local or touching a
// local cell's nodes only) from the local vector form.
std::array<double, 4> evaluate_at(const FluidLayout& layout, std::span<const double> local,
                                  std::int32_t c, const double* xi) {
  const auto& mesh = layout.mesh();
  const int dim = mesh.dim;
  const auto type = mesh.cell_type[c];
  const auto nodes = mesh.cell(c);
  std::array<double, fem::max_cell_nodes> N{};
  std::array<double, 8> M{};
  fem::shape_values(type, xi, N.data());
  fem::shape_values(fluid::pressure_cell(type), xi, M.data());
  std::array<double, 4> out{};
  for (std::size_t a = 0; a < nodes.size(); ++a)
    for (int i = 0; i < dim; ++i) out[i] += N[a] * local[layout.local_dof(nodes[a], i)];
  for (int k = 0; k < fem::n_vertices(type); ++k)
    out[3] += M[k] * local[layout.local_dof(nodes[k], dim)];
  return out;
}

} // namespace

void FluidOutput::newton(int step, int iteration, double residual, double increment) {
  if (!layout_.comm().is_root()) return;
  newton_->add_row({step, iteration, residual, increment, 0});
}

void FluidOutput::step(const FluidStepRecord& r, const la::Vector& w,
                       std::span<const double> mesh_displacement, bool force_fields) {
  ScopedTimer timer(timers_, "output");
  const bool due = force_fields || r.step % config_.output.every == 0;
  // Probes: the rank of the probe's cell evaluates (velocity, pressure, mesh displacement),
  // then the values are summed over the ranks.
  std::vector<double> probe(located_.size() * 7, 0.0);
  {
    la::Vector::LocalView view(w, false);
    if (due) write_fields(r.step, r.time, view.values(), mesh_displacement);
    const auto& mesh = layout_.mesh();
    for (std::size_t k = 0; k < located_.size(); ++k) {
      const auto& pr = located_[k];
      if (pr.cell < 0) continue;
      const auto v = evaluate_at(layout_, view.values(), pr.cell, pr.xi.data());
      double* out = &probe[k * 7];
      for (int i = 0; i < 4; ++i) out[3 + i] = v[i];
      if (mesh_displacement.empty()) continue;
      const auto nodes = mesh.cell(pr.cell);
      std::array<double, fem::max_cell_nodes> N{};
      fem::shape_values(mesh.cell_type[pr.cell], pr.xi.data(), N.data());
      for (std::size_t a = 0; a < nodes.size(); ++a)
        for (int i = 0; i < mesh.dim; ++i)
          out[i] += N[a] * mesh_displacement[nodes[a] * mesh.dim + i];
    }
  }
  layout_.comm().sum_in_place(probe);
  last_errors_ = r.errors;
  last_forces_ = r.forces;
  if (!layout_.comm().is_root()) return;
  const double wall = wall_seconds() - start_wall_;
  steps_->add_row({r.step, r.time, r.newton_iterations, r.residual, 0, 0, 0.0, 0.0, 0.0, 0.0, 0.0,
                   0.0, 0.0, 0.0, 0.0, 0.0, wall});
  for (std::size_t k = 0; k < r.forces.size(); ++k)
    forces_->add_row(
        {r.step, r.time, model_.forces[k].name, r.forces[k][0], r.forces[k][1], r.forces[k][2]});
  for (std::size_t k = 0; k < located_.size(); ++k) {
    const auto& pt = located_[k].point;
    const double* v = &probe[k * 7];
    probes_->add_row({r.step, r.time, static_cast<int>(k), pt[0], pt[1], pt[2], v[0], v[1], v[2],
                      v[3], v[4], v[5], v[6]});
  }
  if (errors_ && r.errors)
    errors_->add_row({r.step, r.time, r.errors->velocity_l2, r.errors->pressure_l2});
  if (!quiet_)
    print_step_line(
        r.step, r.time, r.newton_iterations, r.residual, wall,
        time_left(wall_seconds() - start_wall_, r.time - start_time_, config_.time.end - r.time));
}

std::vector<double> FluidOutput::nodal_pressure(std::span<const double> local) const {
  const auto& mesh = layout_.mesh();
  std::vector<double> pressure(grid_->nodes.size(), 0.0);
  // The pressure is linear on each cell: its value at a node that is not a vertex is that of
  // the linear interpolant of the cell's vertices there.
  std::size_t next = 0;
  for (auto c : layout_.local_cells()) {
    const auto type = mesh.cell_type[c];
    const auto xi = fem::reference_nodes(type);
    for (int k : fem::vtk_node_order(type))
      pressure[grid_->connectivity[next++]] = evaluate_at(layout_, local, c, &xi[k * mesh.dim])[3];
  }
  return pressure;
}

void FluidOutput::write_fields(int step, double time, std::span<const double> local,
                               std::span<const double> mesh_displacement) {
  const auto& mesh = layout_.mesh();
  const int dim = mesh.dim;
  const auto n = grid_->nodes.size();
  std::vector<double> points(n * dim), velocity(n * 3, 0.0), displacement(n * 3, 0.0);
  for (std::size_t p = 0; p < n; ++p) {
    const auto node = grid_->nodes[p];
    for (int i = 0; i < dim; ++i) {
      points[p * dim + i] = mesh.x[static_cast<std::size_t>(node) * dim + i];
      velocity[p * 3 + i] = local[layout_.local_dof(node, i)];
      if (!mesh_displacement.empty())
        displacement[p * 3 + i] = mesh_displacement[static_cast<std::size_t>(node) * dim + i];
    }
  }
  const auto pressure = nodal_pressure(local);
  auto piece = grid_->piece(dim, points, time, step);
  piece.point_data.emplace_back("velocity", 3, std::span<const double>(velocity));
  piece.point_data.emplace_back("pressure", 1, std::span<const double>(pressure));
  piece.point_data.emplace_back("mesh_displacement", 3, std::span<const double>(displacement));
  const auto file = write_step_fields(dir_, step, piece, layout_.comm());
  if (layout_.comm().is_root()) pvd_->add(time, file);
}

void FluidOutput::finish(bool converged, int n_steps) {
  const auto& comm = layout_.comm();
  const double wall = comm.max(wall_seconds() - start_wall_);
  std::vector<double> phases;
  const char* names[] = {"assembly", "linear_solve", "output"};
  for (const char* n : names) phases.push_back(comm.max(timers_.get(n)));
  // Every rank's share (CONTRACT.md, ranks_detail; output.hpp): the cells it assembles and
  // the other cells it holds, the tied interfaces' counts, its peak memory, the cells it holds
  // only for an interface side, its owned and ghost nodes and the nodes it holds.
  parallel::mark_memory(comm.get(), "end");
  constexpr std::size_t n_detail = n_rank_detail_basics;
  std::vector<double> detail(static_cast<std::size_t>(comm.size()) * n_detail, 0.0);
  {
    const auto& mesh = layout_.mesh();
    double* mine = &detail[static_cast<std::size_t>(comm.rank()) * n_detail];
    mine[0] = static_cast<double>(layout_.local_cells().size());
    mine[1] = static_cast<double>(mesh.n_cells()) - mine[0];
    for (std::size_t k = 0; k < 4; ++k) mine[2 + k] = interface_counts_[k];
    mine[6] = parallel::peak_rss_mb();
    if (const auto* part = layout_.part())
      mine[7] = static_cast<double>(part->count(mesh::CellRole::interface));
    for (std::int32_t n = 0; n < mesh.n_nodes(); ++n) {
      if (layout_.owns_node(n))
        mine[8] += 1.0;
      else if (layout_.local_dof(n, 0) >= 0)
        mine[9] += 1.0;
    }
    mine[10] = static_cast<double>(mesh.n_nodes());
  }
  comm.sum_in_place(detail);
  if (!comm.is_root()) return;
  io::Json j = io::Json::object();
  j["status"] = converged ? "converged" : "failed";
  j["steps"] = n_steps;
  j["dofs"] = static_cast<std::int64_t>(layout_.n_global_dofs());
  j["ranks"] = comm.size();
  j["wall_seconds"] = wall;
  // Newton's linear solves and their iterations (a direct solve counts one).
  if (!linear_solver_.empty()) j["linear_solver"] = linear_solver_;
  j["linear_solves"] = linear_solves_;
  j["linear_iterations"] = linear_iterations_;
  auto& t = j["timings"];
  for (std::size_t k = 0; k < phases.size(); ++k) t[names[k]] = phases[k];
  j["nodes"] = layout_.n_global_nodes();
  j["cells"] = layout_.n_global_cells();
  auto& ranks = j["ranks_detail"];
  ranks = io::Json::array();
  for (int r = 0; r < comm.size(); ++r) {
    io::Json e = io::Json::object();
    put_rank_detail_basics(e, r, &detail[static_cast<std::size_t>(r) * n_detail]);
    ranks.push_back(std::move(e));
  }
  auto& forces = j["forces"];
  forces = io::Json::array();
  for (std::size_t k = 0; k < last_forces_.size(); ++k) {
    io::Json e = io::Json::object();
    e["name"] = model_.forces[k].name;
    e["fx"] = last_forces_[k][0];
    e["fy"] = last_forces_[k][1];
    e["fz"] = last_forces_[k][2];
    forces.push_back(std::move(e));
  }
  if (last_errors_) {
    j["errors"]["velocity_l2"] = last_errors_->velocity_l2;
    j["errors"]["pressure_l2"] = last_errors_->pressure_l2;
  }
  io::write_json(dir_ / "summary.json", j);
}

void FluidOutput::write_checkpoint(RecordWriter& out) const {
  put_pvd(out, pvd_.get());
}

} // namespace seam::flow
