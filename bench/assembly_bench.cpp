// seam-bench assembly: throughput of the solid element kernels, of the global assembly into
// PETSc, and the time per Newton iteration (assembly + GMRES/GAMG solve) of a compressed
// Neo-Hooke block (docs/performance.md).
#include "registry.hpp"

#include "seam/common/mpi.hpp"
#include "seam/fem/cell.hpp"
#include "seam/la/petsc.hpp"
#include "seam/mesh/mesh.hpp"
#include "seam/problem/assembly.hpp"
#include "seam/problem/discretization.hpp"
#include "seam/problem/model.hpp"
#include "seam/solid/detail/cell_geometry.hpp"
#include "seam/solid/element.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <random>
#include <stdexcept>
#include <string>
#include <sys/resource.h>
#include <vector>

namespace {

using namespace seam;
using fem::CellType;
using solid::MaterialModel;

/// CPU seconds of this thread: the element kernels are single-threaded, and on a shared
/// machine CPU time is what they cost, where wall time would include waiting for a core.
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}
double wall() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
double load_average() {
  double l = -1;
  if (std::FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf", &l) != 1) l = -1;
    std::fclose(f);
  }
  return l;
}
double max_rss_gib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / (1024.0 * 1024.0); // ru_maxrss is in KiB on Linux
}

/// Key-value pairs printed as one JSON object.
struct Json {
  std::string body;
  void add(const std::string& key, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    body += (body.empty() ? "\"" : ", \"") + key + "\": " + buf;
  }
  void add(const std::string& key, const std::string& v) {
    body += (body.empty() ? "\"" : ", \"") + key + "\": \"" + v + "\"";
  }
};

solid::Material material(MaterialModel model) {
  solid::Material m;
  m.model = model;
  m.young = 1.0;
  m.poisson = 0.3;
  return m;
}

// ---------------------------------------------------------------- element kernels, one core

/// A batch of distinct, mildly distorted cells of size ~1 with small random displacements, so
/// that the timing does not run on one cell that stays in L1 with perfectly predicted data.
struct Batch {
  CellType type;
  int nd = 0; // dofs per cell
  std::vector<double> X, u;
  std::span<const double> X_of(int e) const {
    return {X.data() + std::size_t(e) * nd, std::size_t(nd)};
  }
  std::span<const double> u_of(int e) const {
    return {u.data() + std::size_t(e) * nd, std::size_t(nd)};
  }
};

Batch make_batch(CellType type, int n_cells) {
  Batch b{type, fem::n_nodes(type) * 3, {}, {}};
  const auto ref = fem::reference_nodes(type);
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> jitter(-0.04, 0.04), disp(-0.01, 0.01);
  for (int e = 0; e < n_cells; ++e)
    for (std::size_t k = 0; k < ref.size(); ++k) {
      b.X.push_back(ref[k] + jitter(rng));
      b.u.push_back(disp(rng));
    }
  return b;
}

/// Elements per CPU second of `f(e)` over the batch: repeated until 0.2 s have passed, best
/// of `repeat`.
template <class F> double elements_per_second(int n_cells, int repeat, F&& f) {
  double best = 0;
  for (int r = 0; r < repeat; ++r) {
    long count = 0;
    const double t0 = cpu_seconds();
    double t = t0;
    while (t - t0 < 0.2) {
      for (int e = 0; e < n_cells; ++e) f(e);
      count += n_cells;
      t = cpu_seconds();
    }
    best = std::max(best, double(count) / (t - t0));
  }
  return best;
}

struct KernelRates {
  double geometry = 0, le_rK = 0, nh_r = 0, nh_rK = 0;
};

