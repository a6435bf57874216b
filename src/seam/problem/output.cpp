#include "seam/problem/output.hpp"
#include "seam/problem/progress.hpp"

#include "seam/common/collective.hpp"
#include "seam/problem/checkpoint.hpp"

#include "seam/common/error.hpp"
#include "seam/fem/cell.hpp"
#include "seam/io/json.hpp"
#include "seam/mesh/locate.hpp"
#include "seam/parallel/exchange.hpp"
#include "seam/parallel/load_balance.hpp"
#include "seam/parallel/memory_trace.hpp"
#include "seam/problem/error_norms.hpp"
#include "seam/solid/element.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace seam::problem {

namespace {

/// A rank's answer for one probe: how far outside its cell (0 inside, to round-off) and the
/// cell's id; ordered as the whole-mesh search chooses.
struct ProbeCandidate {
  double distance;
  std::int64_t gid;
  bool operator<(const ProbeCandidate& o) const {
    return distance < o.distance || (distance == o.distance && gid < o.gid);
  }
};

double probe_distance(const mesh::Mesh& mesh, const mesh::PointLocation& loc) {
  const double d = mesh::reference_distance(mesh.cell_type[loc.cell], loc.xi.data());
  return d <= 1e-13 ? 0.0 : d; // PointLocator's "inside up to round-off"
}

std::vector<std::string> columns(std::initializer_list<const char*> names) {
  return {names.begin(), names.end()};
}

} // namespace

double time_left(double elapsed, double simulated, double remaining) {
  return simulated > 0.0 ? elapsed / simulated * std::max(remaining, 0.0) : -1.0;
}

std::string duration_text(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0) return "?";
  char buf[32];
  const auto s = static_cast<long long>(std::llround(seconds));
  if (s < 60)
    std::snprintf(buf, sizeof buf, "%lld s", s);
  else if (s < 3600)
    std::snprintf(buf, sizeof buf, "%lld min %02lld s", s / 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%lld h %02lld min", s / 3600, (s % 3600) / 60);
  return buf;
}

void print_step_line(int step, double t, int newton_iterations, double residual, double wall,
                     double left) {
  std::printf("step %5d  t = %-12.6g newton %3d  residual %9.3e  wall %8.2f s  left %s\n", step, t,
              newton_iterations, residual, wall, duration_text(left).c_str());
  std::fflush(stdout);
}

std::string write_step_fields(const std::filesystem::path& dir, int step, const io::VtuPiece& piece,
                              Comm comm) {
  if (comm.size() == 1) {
    auto file = io::step_file_name("results", step, ".vtu");
    io::write_vtu(dir / file, piece);
    return file;
  }
  io::write_vtu(dir / io::piece_file_name("results", step, comm.rank()), piece);
  comm.barrier();
  auto file = io::step_file_name("results", step, ".pvtu");
  if (comm.is_root()) {
    std::vector<std::string> pieces;
    for (int r = 0; r < comm.size(); ++r) pieces.push_back(io::piece_file_name("results", step, r));
    io::write_pvtu(dir / file, piece, pieces);
  }
  return file;
}

void put_rank_detail_basics(io::Json& e, int rank, const double* d) {
  e["rank"] = rank;
  const char* names[] = {"cells",       "ghost_cells",       "slave_elements", "master_ghosts",
                         "pairs",       "integration_cells", nullptr,          "interface_cells",
                         "owned_nodes", "ghost_nodes",       "nodes"};
  for (std::size_t k = 0; k < n_rank_detail_basics; ++k)
    if (names[k]) e[names[k]] = static_cast<std::int64_t>(d[k]);
  e["peak_rss_mb"] = d[6];
}

LocatedProbe locate_probe(const mesh::Mesh& mesh, std::span<const std::int32_t> cells,
                          const std::function<std::int64_t(std::int32_t)>& cell_gid,
                          const io::Probe& probe, Comm comm) {
  const mesh::PointLocator locator(mesh, cells);
  const auto loc = locator.locate(std::span<const double>(probe.point.data(), mesh.dim), 1e-10);
  const ProbeCandidate mine = loc ? ProbeCandidate{probe_distance(mesh, *loc), cell_gid(loc->cell)}
                                  : ProbeCandidate{std::numeric_limits<double>::infinity(), -1};
  std::vector<std::int64_t> offsets;
  const auto all = parallel::allgatherv<ProbeCandidate>(
      comm.get(), std::span<const ProbeCandidate>(&mine, 1), offsets);
  const auto best = std::min_element(all.begin(), all.end());
  if (best->gid < 0) {
    std::ostringstream s;
    s << "probe (" << probe.point[0] << ", " << probe.point[1];
    if (mesh.dim == 3) s << ", " << probe.point[2];
    s << ") lies outside the mesh";
    io::fail_at(probe.mark, s.str());
  }
  if (best - all.begin() != comm.rank()) return {probe.point, -1, {}};
  return {probe.point, loc->cell, loc->xi};
}

