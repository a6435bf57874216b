// seam-bench assembly: throughput of the solid element kernels, of the global assembly into
// PETSc, and the time per Newton iteration (assembly + GMRES/GAMG solve) of a compressed
// Neo-Hooke block (docs/performance.md).
#include "allocation_counter.hpp"
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
  double allocations = 0; ///< heap allocations per Neo-Hooke r+K call
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
  // One untimed pass over the batch, counted: the kernels must not allocate.
  const auto before = seam::bench::AllocationCount::now();
  for (int e = 0; e < n_cells; ++e) {
    const solid::ElementInput in{
        type,      3, solid::PlaneMode::none, material(MaterialModel::neo_hooke), b.X_of(e),
        b.u_of(e), 0};
    solid::internal_force(in, std::span<double>(r.data(), b.nd), K);
  }
  const auto count = seam::bench::AllocationCount::now() - before;
  out.allocations = double(count.operator_new + count.malloc) / n_cells;
  return out;
}

void run_kernels(int repeat, Json& json) {
  std::printf("\n1. Element kernels, one core (CPU time, best of %d; 256 distorted cells, random "
              "u, E = 1, nu = 0.3, full Gauss integration)\n",
              repeat);
  std::printf("  %-6s %4s %12s %12s %12s %12s %9s %9s %9s %7s\n", "cell", "qp", "geometry/s",
              "linel r+K/s", "NH r/s", "NH r+K/s", "us NH r+K", "NH/linel", "NH/geom", "allocs");
  for (CellType t :
       {CellType::hex8, CellType::hex20, CellType::hex27, CellType::tet4, CellType::tet10}) {
    const auto k = time_kernels(t, repeat);
    const int qp = fem::quadrature(t, fem::default_quadrature_degree(t)).n_points;
    std::printf("  %-6s %4d %12.4g %12.4g %12.4g %12.4g %9.2f %9.2f %9.1f %7.3g\n",
                std::string(fem::name(t)).c_str(), qp, k.geometry, k.le_rK, k.nh_r, k.nh_rK,
                1e6 / k.nh_rK, k.le_rK / k.nh_rK, k.geometry / k.nh_rK, k.allocations);
    const std::string p = "kernel_" + std::string(fem::name(t)) + "_";
    json.add(p + "geometry_per_s", k.geometry);
    json.add(p + "linear_elastic_rK_per_s", k.le_rK);
    json.add(p + "neo_hooke_r_per_s", k.nh_r);
    json.add(p + "neo_hooke_rK_per_s", k.nh_rK);
    json.add(p + "allocations_per_call", k.allocations);
  }
  std::printf("  ratios: NH/linel = time of Neo-Hooke r+K over linear-elastic r+K; NH/geom = over "
              "the geometry baseline;\n"
              "  allocs = heap allocations per Neo-Hooke r+K call (operator new and malloc)\n");
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

/// Process CPU seconds (all threads): with other jobs on the machine, the wall time of a phase
/// includes waiting for a core, its CPU time does not (it does include MPI's busy waiting).
double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

/// Wall and CPU seconds, each the maximum over ranks.
struct Cost {
  double wall = 0, cpu = 0;
};

/// The cost of f, started on all ranks together after a barrier.
template <class F> Cost measure(const Comm& comm, F&& f) {
  comm.barrier();
  const double w0 = wall(), c0 = process_cpu_seconds();
  f();
  const double c = process_cpu_seconds() - c0, w = wall() - w0;
  return {comm.max(w), comm.max(c)};
}

/// Best (smallest) wall and CPU time over `repeat` runs.
template <class F> Cost best_of(const Comm& comm, int repeat, F&& f) {
  Cost best{1e300, 1e300};
  for (int i = 0; i < repeat; ++i) {
    const Cost c = measure(comm, f);
    best = {std::min(best.wall, c.wall), std::min(best.cpu, c.cpu)};
  }
  return best;
}

/// Buffers of one cell, filled as problem::assemble gathers them.
struct CellBuffers {
  static constexpr int max_dofs = fem::max_cell_nodes * 3;
  std::array<double, max_dofs> X{}, u{}, r{};
  std::array<PetscInt, max_dofs> dofs{};
  std::vector<double> K = std::vector<double>(std::size_t(max_dofs) * max_dofs);
  int nd = 0;

  void gather(const problem::Discretization& disc, std::span<const double> u_local,
              std::int32_t c) {
    const auto nodes = disc.mesh().cell(c);
    nd = int(nodes.size()) * 3;
    for (std::size_t a = 0; a < nodes.size(); ++a)
      for (int k = 0; k < 3; ++k) {
        X[a * 3 + k] = disc.mesh().x[std::size_t(nodes[a]) * 3 + k];
        u[a * 3 + k] = u_local[std::size_t(disc.local_dof(nodes[a], k))];
        dofs[a * 3 + k] = disc.global_dof(nodes[a], k);
      }
  }
  std::span<const PetscInt> dof_span() const { return {dofs.data(), std::size_t(nd)}; }
  std::span<double> r_span() { return {r.data(), std::size_t(nd)}; }
  std::span<double> K_span() { return {K.data(), std::size_t(nd) * nd}; }
};

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
  const Cost matrix = measure(comm, [&] { K = disc.make_matrix(); });

  // seam's own code path.
  const Cost rK = best_of(comm, repeat, [&] { problem::assemble(model, disc, u, 0.0, r, &K); });
  PetscReal norm_K = 0;
  MatNorm(K.get(), NORM_FROBENIUS, &norm_K);
  // Heap allocations of one more such assembly (this rank): PETSc may allocate in the final
  // assembly (the stash of off-rank rows), the loop over cells should not.
  const auto before = seam::bench::AllocationCount::now();
  problem::assemble(model, disc, u, 0.0, r, &K);
  const auto allocations = seam::bench::AllocationCount::now() - before;
  const std::int64_t n_allocations =
      comm.max(std::int64_t(allocations.operator_new + allocations.malloc));
  const Cost r_only =
      best_of(comm, repeat, [&] { problem::assemble(model, disc, u, 0.0, r, nullptr); });

  // Its phases, as separate loops (a clock read per cell would cost a good part of a hex8):
  // gather + element kernel; gather + VecSetValues + MatSetValues of one fixed element
  // matrix (the cost of insertion depends on the indices, not the values); the final
  // Vec/MatAssemblyBegin/End, which sends the entries of rows owned by other ranks.
  CellBuffers b;
  const auto& mat = model.materials[0];
  const Cost zero = best_of(comm, repeat, [&] {
    r.zero();
    K.zero();
  });
  const Cost kernel = best_of(comm, repeat, [&] {
    la::Vector::LocalView v(u, false);
    for (auto c : disc.local_cells()) {
      b.gather(disc, v.values(), c);
      const solid::ElementInput in{mesh.cell_type[c],
                                   3,
                                   solid::PlaneMode::none,
                                   mat,
                                   std::span<const double>(b.X.data(), std::size_t(b.nd)),
                                   std::span<const double>(b.u.data(), std::size_t(b.nd)),
                                   0};
      solid::internal_force(in, b.r_span(), b.K_span());
    }
  });
  // b holds the last cell's r and K: insert those at every cell's dofs. Each final assembly
  // follows its own insertion, so that it has the off-rank entries to send.
  Cost insert{1e300, 1e300}, final{1e300, 1e300};
  for (int i = 0; i < repeat; ++i) {
    const Cost ins = measure(comm, [&] {
      la::Vector::LocalView v(u, false);
      for (auto c : disc.local_cells()) {
        b.gather(disc, v.values(), c);
        r.add_values(b.dof_span(), b.r_span());
        K.add_values(b.dof_span(), b.dof_span(), b.K_span());
      }
    });
    const Cost fin = measure(comm, [&] {
      r.assemble();
      K.assemble();
    });
    insert = {std::min(insert.wall, ins.wall), std::min(insert.cpu, ins.cpu)};
    final = {std::min(final.wall, fin.wall), std::min(final.cpu, fin.cpu)};
  }
  // seam's insertion (problem::assemble): by 3x3 blocks straight into the AIJ arrays
  // (la::BlockAdder), against MatSetValues above (the insertion before it) and PETSc's own
  // MatSetValuesBlocked into the same AIJ matrix of block size 3.
  Cost insert_adder{1e300, 1e300};
  for (int i = 0; i < repeat; ++i) {
    const Cost ins = measure(comm, [&] {
      la::Vector::LocalView v(u, false);
      la::BlockAdder adder(K);
      for (auto c : disc.local_cells()) {
        b.gather(disc, v.values(), c);
        r.add_values(b.dof_span(), b.r_span());
        adder.add(b.dof_span(), b.K_span());
      }
      adder.finish();
    });
    r.assemble();
    K.assemble();
    insert_adder = {std::min(insert_adder.wall, ins.wall), std::min(insert_adder.cpu, ins.cpu)};
  }
  std::array<PetscInt, fem::max_cell_nodes> block{};
  const Cost insert_aij_blocked = best_of(comm, repeat, [&] {
    la::Vector::LocalView v(u, false);
    for (auto c : disc.local_cells()) {
      b.gather(disc, v.values(), c);
      const int nn = b.nd / 3;
      for (int a = 0; a < nn; ++a) block[std::size_t(a)] = b.dofs[std::size_t(a) * 3] / 3;
      r.add_values(b.dof_span(), b.r_span());
      la::check(
          MatSetValuesBlocked(K.get(), nn, block.data(), nn, block.data(), b.K.data(), ADD_VALUES),
          "MatSetValuesBlocked");
    }
  });
  r.assemble();
  K.assemble();
  // Not seam's path: the same insertion into a block AIJ copy of the matrix (MATBAIJ, 3x3
  // blocks) with MatSetValuesBlocked, which searches once per node pair instead of once per
  // entry. Only the insertion is timed; the copy exists for this comparison alone.
  Mat Kb = nullptr;
  la::check(MatConvert(K.get(), MATBAIJ, MAT_INITIAL_MATRIX, &Kb), "MatConvert");
  const Cost insert_blocked = best_of(comm, repeat, [&] {
    la::Vector::LocalView v(u, false);
    for (auto c : disc.local_cells()) {
      b.gather(disc, v.values(), c);
      const int nn = b.nd / 3;
      for (int a = 0; a < nn; ++a) block[std::size_t(a)] = b.dofs[std::size_t(a) * 3] / 3;
      r.add_values(b.dof_span(), b.r_span());
      la::check(MatSetValuesBlocked(Kb, nn, block.data(), nn, block.data(), b.K.data(), ADD_VALUES),
                "MatSetValuesBlocked");
    }
  });
  la::check(MatAssemblyBegin(Kb, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  la::check(MatAssemblyEnd(Kb, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  r.assemble();
  // Both insertions must build the same matrix: one untimed pass each from zero.
  K.zero();
  la::check(MatZeroEntries(Kb), "MatZeroEntries");
  {
    la::Vector::LocalView v(u, false);
    for (auto c : disc.local_cells()) {
      b.gather(disc, v.values(), c);
      const int nn = b.nd / 3;
      for (int a = 0; a < nn; ++a) block[std::size_t(a)] = b.dofs[std::size_t(a) * 3] / 3;
      K.add_values(b.dof_span(), b.dof_span(), b.K_span());
      la::check(MatSetValuesBlocked(Kb, nn, block.data(), nn, block.data(), b.K.data(), ADD_VALUES),
                "MatSetValuesBlocked");
    }
  }
  K.assemble();
  la::check(MatAssemblyBegin(Kb, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  la::check(MatAssemblyEnd(Kb, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  PetscReal norm_aij = 0, norm_baij = 0;
  MatNorm(K.get(), NORM_FROBENIUS, &norm_aij);
  MatNorm(Kb, NORM_FROBENIUS, &norm_baij);
  MatDestroy(&Kb);
  // The block insertion must build the same matrix as MatSetValues: K - K_blocks, entry by
  // entry (the largest difference against the largest entry).
  la::Matrix K_blocks = K.copy();
  K_blocks.zero();
  {
    la::Vector::LocalView v(u, false);
    la::BlockAdder adder(K_blocks);
    for (auto c : disc.local_cells()) {
      b.gather(disc, v.values(), c);
      adder.add(b.dof_span(), b.K_span());
    }
    adder.finish();
  }
  K_blocks.assemble();
  PetscReal max_entry = 0, max_diff = 0;
  MatNorm(K.get(), NORM_MAX, &max_entry);
  K_blocks.axpy(-1.0, K);
  MatNorm(K_blocks.get(), NORM_MAX, &max_diff);
  // A second assembly after the timing loops must give the same matrix (problem::assemble
  // zeroes what it assembles into).
  problem::assemble(model, disc, u, 0.0, r, &K);
  PetscReal norm_K2 = 0;
  MatNorm(K.get(), NORM_FROBENIUS, &norm_K2);

  const auto type = std::string(fem::name(mesh.cell_type[0]));
  const std::int64_t local = comm.max(std::int64_t(disc.local_cells().size()));
  const Cost sum{zero.wall + kernel.wall + insert.wall + final.wall,
                 zero.cpu + kernel.cpu + insert.cpu + final.cpu};
  if (comm.is_root()) {
    std::printf("\n2. Global assembly, problem::assemble into PETSc AIJ (max over ranks, best of "
                "%d)\n",
                repeat);
    std::printf("  %s, %d cells, %lld dofs, %d rank(s), at most %lld cells per rank\n",
                type.c_str(), mesh.n_cells(), (long long)disc.n_global_dofs(), comm.size(),
                (long long)local);
    std::printf("  %-38s %9s %9s %12s %12s\n", "phase", "wall s", "CPU s", "cells/s wall",
                "cells/s CPU");
    auto row = [&](const char* what, Cost t) {
      std::printf("  %-38s %9.4g %9.4g %12.4g %12.4g\n", what, t.wall, t.cpu, n_cells / t.wall,
                  n_cells / t.cpu);
    };
    row("make_matrix (pattern, preallocation)", matrix);
    row("problem::assemble, r + K", rK);
    row("problem::assemble, r only", r_only);
    row("  phase: zero r, K", zero);
    row("  phase: gather + element kernel", kernel);
    row("  phase: gather + Vec/MatSetValues", insert);
    row("  phase: Vec/MatAssemblyBegin/End", final);
    row("  phase: gather + VecSetValues + blocks", insert_adder);
    row("  AIJ (bs 3), MatSetValuesBlocked", insert_aij_blocked);
    row("  what-if: BAIJ, MatSetValuesBlocked", insert_blocked);
    row("  sum of the phases", sum);
    std::printf(
        "  ratios (CPU): assemble r+K / kernel = %.2f, insertion / kernel = %.2f, BAIJ / "
        "AIJ insertion = %.2f\n  heap allocations in one problem::assemble r+K: %lld (max over "
        "ranks)\n  checks: |K|_F of a repeated assembly, rel. diff %.1e; of "
        "BAIJ vs AIJ "
        "insertion %.1e\n  insertion by blocks (seam) / MatSetValues (before) = %.2f / %.2f = "
        "%.3f (CPU); AIJ MatSetValuesBlocked / MatSetValues = %.3f; max |K_blocks - K| / max "
        "|K| = %.1e\n",
        rK.cpu / kernel.cpu, insert.cpu / kernel.cpu, insert_blocked.cpu / insert.cpu,
        (long long)n_allocations, std::abs(norm_K2 - norm_K) / norm_K,
        std::abs(norm_baij - norm_aij) / norm_aij, insert_adder.cpu, insert.cpu,
        insert_adder.cpu / insert.cpu, insert_aij_blocked.cpu / insert.cpu, max_diff / max_entry);
  }
  json.add("assembly_cell", type);
  json.add("assembly_cells", n_cells);
  json.add("assembly_dofs", double(disc.n_global_dofs()));
  json.add("make_matrix_wall_s", matrix.wall);
  json.add("assemble_rK_wall_s", rK.wall);
  json.add("assemble_rK_cpu_s", rK.cpu);
  json.add("assemble_r_wall_s", r_only.wall);
  json.add("assemble_r_cpu_s", r_only.cpu);
  json.add("assemble_rK_cells_per_cpu_s", n_cells / rK.cpu);
  json.add("assemble_rK_allocations", double(n_allocations));
  json.add("phase_kernel_cpu_s", kernel.cpu);
  json.add("phase_insert_cpu_s", insert.cpu);
  json.add("phase_final_cpu_s", final.cpu);
  json.add("whatif_baij_insert_cpu_s", insert_blocked.cpu);
  json.add("phase_insert_blocks_cpu_s", insert_adder.cpu);
  json.add("aij_blocked_insert_cpu_s", insert_aij_blocked.cpu);
  json.add("blocks_vs_matsetvalues_max_diff", max_diff / max_entry);
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
/// Vectors of the matrix's near-null space (+1 if it holds the constant).
int near_null_vectors(const la::Matrix& K) {
  MatNullSpace nsp = nullptr;
  la::check(MatGetNearNullSpace(K.get(), &nsp), "MatGetNearNullSpace");
  if (!nsp) return 0;
  PetscBool has_constant = PETSC_FALSE;
  PetscInt n = 0;
  const Vec* vecs = nullptr;
  la::check(MatNullSpaceGetVecs(nsp, &has_constant, &n, &vecs), "MatNullSpaceGetVecs");
  return int(n) + (has_constant ? 1 : 0);
}

void run_newton(const problem::Discretization& disc, const problem::Model& model,
                double compression, int max_iterations, Json& json) {
  const Comm comm = disc.comm();
  la::Vector u = disc.make_vector(), r = disc.make_vector(), du = disc.make_vector();
  la::Vector g = disc.make_vector();
  la::Matrix K = disc.make_matrix();
  K.set_near_null_space(disc.coordinates_vector()); // as problem::run_static
  const int n_near_null = near_null_vectors(K);
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
    std::printf("  GMRES(200) + GAMG, rtol 1e-10, near-null space of %d vector(s); Newton tol "
                "1e-10; seconds, max over ranks\n",
                n_near_null);
    std::printf("  %3s %10s %9s %9s %9s %9s %9s %5s %9s %9s\n", "it", "|r|/ref", "asm wall",
                "asm CPU", "AMG setup", "Krylov", "solve CPU", "ksp", "it wall", "it CPU");
  }
  const double tol = 1e-10;
  double reference = 0;
  Cost sum_it, sum_asm, sum_solve;
  double sum_setup = 0;
  int n_solves = 0, ksp_total = 0;
  bool converged = false;
  for (int it = 0; it <= max_iterations; ++it) {
    problem::AssemblyStatus status;
    const Cost asm_cost =
        measure(comm, [&] { status = problem::assemble(model, disc, u, 1.0, r, &K); });
    if (comm.any(status.inverted)) throw std::runtime_error("an element inverted");
    double norm = 0;
    const bool predictor = it == 0;
    const Cost bc_cost = measure(comm, [&] {
      {
        la::Vector::LocalView view(r, true);
        auto x = view.values();
        for (auto row : rows) x[std::size_t(row - first)] = 0.0;
      }
      norm = r.norm();
    });
    if (it <= 1) reference = std::max(reference, norm);
    converged = !predictor && norm <= tol * reference;
    const double rel = reference > 0 ? norm / reference : 0.0;
    if (converged || it == max_iterations) {
      if (comm.is_root())
        std::printf("  %3d %10.3e %9.4g %9.4g   (converged: assembly only)\n", it, rel,
                    asm_cost.wall, asm_cost.cpu);
      break;
    }
    const double setup0 = event_seconds("PCSetUp");
    bool solved = false;
    const Cost solve_cost = measure(comm, [&] {
      r.scale(-1.0);
      K.zero_rows_columns(rows, predictor ? &g : nullptr, predictor ? &r : nullptr);
      du.zero();
      solved = solver.solve(K, r, du);
      u.axpy(1.0, du);
      if (predictor) set_prescribed(u, false); // the prescribed values exactly
      u.update_ghosts();
    });
    if (comm.any(!solved)) throw std::runtime_error("the linear solver did not converge");
    const double setup = comm.max(event_seconds("PCSetUp") - setup0);
    const Cost it_cost{asm_cost.wall + bc_cost.wall + solve_cost.wall,
                       asm_cost.cpu + bc_cost.cpu + solve_cost.cpu};
    if (comm.is_root()) {
      char label[16];
      std::snprintf(label, sizeof label, predictor ? "pred." : "%10.3e", rel);
      std::printf("  %3d %10s %9.4g %9.4g %9.4g %9.4g %9.4g %5d %9.4g %9.4g\n", it, label,
                  asm_cost.wall, asm_cost.cpu, setup, solve_cost.wall - setup, solve_cost.cpu,
                  solver.last_iterations(), it_cost.wall, it_cost.cpu);
    }
    ++n_solves;
    ksp_total += solver.last_iterations();
    sum_it = {sum_it.wall + it_cost.wall, sum_it.cpu + it_cost.cpu};
    sum_asm = {sum_asm.wall + asm_cost.wall, sum_asm.cpu + asm_cost.cpu};
    sum_solve = {sum_solve.wall + solve_cost.wall, sum_solve.cpu + solve_cost.cpu};
    sum_setup += setup;
  }
  const double rss = comm.max(max_rss_gib());
  const double ns = std::max(n_solves, 1);
  if (comm.is_root())
    std::printf("  %s after %d solves. Mean per Newton iteration: %.4g s wall, %.4g s CPU "
                "(assembly %.4g / %.4g, solve %.4g / %.4g, of which AMG setup %.4g wall), "
                "%.1f GMRES its; peak RSS %.2f GiB per rank\n",
                converged ? "Converged" : "NOT converged", n_solves, sum_it.wall / ns,
                sum_it.cpu / ns, sum_asm.wall / ns, sum_asm.cpu / ns, sum_solve.wall / ns,
                sum_solve.cpu / ns, sum_setup / ns, double(ksp_total) / ns, rss);
  json.add("newton_dofs", double(disc.n_global_dofs()));
  json.add("newton_near_null_vectors", n_near_null);
  json.add("newton_converged", converged ? 1.0 : 0.0);
  json.add("newton_solves", n_solves);
  json.add("newton_iteration_wall_s", sum_it.wall / ns);
  json.add("newton_iteration_cpu_s", sum_it.cpu / ns);
  json.add("newton_assembly_wall_s", sum_asm.wall / ns);
  json.add("newton_assembly_cpu_s", sum_asm.cpu / ns);
  json.add("newton_solve_wall_s", sum_solve.wall / ns);
  json.add("newton_solve_cpu_s", sum_solve.cpu / ns);
  json.add("newton_amg_setup_wall_s", sum_setup / ns);
  json.add("newton_ksp_its", double(ksp_total) / ns);
  json.add("peak_rss_gib", rss);
}

// ----------------------------------------------------------------------------- command

void help() {
  std::printf(
      "usage: seam-bench assembly [--cells-per-side N] [--order 1|2] [--serendipity]\n"
      "                           [--newton] [--compression C] [--max-newton K] [--repeat R]\n"
      "                           [--no-kernels] [--no-assembly] [--json] [-- PETSc options]\n"
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
  bool assembly = true;
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
    else if (a == "--no-assembly")
      assembly = false;
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

  // Line-buffered, so that progress shows in a log file during the long sections.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
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
  if (assembly) run_assembly(disc, model, repeat, json);
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