KernelRates time_kernels(CellType type, int repeat) {
  constexpr int n_cells = 256;
  const Batch b = make_batch(type, n_cells);
  std::array<double, fem::max_cell_nodes * 3> r{};
  std::vector<double> K(std::size_t(b.nd) * b.nd);
  volatile double sink = 0;
  KernelRates out;
  // Baseline: the quadrature loop's geometry alone (shape gradients, Jacobian, its inverse,
  // dN/dX), which every element kernel pays before any mechanics.
  const int n = fem::n_nodes(type);
  out.geometry = elements_per_second(n_cells, repeat, [&](int e) {
    const auto rule = fem::quadrature(type, fem::default_quadrature_degree(type));
    solid::detail::NodalGradients<3> G;
    double s = 0;
    for (int q = 0; q < rule.n_points; ++q)
      s += solid::detail::reference_gradients<3>(type, n, &rule.points[q * 3], b.X_of(e), G) *
           G(n - 1, 2);
    sink = sink + s;
  });
  auto kernel = [&](MaterialModel model, bool tangent) {
    const solid::Material m = material(model);
    return elements_per_second(n_cells, repeat, [&](int e) {
      const solid::ElementInput in{type, 3, solid::PlaneMode::none, m, b.X_of(e), b.u_of(e), 0};
      const auto res = solid::internal_force(in, std::span<double>(r.data(), b.nd),
                                             tangent ? std::span<double>(K) : std::span<double>());
      if (res.status != solid::KernelStatus::ok)
        throw std::runtime_error(std::string("kernel failed: ") +
                                 std::string(solid::describe(res.status)));
      sink = sink + r[0];
    });
  };
  out.le_rK = kernel(MaterialModel::linear_elastic, true);
  out.nh_r = kernel(MaterialModel::neo_hooke, false);
  out.nh_rK = kernel(MaterialModel::neo_hooke, true);
  return out;
}

void run_kernels(int repeat, Json& json) {
  std::printf("\n1. Element kernels, one core (CPU time, best of %d; 256 distorted cells, random "
              "u, E = 1, nu = 0.3, full Gauss integration)\n",
              repeat);
  std::printf("  %-6s %4s %12s %12s %12s %12s %9s %9s %9s\n", "cell", "qp", "geometry/s",
              "linel r+K/s", "NH r/s", "NH r+K/s", "us NH r+K", "NH/linel", "NH/geom");
  for (CellType t :
       {CellType::hex8, CellType::hex20, CellType::hex27, CellType::tet4, CellType::tet10}) {
    const auto k = time_kernels(t, repeat);
    const int qp = fem::quadrature(t, fem::default_quadrature_degree(t)).n_points;
    std::printf("  %-6s %4d %12.4g %12.4g %12.4g %12.4g %9.2f %9.2f %9.1f\n",
                std::string(fem::name(t)).c_str(), qp, k.geometry, k.le_rK, k.nh_r, k.nh_rK,
                1e6 / k.nh_rK, k.le_rK / k.nh_rK, k.geometry / k.nh_rK);
    const std::string p = "kernel_" + std::string(fem::name(t)) + "_";
    json.add(p + "geometry_per_s", k.geometry);
    json.add(p + "linear_elastic_rK_per_s", k.le_rK);
    json.add(p + "neo_hooke_r_per_s", k.nh_r);
    json.add(p + "neo_hooke_rK_per_s", k.nh_rK);
  }
  std::printf("  ratios: NH/linel = time of Neo-Hooke r+K over linear-elastic r+K; NH/geom = over "
              "the geometry baseline\n");
}

// ------------------------------------------------------------------- structured block mesh