Output::Output(const io::Config& config, const Discretization& disc, const Model& model,
               const std::vector<meshtying::TiedInterface>& tied, std::filesystem::path dir,
               bool quiet, const Checkpoints* restart)
    : config_(config), disc_(disc), model_(model), tied_(tied), dir_(std::move(dir)), quiet_(quiet),
      start_wall_(wall_seconds()), progress_wall_(start_wall_) {
  for (const auto& itf : config.interfaces)
    has_contact_ = has_contact_ || itf.type == io::InterfaceType::contact;
  const auto& comm = disc.comm();
  const auto& mesh = disc.mesh();
  // A slave node is tied if it has a row of D and not every component is prescribed (known on
  // the rank that owns the node; only owned nodes are read).
  for (const auto& t : tied_) {
    const auto& nodes = t.slave.mesh_nodes;
    std::vector<int> n_prescribed(nodes.size(), 0);
    for (const auto& d : model.dirichlet) {
      const auto it = std::lower_bound(nodes.begin(), nodes.end(), d.node);
      if (it != nodes.end() && *it == d.node) ++n_prescribed[it - nodes.begin()];
    }
    auto& rows = tied_rows_.emplace_back(nodes.size(), 0);
    for (const auto& e : t.operators.D)
      if (e.value != 0.0 && n_prescribed[e.row] < mesh.dim) rows[e.row] = 1;
  }

  // Probes: every rank looks among the cells it assembles, which together are the mesh; the
  // cell the whole-mesh search would pick (inside, then lowest id; else the nearest within the
  // tolerance) wins, and its rank evaluates the probe.
  for (const auto& p : config.output.probes) {
    probes_.push_back(locate_probe(
        mesh, disc.local_cells(), [&](std::int32_t c) { return disc.cell_gid(c); }, p, comm));
  }

  // A restart's tables may refuse to continue (another header): every rank stops.
  on_root_collectively(comm, [&] {
    std::error_code ec;
    std::filesystem::create_directories(dir_, ec);
    if (ec)
      SEAM_THROW(InputError, "cannot create the output directory ", dir_.string(), ": ",
                 ec.message());
    // A restart continues the tables (rows after its step dropped).
    const auto mode = [&](const char* file) {
      return restart ? restart->table_mode(dir_ / file) : io::CsvTable::Mode::truncate;
    };
    steps_ = std::make_unique<io::CsvTable>(
        dir_ / "steps.csv",
        columns({"step", "time", "newton_iterations", "residual", "active_nodes", "slip_nodes",
                 "kinetic_energy", "internal_energy", "external_work", "total_energy", "momentum_x",
                 "momentum_y", "momentum_z", "angular_momentum_x", "angular_momentum_y",
                 "angular_momentum_z", "wall_seconds"}),
        mode("steps.csv"));
    newton_ = std::make_unique<io::CsvTable>(
        dir_ / "newton.csv",
        columns({"step", "iteration", "residual", "increment", "active_set_changes"}),
        mode("newton.csv"));
    reactions_ = std::make_unique<io::CsvTable>(
        dir_ / "reactions.csv", columns({"step", "time", "region", "fx", "fy", "fz"}),
        mode("reactions.csv"));
    probes_table_ = std::make_unique<io::CsvTable>(
        dir_ / "probes.csv", columns({"step", "time", "probe", "x", "y", "z", "ux", "uy", "uz"}),
        mode("probes.csv"));
    interfaces_ = std::make_unique<io::CsvTable>(
        dir_ / "interfaces.csv",
        columns({"step", "time", "interface", "normal_force", "tangential_force", "active_nodes",
                 "slip_nodes", "contact_area", "frictional_dissipation"}),
        mode("interfaces.csv"));
    if (has_contact_)
      parallel_ = std::make_unique<io::CsvTable>(
          dir_ / "parallel.csv",
          columns({"step", "time", "interface", "ranks", "min_work", "mean_work", "max_work",
                   "imbalance", "redistributed"}),
          mode("parallel.csv"));
    pvd_ = std::make_unique<io::PvdCollection>(dir_ / "results.pvd",
                                               restart ? restart->pvd_entries(dir_)
                                                       : std::vector<io::PvdCollection::Entry>{});
    if (!config.output.exact_displacement.empty())
      errors_ = std::make_unique<io::CsvTable>(
          dir_ / "errors.csv", columns({"step", "time", "l2_error", "h1_error", "l2_exact"}),
          mode("errors.csv"));
  });
  comm.barrier(); // the directory exists before any rank writes a piece
  if (restart) progress_time_ = restart->restart_time();

  for (const auto& t : tied) {
    std::vector<PetscInt> dofs;
    for (const auto node : t.slave.mesh_nodes)
      for (int c = 0; c < disc.dim(); ++c) dofs.push_back(disc.global_dof(node, c));
    if (t.distributed) { // the master nodes the rows of M reach, by global number
      for (const auto index : t.master_index)
        for (int c = 0; c < disc.dim(); ++c)
          dofs.push_back(static_cast<PetscInt>(index) * disc.dim() + c);
    } else {
      for (const auto node : t.master.mesh_nodes)
        for (int c = 0; c < disc.dim(); ++c) dofs.push_back(disc.global_dof(node, c));
    }
    tied_gather_.emplace_back(disc.make_vector(), dofs);
  }

  // The VTU topology of this rank's piece: its local cells over its local nodes.
  std::vector<std::int32_t> point_of(static_cast<std::size_t>(mesh.n_nodes()), -1);
  for (std::int32_t n = 0; n < mesh.n_nodes(); ++n)
    if (disc.local_dof(n, 0) >= 0) point_of[n] = disc.local_dof(n, 0) / disc.dim();
  grid_.emplace(mesh, disc.local_cells(), comm.rank(), std::move(point_of));
  for (auto c : disc.local_cells()) cell_material_.push_back(model.cell_material[c]);
}