/// n^3 cells of `type` on [0,1]^3; nodes numbered lexicographically (x fastest) over the
/// nodes the cells use (hex20 leaves face and body centres of the order-2 grid out).
mesh::Mesh block_mesh(CellType type, int n) {
  const int o = fem::order(type), m = o * n + 1, nn = fem::n_nodes(type);
  const auto ref = fem::reference_nodes(type);
  std::vector<std::array<int, 3>> offset(nn);
  for (int a = 0; a < nn; ++a)
    for (int d = 0; d < 3; ++d) offset[a][d] = int(std::lround((ref[a * 3 + d] + 1.0) * 0.5 * o));
  auto grid = [m](int i, int j, int k) { return (std::size_t(k) * m + j) * m + i; };
  std::vector<std::int32_t> id(std::size_t(m) * m * m, -1);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (const auto& d : offset) id[grid(o * i + d[0], o * j + d[1], o * k + d[2])] = 0;
  mesh::Mesh mesh;
  mesh.dim = 3;
  std::int32_t next = 0;
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        auto& g = id[grid(i, j, k)];
        if (g < 0) continue;
        g = next++;
        mesh.x.insert(mesh.x.end(),
                      {double(i) / (m - 1), double(j) / (m - 1), double(k) / (m - 1)});
      }
  std::vector<std::int32_t> nodes(nn);
  mesh.cell_type.reserve(std::size_t(n) * n * n);
  mesh.cell_nodes.reserve(std::size_t(n) * n * n * nn);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        for (int a = 0; a < nn; ++a)
          nodes[a] = id[grid(o * i + offset[a][0], o * j + offset[a][1], o * k + offset[a][2])];
        mesh.add_cell(type, nodes);
      }
  mesh.check();
  return mesh;
}

/// Neo-Hooke everywhere, no loads: the displacement is driven by Dirichlet values alone.
problem::Model block_model(const mesh::Mesh& mesh) {
  problem::Model model;
  model.dim = 3;
  model.materials = {material(MaterialModel::neo_hooke)};
  model.material_names = {"block"};
  model.cell_material.assign(std::size_t(mesh.n_cells()), 0);
  return model;
}

/// Sets the owned entries of u from f(X) (3 values) and updates the ghosts.
template <class F> void set_field(const problem::Discretization& disc, la::Vector& u, F&& f) {
  {
    la::Vector::LocalView view(u, true);
    auto v = view.values();
    const auto nodes = disc.local_nodes();
    for (std::int32_t i = 0; i < disc.n_owned_nodes(); ++i) {
      const auto X = disc.mesh().node(nodes[i]);
      const auto d = f(X[0], X[1], X[2]);
      for (int c = 0; c < 3; ++c) v[std::size_t(i) * 3 + c] = d[c];
    }
  }
  u.update_ghosts();
}

// ---------------------------------------------------------------------- global assembly

/// Max over ranks of the wall time of f (started together after a barrier).
template <class F> double timed(const Comm& comm, F&& f) {
  comm.barrier();
  const double t0 = wall();
  f();
  return comm.max(wall() - t0);
}

void run_assembly(const problem::Discretization& disc, const problem::Model& model, int repeat,
                  Json& json) {
  const Comm comm = disc.comm();
  const auto& mesh = disc.mesh();
  const double n_cells = mesh.n_cells();
  la::Vector u = disc.make_vector(), r = disc.make_vector();
  set_field(disc, u, [](double x, double y, double z) {
    return std::array<double, 3>{0.01 * y * z, 0.01 * x * z, -0.05 * z};
  });
  la::Matrix K;
  const double t_matrix = timed(comm, [&] { K = disc.make_matrix(); });

  auto best = [&](auto&& f) {
    double b = 1e300;
    for (int i = 0; i < repeat; ++i) b = std::min(b, timed(comm, f));
    return b;
  };
  const double t_rK = best([&] { problem::assemble(model, disc, u, 0.0, r, &K); });
  PetscReal norm_K = 0;
  MatNorm(K.get(), NORM_FROBENIUS, &norm_K);
  const double norm_r = r.norm();
  const double t_r = best([&] { problem::assemble(model, disc, u, 0.0, r, nullptr); });

  // The same loop as problem::assemble with the phases timed per cell: gather + kernel, then
  // MatSetValues/VecSetValues, then the final (communicating) MatAssembly/VecAssembly.
  struct Split {
    double zero = 0, kernel = 0, insert = 0, final = 0;
  } split{1e300, 1e300, 1e300, 1e300};
  constexpr int max_dofs = fem::max_cell_nodes * 3;
  std::array<double, max_dofs> X{}, ue{}, re{};
  std::array<PetscInt, max_dofs> dofs{};
  std::vector<double> Ke(std::size_t(max_dofs) * max_dofs);
  for (int i = 0; i < repeat; ++i) {
    Split s;
    comm.barrier();
    double t0 = wall();
    r.zero();
    K.zero();
    s.zero = wall() - t0;
    {
      la::Vector::LocalView view(u, false);
      const auto ul = view.values();
      for (auto c : disc.local_cells()) {
        t0 = wall();
        const auto nodes = mesh.cell(c);
        const int nd = int(nodes.size()) * 3;
        for (std::size_t a = 0; a < nodes.size(); ++a)
          for (int k = 0; k < 3; ++k) {
            X[a * 3 + k] = mesh.x[std::size_t(nodes[a]) * 3 + k];
            ue[a * 3 + k] = ul[std::size_t(disc.local_dof(nodes[a], k))];
            dofs[a * 3 + k] = disc.global_dof(nodes[a], k);
          }
        const solid::ElementInput in{mesh.cell_type[c],
                                     3,
                                     solid::PlaneMode::none,
                                     model.materials[std::size_t(model.cell_material[c])],
                                     std::span<const double>(X.data(), nd),
                                     std::span<const double>(ue.data(), nd),
                                     0};
        solid::internal_force(in, std::span<double>(re.data(), nd),
                              std::span<double>(Ke.data(), std::size_t(nd) * nd));
        const double t1 = wall();
        const std::span<const PetscInt> d(dofs.data(), nd);
        r.add_values(d, std::span<const double>(re.data(), nd));
        K.add_values(d, d, std::span<const double>(Ke.data(), std::size_t(nd) * nd));
        const double t2 = wall();
        s.kernel += t1 - t0;
        s.insert += t2 - t1;
      }
    }
    t0 = wall();
    r.assemble();
    K.assemble();
    s.final = wall() - t0;
    split.zero = std::min(split.zero, comm.max(s.zero));
    split.kernel = std::min(split.kernel, comm.max(s.kernel));
    split.insert = std::min(split.insert, comm.max(s.insert));
    split.final = std::min(split.final, comm.max(s.final));
  }
  // The replica must build what problem::assemble built.
  PetscReal norm_K2 = 0;
  MatNorm(K.get(), NORM_FROBENIUS, &norm_K2);
  const double dK = std::abs(norm_K2 - norm_K) / norm_K, dr = std::abs(r.norm() - norm_r) / norm_r;

  const auto type = std::string(fem::name(mesh.cell_type[0]));
  const std::int64_t local = comm.max(std::int64_t(disc.local_cells().size()));
  if (comm.is_root()) {
    std::printf("\n2. Global assembly, problem::assemble into PETSc AIJ (wall time, max over "
                "ranks, best of %d)\n",
                repeat);
    std::printf("  %s, %d cells, %lld dofs, %d rank(s), at most %lld cells per rank\n",
                type.c_str(), mesh.n_cells(), (long long)disc.n_global_dofs(), comm.size(),
                (long long)local);
    std::printf("  %-40s %10s %14s\n", "phase", "s", "cells/s");
    auto row = [&](const char* what, double t) {
      std::printf("  %-40s %10.4g %14.4g\n", what, t, n_cells / t);
    };
    row("make_matrix (pattern, preallocation)", t_matrix);
    row("assemble r + K (problem::assemble)", t_rK);
    row("assemble r only (problem::assemble)", t_r);
    row("  split: zero r, K", split.zero);
    row("  split: gather + element kernel", split.kernel);
    row("  split: VecSetValues + MatSetValues", split.insert);
    row("  split: Vec/MatAssemblyBegin/End", split.final);
    const double sum = split.zero + split.kernel + split.insert + split.final;
    std::printf("  split sum %.4g s (vs %.4g s); replica vs assemble: |K|_F rel. diff %.1e, |r| "
                "%.1e\n",
                sum, t_rK, dK, dr);
    std::printf("  ratios: assemble r+K / kernel alone = %.2f, insertion / kernel = %.2f\n",
                t_rK / split.kernel, split.insert / split.kernel);
  }
  json.add("assembly_cell", type);
  json.add("assembly_cells", n_cells);
  json.add("assembly_dofs", double(disc.n_global_dofs()));
  json.add("make_matrix_s", t_matrix);
  json.add("assemble_rK_s", t_rK);
  json.add("assemble_r_s", t_r);
  json.add("assemble_rK_cells_per_s", n_cells / t_rK);
  json.add("split_zero_s", split.zero);
  json.add("split_kernel_s", split.kernel);
  json.add("split_insert_s", split.insert);
  json.add("split_final_s", split.final);
}