Output::~Output() = default;

void Output::warning(const std::string& message) const {
  if (disc_.comm().is_root() && !quiet_)
    std::fprintf(stderr, "seam: warning: %s\n", message.c_str());
}

void Output::note(const std::string& message) const {
  if (disc_.comm().is_root() && !quiet_) std::printf("  %s\n", message.c_str());
}

void Output::newton(const NewtonRecord& r) {
  if (!disc_.comm().is_root()) return;
  newton_->add_row({r.step, r.iteration, r.residual, r.increment, r.active_set_changes});
  // With contact, the iterations of every step as in the seed's Table 1: the active set
  // changes are marked.
  if (has_contact_ && !quiet_)
    std::printf("  step %5d  iteration %3d  residual %9.3e  increment %9.3e  %s\n", r.step,
                r.iteration, r.residual, r.increment,
                r.active_set_changes > 0
                    ? ("* active set: " + std::to_string(r.active_set_changes) + " changes").c_str()
                    : "");
}

void Output::initial(const la::Vector& u) {
  std::vector<InterfaceState> states(tied_.size());
  for (std::size_t k = 0; k < tied_.size(); ++k) {
    const auto n = tied_[k].slave.mesh_nodes.size() * disc_.dim();
    states[k].lambda.assign(n, 0.0);
    states[k].gap.assign(n / disc_.dim(), 0.0);
    states[k].displacement.assign(n, 0.0);
  }
  write_fields(0, 0.0, u, nullptr, states);
  progress_wall_ = wall_seconds();
  progress_time_ = 0.0;
}

std::vector<Output::InterfaceState>
Output::interface_states(const la::Vector& u, const std::vector<std::vector<double>>& multipliers,
                         bool node_rows) const {
  std::vector<InterfaceState> states;
  if (tied_.empty()) return states;
  const int dim = disc_.dim();
  std::vector<double> values;
  for (std::size_t k = 0; k < tied_.size(); ++k) {
    const auto& t = tied_[k];
    InterfaceState s;
    s.lambda = multipliers[k];
    const auto n_slave = t.slave.mesh_nodes.size();
    // The slave nodes' displacements, then the master nodes'.
    tied_gather_[k](u, values);
    s.displacement.assign(values.begin(),
                          values.begin() + static_cast<std::ptrdiff_t>(n_slave * dim));
    const double* u_master = values.data() + n_slave * dim;
    // Weighted constraint residual D u~_S - M u_M, its part along the slave normal; with a
    // modified slave basis (tri6/quad8 dual) D acts on the coefficients u~_S = T^-1 u_S.
    std::vector<double> us = s.displacement;
    if (!t.operators.T.empty()) {
      std::vector<char> has_row(n_slave, 0);
      const auto T_inverse = mortar::inverse_transformation(t.operators.T);
      for (const auto& e : T_inverse) has_row[static_cast<std::size_t>(e.row)] = 1;
      for (std::size_t j = 0; j < n_slave; ++j)
        if (has_row[j])
          for (int c = 0; c < dim; ++c) us[j * dim + c] = 0.0;
      for (const auto& e : T_inverse)
        for (int c = 0; c < dim; ++c)
          us[static_cast<std::size_t>(e.row) * dim + c] +=
              e.value * s.displacement[static_cast<std::size_t>(e.col) * dim + c];
    }
    std::vector<double> g(n_slave * dim, 0.0);
    for (const auto& e : t.operators.D)
      for (int c = 0; c < dim; ++c) g[e.row * dim + c] += e.value * us[e.col * dim + c];
    for (const auto& e : t.operators.M)
      for (int c = 0; c < dim; ++c)
        g[e.row * dim + c] -= e.value * u_master[static_cast<std::size_t>(e.col) * dim + c];
    s.gap.assign(n_slave, 0.0);
    for (std::size_t j = 0; j < n_slave; ++j)
      for (int c = 0; c < dim; ++c)
        s.gap[j] += g[j * dim + c] * t.operators.nodal_normals[j * dim + c];
    summarize(k, s, node_rows);
    states.push_back(std::move(s));
  }
  return states;
}

void Output::summarize(std::size_t k, InterfaceState& s, bool node_rows) const {
  const auto& t = tied_[k];
  const auto& comm = disc_.comm();
  const auto& mesh = disc_.mesh();
  const int dim = disc_.dim();
  const auto& normals = t.operators.nodal_normals;
  const auto n_slave = t.slave.mesh_nodes.size();
  // Interface force on the slave nodes from the multipliers, F = D^T lambda, from the rows of
  // the nodes this rank owns, summed on the owners of the columns; its normal part along the
  // slave nodal normals and the magnitude of the rest.
  std::vector<double> force(n_slave * dim, 0.0);
  std::vector<std::int64_t> keys(n_slave);
  std::vector<int> owners(n_slave);
  for (std::size_t j = 0; j < n_slave; ++j) {
    keys[j] = disc_.global_dof(t.slave.mesh_nodes[j], 0);
    owners[j] = disc_.node_owner(t.slave.mesh_nodes[j]);
  }
  for (const auto& e : t.operators.D)
    if (owners[e.row] == comm.rank())
      for (int c = 0; c < dim; ++c) force[e.col * dim + c] += e.value * s.lambda[e.row * dim + c];
  parallel::sum_on_owners(comm.get(), keys, owners, force, dim);
  double totals[4] = {0.0, 0.0, 0.0, 0.0}; // fn, ft (3)
  double tied = 0.0;
  std::vector<InterfaceNodeRow> rows;
  for (std::size_t j = 0; j < n_slave; ++j) {
    if (owners[j] != comm.rank()) continue;
    tied += tied_rows_[k][j];
    double fj_n = 0.0;
    for (int c = 0; c < dim; ++c) fj_n += force[j * dim + c] * normals[j * dim + c];
    totals[0] += fj_n;
    for (int c = 0; c < dim; ++c) totals[1 + c] += force[j * dim + c] - fj_n * normals[j * dim + c];
    if (!node_rows) continue;
    InterfaceNodeRow row;
    const auto node = t.slave.mesh_nodes[j];
    row.node = disc_.node_gid(node);
    row.order = row.node;
    double ln = 0.0, lt2 = 0.0;
    for (int c = 0; c < dim; ++c) {
      row.x[c] = mesh.x[static_cast<std::size_t>(node) * dim + c];
      row.u[c] = s.displacement[j * dim + c];
      ln += s.lambda[j * dim + c] * normals[j * dim + c];
    }
    for (int c = 0; c < dim; ++c) {
      const double lt = s.lambda[j * dim + c] - ln * normals[j * dim + c];
      lt2 += lt * lt;
    }
    row.gap = s.gap[j];
    row.normal = ln;
    row.tangential = std::sqrt(lt2);
    row.status = tied_rows_[k][j] ? InterfaceNodeRow::tied : InterfaceNodeRow::inactive;
    rows.push_back(row);
  }
  comm.sum_in_place(totals);
  s.normal_force = totals[0];
  s.tangential_force =
      std::sqrt(totals[1] * totals[1] + totals[2] * totals[2] + totals[3] * totals[3]);
  s.tied = static_cast<int>(std::lround(comm.sum(tied)));
  if (node_rows) s.rows = rows_on_root(comm, rows); // in the order of the node ids
}

std::vector<InterfaceNodeRow> rows_on_root(const Comm& comm,
                                           const std::vector<InterfaceNodeRow>& rows) {
  std::vector<std::int64_t> offsets(static_cast<std::size_t>(comm.size()) + 1,
                                    static_cast<std::int64_t>(rows.size()));
  offsets[0] = 0;
  std::vector<std::int64_t> recv_offsets;
  auto out = parallel::alltoallv<InterfaceNodeRow>(comm.get(), rows, offsets, recv_offsets);
  std::sort(out.begin(), out.end(),
            [](const InterfaceNodeRow& a, const InterfaceNodeRow& b) { return a.order < b.order; });
  return out;
}

void Output::write_node_rows(const std::string& name,
                             const std::vector<InterfaceNodeRow>& rows) const {
  // Status per CONTRACT.md: inactive / stick / slip (without friction every active node
  // slips); tied for a mesh-tying node with a row of D.
  static constexpr const char* status_names[] = {"inactive", "stick", "slip", "tied"};
  io::CsvTable table(dir_ / ("interface_" + name + ".csv"),
                     columns({"node", "x", "y", "z", "ux", "uy", "uz", "gap", "normal_traction",
                              "tangential_traction", "status"}));
  for (const auto& row : rows)
    table.add_row({row.node, row.x[0], row.x[1], row.x[2], row.u[0], row.u[1], row.u[2], row.gap,
                   row.normal, row.tangential, status_names[row.status]});
}

void Output::write_interfaces(const StepRecord& r, const std::vector<InterfaceState>& states,
                              const std::vector<std::vector<InterfaceNodeRow>>& contact_rows,
                              bool write_nodes) {
  for (std::size_t k = 0; k < contact_.size(); ++k) {
    const auto& c = contact_[k];
    interfaces_->add_row({r.step, r.time, c.name, c.normal_force, c.tangential_force,
                          c.active_nodes, c.slip_nodes, c.contact_area, c.frictional_dissipation});
    const parallel::WorkStats work{c.work_min, c.work_mean, c.work_max};
    parallel_->add_row({r.step, r.time, c.name, disc_.comm().size(), c.work_min, c.work_mean,
                        c.work_max, work.imbalance(), c.redistributed ? 1 : 0});
    if (write_nodes) write_node_rows(c.name, contact_rows[k]);
  }
  for (std::size_t k = 0; k < tied_.size(); ++k) {
    const auto& t = tied_[k];
    const auto& s = states[k];
    interfaces_->add_row({r.step, r.time, t.name, s.normal_force, s.tangential_force, s.tied, 0,
                          t.operators.integrated_area, 0.0});
    if (write_nodes) write_node_rows(t.name, s.rows);
  }
}