// ----------------------------------------------------------------------- Newton iteration

/// Accumulated wall time of a PETSc log event on this rank (logging is switched on at start).
double event_seconds(const char* name) {
  PetscLogEvent e = 0;
  la::check(PetscLogEventGetId(name, &e), "PetscLogEventGetId");
  PetscEventPerfInfo info{};
  la::check(PetscLogEventGetPerfInfo(PETSC_DETERMINE, e, &info), "PetscLogEventGetPerfInfo");
  return info.time;
}

/// One load step of the compressed block, iterated as problem::run_static does it: a
/// predictor that carries the prescribed increment as an inhomogeneous constraint, then
/// correctors until |r| <= tol * reference (Newton tolerance and linear solver of seam's
/// iterative setting).
void run_newton(const problem::Discretization& disc, const problem::Model& model,
                double compression, int max_iterations, Json& json) {
  const Comm comm = disc.comm();
  la::Vector u = disc.make_vector(), r = disc.make_vector(), du = disc.make_vector();
  la::Vector g = disc.make_vector();
  la::Matrix K = disc.make_matrix();
  K.set_near_null_space(disc.coordinates_vector());
  la::LinearSolver solver(comm.get(), la::SolverKind::iterative);
  // Bottom (z = 0) clamped; top (z = 1) clamped in x, y and moved down by `compression`.
  std::vector<PetscInt> rows;
  std::vector<double> values;
  const auto nodes = disc.local_nodes();
  for (std::int32_t i = 0; i < disc.n_owned_nodes(); ++i) {
    const double z = disc.mesh().node(nodes[i])[2];
    if (z != 0.0 && z != 1.0) continue;
    for (int c = 0; c < 3; ++c) {
      rows.push_back(disc.global_dof(nodes[i], c));
      values.push_back(c == 2 && z == 1.0 ? -compression : 0.0);
    }
  }
  const PetscInt first = disc.first_owned_dof();
  auto set_prescribed = [&](la::Vector& v, bool increment) {
    {
      la::Vector::LocalView view(v, true);
      auto x = view.values();
      if (increment) std::fill(x.begin(), x.end(), 0.0);
      for (std::size_t k = 0; k < rows.size(); ++k) x[std::size_t(rows[k] - first)] = values[k];
    }
    v.update_ghosts();
  };
  set_prescribed(g, true); // u = 0: the increment is the prescribed value

  if (comm.is_root()) {
    std::printf("\n3. Newton, compressed Neo-Hooke block (%.0f %% of its height, clamped ends), "
                "%lld dofs, %d rank(s)\n",
                100 * compression, (long long)disc.n_global_dofs(), comm.size());
    std::printf("  GMRES(200) + GAMG, rigid-body near-null space, rtol 1e-10; Newton tol 1e-10 "
                "(wall s, max over ranks)\n");
    std::printf("  %3s %11s %10s %9s %10s %10s %6s %10s\n", "it", "|r|/ref", "assembly", "bc",
                "amg setup", "krylov", "ksp", "iteration");
  }
  const double tol = 1e-10;
  double reference = 0, sum_iteration = 0, sum_assembly = 0, sum_setup = 0, sum_krylov = 0;
  int n_solves = 0, ksp_total = 0;
  bool converged = false;
  for (int it = 0; it <= max_iterations; ++it) {
    comm.barrier();
    const double t0 = wall();
    const auto status = problem::assemble(model, disc, u, 1.0, r, &K);
    const double t_asm = comm.max(wall() - t0);
    if (comm.any(status.inverted)) throw std::runtime_error("an element inverted");
    {
      la::Vector::LocalView view(r, true);
      auto x = view.values();
      for (auto row : rows) x[std::size_t(row - first)] = 0.0;
    }
    const double norm = r.norm();
    const bool predictor = it == 0;
    if (it <= 1) reference = std::max(reference, norm);
    converged = !predictor && norm <= tol * reference;
    const double rel = reference > 0 ? norm / reference : 0.0;
    if (converged || it == max_iterations) {
      if (comm.is_root()) std::printf("  %3d %11.3e %10.4g\n", it, rel, t_asm);
      break;
    }
    const double t1 = wall();
    r.scale(-1.0);
    K.zero_rows_columns(rows, predictor ? &g : nullptr, predictor ? &r : nullptr);
    const double t_bc = comm.max(wall() - t1);
    const double setup0 = event_seconds("PCSetUp");
    const double t2 = wall();
    du.zero();
    if (!solver.solve(K, r, du)) throw std::runtime_error("the linear solver did not converge");
    const double t_solve = comm.max(wall() - t2);
    const double t_setup = comm.max(event_seconds("PCSetUp") - setup0);
    u.axpy(1.0, du);
    if (predictor) set_prescribed(u, false); // the prescribed values exactly
    u.update_ghosts();
    const double t_it = comm.max(wall() - t0);
    if (comm.is_root())
      std::printf("  %3d %11.3e %10.4g %9.3g %10.4g %10.4g %6d %10.4g\n", it, rel, t_asm, t_bc,
                  t_setup, t_solve - t_setup, solver.last_iterations(), t_it);
    ++n_solves;
    ksp_total += solver.last_iterations();
    sum_iteration += t_it;
    sum_assembly += t_asm;
    sum_setup += t_setup;
    sum_krylov += t_solve - t_setup;
  }
  const double rss = comm.max(max_rss_gib());
  if (comm.is_root())
    std::printf("  %s after %d solves; per Newton iteration: %.4g s (assembly %.4g, AMG setup "
                "%.4g, Krylov %.4g, %.1f GMRES its); peak RSS %.2f GiB per rank\n",
                converged ? "converged" : "NOT converged", n_solves, sum_iteration / n_solves,
                sum_assembly / n_solves, sum_setup / n_solves, sum_krylov / n_solves,
                double(ksp_total) / n_solves, rss);
  json.add("newton_dofs", double(disc.n_global_dofs()));
  json.add("newton_converged", converged ? 1.0 : 0.0);
  json.add("newton_solves", n_solves);
  json.add("newton_iteration_s", sum_iteration / n_solves);
  json.add("newton_assembly_s", sum_assembly / n_solves);
  json.add("newton_amg_setup_s", sum_setup / n_solves);
  json.add("newton_krylov_s", sum_krylov / n_solves);
  json.add("newton_ksp_its", double(ksp_total) / n_solves);
  json.add("peak_rss_gib", rss);
}