void Output::step(const StepRecord& r, const la::Vector& u, const la::Vector* v,
                  std::span<const double> reactions,
                  const std::vector<std::vector<double>>& multipliers, bool force_fields) {
  ScopedTimer timer(timers_, "output");
  const auto& comm = disc_.comm();
  const int dim = disc_.dim();
  const double wall = wall_seconds() - start_wall_;

  // Probes: interpolate on the rank that owns the probe's cell, then sum over ranks.
  std::vector<double> probe_u(probes_.size() * 3, 0.0);
  {
    la::Vector::LocalView view(u, false);
    const auto ul = view.values();
    std::array<double, fem::max_cell_nodes> N{};
    for (std::size_t p = 0; p < probes_.size(); ++p) {
      const auto c = probes_[p].cell;
      if (c < 0) continue; // evaluated on another rank
      const auto type = disc_.mesh().cell_type[c];
      fem::shape_values(type, probes_[p].xi.data(), N.data());
      const auto nodes = disc_.mesh().cell(c);
      for (std::size_t a = 0; a < nodes.size(); ++a)
        for (int i = 0; i < dim; ++i) probe_u[p * 3 + i] += N[a] * ul[disc_.local_dof(nodes[a], i)];
    }
  }
  comm.sum_in_place(probe_u);
  std::optional<ErrorNorms> errors;
  if (!config_.output.exact_displacement.empty())
    errors = error_norms(disc_, u, r.time, config_.output.exact_displacement);

  if (comm.is_root()) {
    const double total = r.kinetic_energy + r.internal_energy;
    steps_->add_row({r.step, r.time, r.newton_iterations, r.residual, r.active_nodes, r.slip_nodes,
                     r.kinetic_energy, r.internal_energy, r.external_work, total, r.momentum[0],
                     r.momentum[1], r.momentum[2], r.angular_momentum[0], r.angular_momentum[1],
                     r.angular_momentum[2], wall});
    for (std::size_t k = 0; k < model_.reaction_regions.size(); ++k) {
      const double* f = &reactions[k * dim];
      reactions_->add_row(
          {r.step, r.time, model_.reaction_regions[k].name, f[0], f[1], dim == 3 ? f[2] : 0.0});
    }
    for (std::size_t p = 0; p < probes_.size(); ++p) {
      const auto& pt = probes_[p].point;
      probes_table_->add_row({r.step, r.time, static_cast<int>(p), pt[0], pt[1], pt[2],
                              probe_u[p * 3], probe_u[p * 3 + 1], probe_u[p * 3 + 2]});
    }
    if (errors) {
      errors_->add_row({r.step, r.time, errors->l2, errors->h1_semi, errors->l2_exact});
      last_errors_ = {errors->l2, errors->h1_semi};
    }
    if (!quiet_) {
      // Time left from the mean wall time per unit of simulated time since the first step.
      print_step_line(r.step, r.time, r.newton_iterations, r.residual, wall,
                      time_left(wall_seconds() - progress_wall_, r.time - progress_time_,
                                config_.time.end - r.time));
    }
    std::fflush(stdout);
  }
  const bool fields = force_fields || r.step % config_.output.every == 0;
  const auto states = interface_states(u, multipliers, fields);
  // The contact node rows, computed by the slave nodes' owners, to rank 0 for the file.
  std::vector<std::vector<InterfaceNodeRow>> contact_rows;
  if (fields)
    for (const auto& c : contact_) contact_rows.push_back(rows_on_root(comm, c.rows));
  if (comm.is_root()) write_interfaces(r, states, contact_rows, fields);
  if (fields) write_fields(r.step, r.time, u, v, states);
}

void Output::write_fields(int step, double time, const la::Vector& u, const la::Vector* v,
                          const std::vector<InterfaceState>& states) {
  const auto& comm = disc_.comm();
  const auto& mesh = disc_.mesh();
  const int dim = disc_.dim();
  const auto local_nodes = disc_.local_nodes();
  const std::size_t n_points = local_nodes.size();

  std::vector<double> points(n_points * 3, 0.0), disp(n_points * 3, 0.0), vel(n_points * 3, 0.0);
  {
    la::Vector::LocalView view(u, false);
    const auto ul = view.values();
    for (std::size_t i = 0; i < n_points; ++i)
      for (int c = 0; c < dim; ++c) {
        disp[i * 3 + c] = ul[i * dim + c];
        points[i * 3 + c] =
            mesh.x[static_cast<std::size_t>(local_nodes[i]) * dim + c] + disp[i * 3 + c];
      }
  }
  if (v) {
    la::Vector::LocalView view(*v, false);
    const auto vl = view.values();
    for (std::size_t i = 0; i < n_points; ++i)
      for (int c = 0; c < dim; ++c) vel[i * 3 + c] = vl[i * dim + c];
  }

  // Cell stresses.
  const auto cells = disc_.local_cells();
  std::vector<double> stress(cells.size() * 6, 0.0), mises(cells.size(), 0.0);
  {
    la::Vector::LocalView view(u, false);
    const auto ul = view.values();
    std::array<double, fem::max_cell_nodes * 3> X{}, ue{};
    for (std::size_t k = 0; k < cells.size(); ++k) {
      const auto c = cells[k];
      const auto nodes = mesh.cell(c);
      const int nd = static_cast<int>(nodes.size()) * dim;
      for (std::size_t a = 0; a < nodes.size(); ++a)
        for (int i = 0; i < dim; ++i) {
          X[a * dim + i] = mesh.x[static_cast<std::size_t>(nodes[a]) * dim + i];
          ue[a * dim + i] = ul[disc_.local_dof(nodes[a], i)];
        }
      solid::ElementInput in{mesh.cell_type[c],
                             dim,
                             model_.plane,
                             model_.materials[model_.cell_material[c]],
                             std::span<const double>(X.data(), nd),
                             std::span<const double>(ue.data(), nd),
                             0};
      const auto s = solid::element_stress(in);
      for (int i = 0; i < 6; ++i) stress[k * 6 + i] = s.cauchy[i];
      mises[k] = s.von_mises;
    }
  }

  auto piece = grid_->piece(3, points, time, step);
  piece.point_data.emplace_back("displacement", 3, std::span<const double>(disp));
  piece.point_data.emplace_back("velocity", 3, std::span<const double>(vel));
  // Interface fields on the slave nodes: multiplier, weighted gap, status (-1 off the
  // interface, 0 inactive, 1 tied / stick, 2 slip). A node that is a slave node of several
  // interfaces (a ring's outer surface in self contact and against the floor) shows the sum
  // of their multipliers, the highest status and the gap of the interface that gives it (the
  // smaller gap where two give it).
  std::vector<double> lambda(n_points * 3, 0.0), gap(n_points, 0.0);
  std::vector<std::int32_t> status(n_points, -1);
  if (!tied_.empty() || !contact_.empty()) {
    // The owners' values, then the ghosts' copies of them (a distributed interface has its
    // multipliers on the owned nodes only, a contact interface the multiplier vectors of the
    // nodes whose normals it computed). Second vector: gap, and status + 2 (0: none).
    la::Vector lambda_v = disc_.make_vector(), gap_v = disc_.make_vector();
    {
      la::Vector::LocalView lv(lambda_v, true), gv(gap_v, true);
      auto l = lv.values();
      auto g = gv.values();
      std::fill(l.begin(), l.end(), 0.0);
      std::fill(g.begin(), g.end(), 0.0);
      const auto put = [&](auto node, std::span<const double> multiplier, double node_gap,
                           double node_status) {
        for (int c = 0; c < dim; ++c) l[disc_.local_dof(node, c)] += multiplier[c];
        double& s = g[disc_.local_dof(node, 1)];
        double& gn = g[disc_.local_dof(node, 0)];
        if (s == 0.0 || node_status > s || (node_status == s && node_gap < gn)) {
          gn = node_gap;
          s = node_status;
        }
      };
      for (std::size_t k = 0; k < tied_.size(); ++k) {
        const auto& t = tied_[k];
        for (std::size_t j = 0; j < t.slave.mesh_nodes.size(); ++j) {
          const auto node = t.slave.mesh_nodes[j];
          if (!disc_.owns_node(node)) continue;
          put(node, std::span<const double>(states[k].lambda).subspan(j * dim, dim),
              states[k].gap[j], tied_rows_[k][j] ? 3.0 : 2.0);
        }
      }
      for (const auto& c : contact_)
        for (std::size_t j = 0; j < c.slave_nodes.size(); ++j) {
          if (!c.owned[j]) continue;
          put(c.slave_nodes[j], std::span<const double>(c.lambda).subspan(j * dim, dim),
              c.weighted_gap[j], 2.0 + c.status[j]);
        }
    }
    lambda_v.update_ghosts();
    gap_v.update_ghosts();
    la::Vector::LocalView lv(lambda_v, false), gv(gap_v, false);
    const auto l = lv.values();
    const auto g = gv.values();
    for (std::size_t i = 0; i < n_points; ++i) {
      if (g[i * dim + 1] == 0.0) continue;
      for (int c = 0; c < dim; ++c) lambda[i * 3 + c] = l[i * dim + c];
      gap[i] = g[i * dim];
      status[i] = static_cast<std::int32_t>(g[i * dim + 1]) - 2;
    }
  }
  if (!tied_.empty() || has_contact_) {
    piece.point_data.emplace_back("lagrange_multiplier", 3, std::span<const double>(lambda));
    piece.point_data.emplace_back("weighted_gap", 1, std::span<const double>(gap));
    piece.point_data.emplace_back("contact_status", 1, std::span<const std::int32_t>(status));
  }
  piece.cell_data.emplace_back("cauchy_stress", 6, std::span<const double>(stress));
  piece.cell_data.emplace_back("von_mises", 1, std::span<const double>(mises));
  piece.cell_data.emplace_back("material", 1, std::span<const std::int32_t>(cell_material_));

  const auto file = write_step_fields(dir_, step, piece, comm);
  if (comm.is_root()) pvd_->add(time, file);
  last_field_step_ = step;
}

void Output::write_checkpoint(RecordWriter& out) const {
  put_pvd(out, pvd_.get());
}