// ----------------------------------------------------------------------------- command

void help() {
  std::printf(
      "usage: seam-bench assembly [--cells-per-side N] [--order 1|2] [--serendipity]\n"
      "                           [--newton] [--compression C] [--max-newton K] [--repeat R]\n"
      "                           [--no-kernels] [--json] [-- PETSc options]\n"
      "  1. element kernels (one core): hex8/20/27 and tet4/10, Neo-Hooke residual and\n"
      "     residual + tangent against a linear-elastic element and the bare geometry loop;\n"
      "  2. problem::assemble of an N^3 block (hex8; --order 2: hex27, with --serendipity\n"
      "     hex20) into the PETSc matrix, split into kernel, insertion and final assembly;\n"
      "  3. --newton: time per Newton iteration (assembly + GMRES/GAMG) of the block\n"
      "     compressed by C (default 0.1) of its height.\n"
      "  N defaults to about 1e6 dofs (69 hex8, 44 hex20, 35 hex27). Run under mpirun for\n"
      "  several ranks (the kernel table is then skipped). --json: one JSON object, last.\n");
}

int run_assembly_bench(int argc, char** argv) {
  int n = 0, order = 1, repeat = 3, max_newton = 15;
  bool serendipity = false, newton = false, json_out = false, kernels = true;
  double compression = 0.1;
  std::vector<std::string> petsc_args;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) throw std::invalid_argument("missing value after " + a);
      return argv[++i];
    };
    if (a == "--") {
      for (++i; i < argc; ++i) petsc_args.emplace_back(argv[i]);
    } else if (a == "--cells-per-side")
      n = std::atoi(value());
    else if (a == "--order")
      order = std::atoi(value());
    else if (a == "--serendipity")
      serendipity = true;
    else if (a == "--newton")
      newton = true;
    else if (a == "--compression")
      compression = std::atof(value());
    else if (a == "--max-newton")
      max_newton = std::atoi(value());
    else if (a == "--repeat")
      repeat = std::atoi(value());
    else if (a == "--no-kernels")
      kernels = false;
    else if (a == "--json")
      json_out = true;
    else if (a == "--help" || a == "-h") {
      help();
      return 0;
    } else
      throw std::invalid_argument("unknown option " + a);
  }
  if ((order != 1 && order != 2) || (serendipity && order != 2))
    throw std::invalid_argument("--order must be 1 or 2; --serendipity needs --order 2");
  if (repeat < 1 || max_newton < 1 || !(compression > 0 && compression < 0.5))
    throw std::invalid_argument("need --repeat >= 1, --max-newton >= 1, 0 < --compression < 0.5");
  const CellType type = order == 1    ? CellType::hex8
                        : serendipity ? CellType::hex20
                                      : CellType::hex27;
  if (n == 0) n = type == CellType::hex8 ? 69 : type == CellType::hex20 ? 44 : 35;
  if (n < 2) throw std::invalid_argument("--cells-per-side must be >= 2");

  la::Session session(argc, argv, petsc_args);
  la::check(PetscLogDefaultBegin(), "PetscLogDefaultBegin"); // for the AMG setup time
  const Comm comm(PETSC_COMM_WORLD);
  Json json;
  json.add("ranks", comm.size());
  json.add("load_average_start", load_average());
  if (comm.is_root())
    std::printf("seam-bench assembly: %d rank(s), load average %.2f at start\n", comm.size(),
                load_average());
  if (kernels && comm.size() == 1) run_kernels(repeat, json);

  const double t0 = wall();
  const mesh::Mesh mesh = block_mesh(type, n);
  const problem::Discretization disc(mesh, comm);
  const problem::Model model = block_model(mesh);
  const double t_setup = comm.max(wall() - t0);
  if (comm.is_root())
    std::printf("\n  mesh %d^3 %s + partition + numbering: %.3g s\n", n,
                std::string(fem::name(type)).c_str(), t_setup);
  run_assembly(disc, model, repeat, json);
  if (newton) run_newton(disc, model, compression, max_newton, json);
  json.add("load_average_end", load_average());
  if (comm.is_root()) {
    std::printf("\n  load average %.2f at end\n", load_average());
    if (json_out) std::printf("{%s}\n", json.body.c_str());
  }
  return 0;
}

const seam::bench::Register registered{
    "assembly", "element kernels, global assembly and Newton iteration throughput",
    &run_assembly_bench};

} // namespace