void Output::finish(bool converged, int n_steps) {
  const auto& comm = disc_.comm();
  const double wall = comm.max(wall_seconds() - start_wall_);
  std::vector<double> phases, cpu;
  // The phases of CONTRACT.md and `condensation` always; the dynamic contact phases of
  // docs/input.md §5 where the run has them.
  std::vector<const char*> names = {"assembly",     "mortar", "search",
                                    "linear_solve", "output", "condensation"};
  const std::size_t n_always = names.size();
  for (const char* n : {"contact_persistency", "contact_velocity_update", "contact_energy_bound"})
    names.push_back(n);
  for (const char* n : names) {
    phases.push_back(comm.max(timers_.get(n)));
    cpu.push_back(comm.max(timers_.get_cpu(n)));
  }
  // Every rank's share (CONTRACT.md, ranks_detail): the cells it assembles, and the cells it
  // holds without assembling them (ghost layer and interface cells of a distributed mesh; all
  // the others when the mesh is replicated).
  // The peak over the phases (memory_trace.hpp): each phase mark resets the kernel's peak.
  parallel::mark_memory(comm.get(), "end");
  const auto& memory = parallel::memory_phases(); // the same phases on every rank
  constexpr std::size_t n_counts = 34;
  const std::size_t n_detail = n_counts + 2 * memory.size();
  std::vector<double> detail(static_cast<std::size_t>(comm.size()) * n_detail, 0.0);
  {
    double* mine = &detail[static_cast<std::size_t>(comm.rank()) * n_detail];
    mine[0] = static_cast<double>(disc_.local_cells().size());
    mine[1] = static_cast<double>(disc_.mesh().n_cells()) - mine[0];
    for (const auto& t : tied_) {
      mine[2] += static_cast<double>(t.local_slave_facets);
      mine[3] += static_cast<double>(t.local_master_ghosts);
      mine[4] += static_cast<double>(t.local_pairs);
      mine[5] += static_cast<double>(t.local_integration_cells);
    }
    for (const auto& c : contact_) {
      mine[2] += c.local_slave_elements;
      mine[3] += c.local_master_ghosts;
      mine[4] += static_cast<double>(c.local_pairs);
      mine[5] += static_cast<double>(c.local_integration_cells);
      mine[11] += static_cast<double>(c.local_contact_nodes);
      mine[12] += static_cast<double>(c.local_nodal_records);
      mine[13] += c.local_master_received;
      // Master sides of two bodies; a self-contact surface is counted as the surface.
      if (c.surface_facets == 0) mine[14] += c.master_elements;
      mine[15] += c.local_surface_received;
      mine[16] += c.surface_facets;
      mine[17] += static_cast<double>(c.local_ghost_exchanges);
      mine[18] += static_cast<double>(c.local_searches);
      mine[19] += static_cast<double>(c.local_nodes_gathered);
      mine[20] += static_cast<double>(c.interface_nodes);
      mine[21] += static_cast<double>(c.local_master_facets_read);
      mine[22] += static_cast<double>(c.local_normals);
      mine[23] += static_cast<double>(c.rows.size());
      mine[24] += static_cast<double>(c.local_owned_nodes);
      mine[25] += static_cast<double>(c.local_side_facets_held);
      mine[26] += static_cast<double>(c.local_side_facets_read);
      mine[27] += static_cast<double>(c.local_slave_facets_held);
      mine[28] += static_cast<double>(c.local_em_entries_sent);
      mine[29] += static_cast<double>(c.local_em_entries_received);
      mine[30] += static_cast<double>(c.local_self_pairs_received);
      mine[31] += static_cast<double>(c.local_self_pairs_returned);
      mine[32] += static_cast<double>(c.local_self_groups);
      mine[33] += static_cast<double>(c.self_label_rounds);
    }
    mine[6] = parallel::peak_rss_mb();
    // What the rank holds beyond its share (issue 12): cells held only for an interface
    // side, and nodes: owned, ghost (of the cells it assembles) and all held.
    mine[7] = disc_.n_cells_held(mesh::CellRole::interface);
    mine[8] = disc_.n_owned_nodes();
    mine[9] = static_cast<double>(disc_.local_nodes().size()) - disc_.n_owned_nodes();
    mine[10] = disc_.mesh().n_nodes();
    for (std::size_t k = 0; k < memory.size(); ++k) {
      mine[n_counts + 2 * k] = memory[k].peak_mb;
      mine[n_counts + 1 + 2 * k] = memory[k].current_mb;
    }
  }
  comm.sum_in_place(detail);
  if (!comm.is_root()) return;
  io::Json j = io::Json::object();
  j["status"] = converged ? "converged" : "failed";
  j["steps"] = n_steps;
  j["dofs"] = static_cast<std::int64_t>(disc_.n_global_dofs());
  j["ranks"] = comm.size();
  j["wall_seconds"] = wall;
  j["linear_solves"] = linear_solves_;
  j["linear_iterations"] = linear_iterations_;
  j["preconditioner_builds"] = preconditioner_builds_;
  if (!factor_ordering_.empty()) {
    j["symbolic_analyses"] = symbolic_analyses_;
    j["factor_ordering"] = factor_ordering_;
  }
  // Both members exist before either is referenced: adding a member may move the others.
  j["timings"] = io::Json::object();
  j["cpu_timings"] = io::Json::object();
  auto& t = j["timings"];
  auto& tc = j["cpu_timings"];
  for (std::size_t k = 0; k < phases.size(); ++k)
    if (k < n_always || phases[k] > 0.0) {
      t[names[k]] = phases[k];
      tc[names[k]] = cpu[k];
    }
  j["nodes"] = disc_.n_global_nodes();
  j["cells"] = disc_.n_global_cells();
  auto& itfs = j["interfaces"];
  itfs = io::Json::array();
  for (const auto& t : tied_) {
    io::Json e = io::Json::object();
    e["name"] = t.name;
    e["type"] = "mesh_tying";
    e["slave_elements"] = t.n_slave_facets;
    e["master_elements"] = t.n_master_facets;
    e["candidate_pairs"] = t.operators.n_candidates;
    e["integrated_pairs"] = t.operators.n_pairs_integrated;
    e["integration_cells"] = t.operators.n_integration_cells;
    e["projection_failures"] = t.operators.n_projection_failures;
    e["area"] = t.operators.integrated_area;
    e["max_slave_relocation"] = t.max_relocation;
    itfs.push_back(std::move(e));
  }
  for (const auto& c : contact_) {
    io::Json e = io::Json::object();
    e["name"] = c.name;
    e["type"] = "contact";
    e["slave_elements"] = c.slave_elements;
    e["master_elements"] = c.master_elements;
    e["candidate_pairs"] = c.candidate_pairs;
    e["active_nodes"] = c.active_nodes;
    e["normal_force"] = c.normal_force;
    e["contact_area"] = c.contact_area;
    if (c.surface_facets > 0) { // a surface: interface (docs/input.md)
      e["role_changes_within_step"] = c.role_changes_within_step;
      e["role_changes_between_steps"] = c.role_changes_between_steps;
      e["role_changes_of_persisting_pairs"] = c.role_changes_persisting;
    }
    itfs.push_back(std::move(e));
  }
  auto& ranks = j["ranks_detail"];
  ranks = io::Json::array();
  for (int r = 0; r < comm.size(); ++r) {
    const double* d = &detail[static_cast<std::size_t>(r) * n_detail];
    io::Json e = io::Json::object();
    put_rank_detail_basics(e, r, d);
    e["contact_nodes"] = static_cast<std::int64_t>(d[11]);
    e["contact_nodal_records"] = static_cast<std::int64_t>(d[12]);
    e["contact_master_received"] = static_cast<std::int64_t>(d[13]);
    e["contact_master_facets"] = static_cast<std::int64_t>(d[14]);
    e["contact_surface_received"] = static_cast<std::int64_t>(d[15]);
    e["contact_surface_facets"] = static_cast<std::int64_t>(d[16]);
    e["contact_ghost_exchanges"] = static_cast<std::int64_t>(d[17]);
    e["contact_searches"] = static_cast<std::int64_t>(d[18]);
    e["contact_interface_nodes_gathered"] = static_cast<std::int64_t>(d[19]);
    e["contact_interface_nodes"] = static_cast<std::int64_t>(d[20]);
    e["contact_master_facets_read"] = static_cast<std::int64_t>(d[21]);
    e["contact_normals_computed"] = static_cast<std::int64_t>(d[22]);
    // The rows of interface_<name>.csv this rank computed at the last step (its slave nodes).
    e["contact_output_rows"] = static_cast<std::int64_t>(d[23]);
    e["contact_slave_nodes_owned"] = static_cast<std::int64_t>(d[24]);
    e["contact_side_facets_held"] = static_cast<std::int64_t>(d[25]);
    e["contact_side_facets_read"] = static_cast<std::int64_t>(d[26]);
    e["contact_slave_facets_held"] = static_cast<std::int64_t>(d[27]);
    e["contact_em_entries_sent"] = static_cast<std::int64_t>(d[28]);
    e["contact_em_entries_received"] = static_cast<std::int64_t>(d[29]);
    e["contact_self_pairs_received"] = static_cast<std::int64_t>(d[30]);
    e["contact_self_pairs_returned"] = static_cast<std::int64_t>(d[31]);
    e["contact_self_groups_decided"] = static_cast<std::int64_t>(d[32]);
    e["contact_self_label_rounds"] = static_cast<std::int64_t>(d[33]);
    // Per phase of the run: the peak since the previous phase and the resident set at its end.
    auto& phases = e["memory_phases"];
    phases = io::Json::array();
    for (std::size_t k = 0; k < memory.size(); ++k) {
      io::Json p = io::Json::object();
      p["phase"] = memory[k].name;
      p["peak_mb"] = d[n_counts + 2 * k];
      p["rss_mb"] = d[n_counts + 1 + 2 * k];
      phases.push_back(std::move(p));
    }
    ranks.push_back(std::move(e));
  }
  if (last_errors_.size() == 2) {
    j["errors"]["l2"] = last_errors_[0];
    j["errors"]["h1"] = last_errors_[1];
  }
  io::write_json(dir_ / "summary.json", j);
}

} // namespace seam::problem
