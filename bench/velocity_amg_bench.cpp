// seam-bench velocity_amg: the cost of PCD's velocity block (BoomerAMG, docs/fluid.md "PCD's
// cost on the finest mesh") per nonzero, on Newton Jacobians of a fluid run written by PETSc
// (`PETSC_OPTIONS="-ksp_view_mat binary:J.bin"`, the last Newton system stays in the file;
// bench/pcd_cost.py writes those of the DFG 2D-1 levels). Per matrix, all in one process:
// the velocity block A (the rows whose diagonal is not zero: the pressure block of seam's
// Taylor-Hood Jacobian is zero) and its CSR bytes; a plain MatMult on A in ns per nonzero;
// for each setting, BoomerAMG on A with seam's defaults for the block (l1-scaled Jacobi,
// HMIS, ext+i) and the setting's options (prefix -u_): its levels, grid and operator
// complexities, the hierarchy's bytes (the operators and the interpolations), the set-up's
// CPU time, and one V-cycle (PCApply) in CPU ms and in ns per nonzero it touches (each level:
// two smoothing sweeps and the residual on A_l, restriction and interpolation with P_l).
// Times are the process's CPU time, the smallest over --repeat runs.
//
// usage: seam-bench velocity_amg [--repeat 3] [--cycles 20] [--rcm] [--bs 2]
//            [--copies 4] [--stream] [--per-level]
//            [--setting "label|-u_pc_hypre_boomeramg_P_max 4 ..."]... J0.bin J1.bin ...
// --rcm: every matrix also reordered by reverse Cuthill-McKee. --bs 2: block size 2 on A
// (BoomerAMG's number of functions). --copies K: MatMult and the V-cycle also on K copies of
// A (K hierarchies) in turn, the same work on a working set K times larger. --stream: a
// STREAM-like triad's bandwidth against its working set first. --per-level: each hierarchy's
// operators and interpolations level by level (rows, nonzeros, MB).
#include "registry.hpp"

#include "seam/la/petsc.hpp"

#include <petscksp.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using seam::la::check;

// --per-level: the hierarchy's rows, nonzeros and bytes level by level.
bool per_level = false;

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

/// The smallest CPU time of `repeat` calls of f.
template <class F> double best_cpu(int repeat, F&& f) {
  double best = 1e300;
  for (int i = 0; i < repeat; ++i) {
    const double c0 = cpu_seconds();
    f();
    best = std::min(best, cpu_seconds() - c0);
  }
  return best;
}

struct Setting {
  std::string label;
  std::vector<std::string> options; // "-name value" pairs, or "-name" flags
};

Setting parse_setting(const std::string& text) {
  const auto bar = text.find('|');
  Setting s{text.substr(0, bar), {}};
  if (bar == std::string::npos) return s;
  std::istringstream in(text.substr(bar + 1));
  for (std::string word; in >> word;) s.options.push_back(word);
  return s;
}

/// Inserts the setting's options and returns their names, to clear after.
std::vector<std::string> insert(const Setting& s) {
  std::string all;
  std::vector<std::string> names;
  for (const auto& w : s.options) {
    all += w + " ";
    if (w.size() > 1 && w[0] == '-' && !(w[1] >= '0' && w[1] <= '9') && w[1] != '.')
      names.push_back(w);
  }
  check(PetscOptionsInsertString(nullptr, all.c_str()), "PetscOptionsInsertString");
  return names;
}

PetscInt nonzeros(Mat A) {
  MatInfo info{};
  check(MatGetInfo(A, MAT_LOCAL, &info), "MatGetInfo");
  return PetscInt(info.nz_used);
}

/// Bytes of a CSR matrix: values, column indices, row starts.
double csr_bytes(Mat A) {
  PetscInt m = 0, n = 0;
  check(MatGetSize(A, &m, &n), "MatGetSize");
  return double(nonzeros(A)) * double(sizeof(PetscScalar) + sizeof(PetscInt)) +
         double(m + 1) * double(sizeof(PetscInt));
}

/// The velocity block of the Jacobian J: the rows (and columns) whose diagonal is not zero.
Mat velocity_block(Mat J) {
  Vec d = nullptr;
  check(MatCreateVecs(J, &d, nullptr), "MatCreateVecs");
  check(MatGetDiagonal(J, d), "MatGetDiagonal");
  PetscInt n = 0;
  check(VecGetLocalSize(d, &n), "VecGetLocalSize");
  const PetscScalar* v = nullptr;
  check(VecGetArrayRead(d, &v), "VecGetArrayRead");
  std::vector<PetscInt> rows;
  for (PetscInt i = 0; i < n; ++i)
    if (v[i] != 0.0) rows.push_back(i);
  check(VecRestoreArrayRead(d, &v), "VecRestoreArrayRead");
  check(VecDestroy(&d), "VecDestroy");
  IS is = nullptr;
  check(
      ISCreateGeneral(PETSC_COMM_SELF, PetscInt(rows.size()), rows.data(), PETSC_COPY_VALUES, &is),
      "ISCreateGeneral");
  Mat A = nullptr;
  check(MatCreateSubMatrix(J, is, is, MAT_INITIAL_MATRIX, &A), "MatCreateSubMatrix");
  check(ISDestroy(&is), "ISDestroy");
  return A;
}

/// A reordered by reverse Cuthill-McKee.
Mat rcm(Mat A) {
  IS rows = nullptr, cols = nullptr;
  check(MatGetOrdering(A, MATORDERINGRCM, &rows, &cols), "MatGetOrdering");
  Mat B = nullptr;
  check(MatPermute(A, rows, cols, &B), "MatPermute");
  check(ISDestroy(&rows), "ISDestroy");
  check(ISDestroy(&cols), "ISDestroy");
  return B;
}

/// The mean distance |i - j| of A's nonzeros from the diagonal.
double mean_distance(Mat A) {
  PetscInt m = 0, n = 0;
  check(MatGetSize(A, &m, &n), "MatGetSize");
  double sum = 0;
  PetscInt count = 0;
  for (PetscInt i = 0; i < m; ++i) {
    PetscInt nc = 0;
    const PetscInt* cols = nullptr;
    check(MatGetRow(A, i, &nc, &cols, nullptr), "MatGetRow");
    for (PetscInt k = 0; k < nc; ++k) sum += double(std::abs(cols[k] - i));
    count += nc;
    check(MatRestoreRow(A, i, &nc, &cols, nullptr), "MatRestoreRow");
  }
  return sum / double(std::max<PetscInt>(count, 1));
}

/// BoomerAMG on A (a preconditioner of prefix u_ set up from the options).
KSP amg(Mat A) {
  KSP ksp = nullptr;
  check(KSPCreate(PETSC_COMM_SELF, &ksp), "KSPCreate");
  check(KSPSetOptionsPrefix(ksp, "u_"), "KSPSetOptionsPrefix");
  check(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
  PC pc = nullptr;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  check(PCSetType(pc, PCHYPRE), "PCSetType");
  check(PCHYPRESetType(pc, "boomeramg"), "PCHYPRESetType");
  check(KSPSetOperators(ksp, A, A), "KSPSetOperators");
  check(KSPSetFromOptions(ksp), "KSPSetFromOptions");
  check(PCSetUp(pc), "PCSetUp");
  return ksp;
}

void amg_row(Mat A, const Setting& setting, int repeat, int cycles, int copies) {
  const auto names = insert(setting);
  // seam's defaults for the velocity block (la/petsc.cpp, schur_defaults); a setting's option
  // given above stays.
  std::vector<std::string> defaults;
  for (const auto& [name, value] :
       {std::pair{"-u_pc_hypre_boomeramg_relax_type_all", "l1scaled-Jacobi"},
        std::pair{"-u_pc_hypre_boomeramg_coarsen_type", "HMIS"},
        std::pair{"-u_pc_hypre_boomeramg_interp_type", "ext+i"}}) {
    PetscBool set = PETSC_FALSE;
    check(PetscOptionsHasName(nullptr, nullptr, name, &set), "PetscOptionsHasName");
    if (set) continue;
    check(PetscOptionsSetValue(nullptr, name, value), "PetscOptionsSetValue");
    defaults.emplace_back(name);
  }
  // The set-up, each time on a new preconditioner; the last one is kept.
  KSP ksp = nullptr;
  double setup = 1e300;
  for (int r = 0; r < repeat; ++r) {
    if (ksp) check(KSPDestroy(&ksp), "KSPDestroy");
    const double c0 = cpu_seconds();
    ksp = amg(A);
    setup = std::min(setup, cpu_seconds() - c0);
  }
  PC pc = nullptr;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  // The same V-cycle on `copies` copies of A, each with its own hierarchy, applied in turn:
  // the same work on a working set `copies` times larger.
  std::vector<Mat> copy(std::size_t(copies - 1), nullptr);
  std::vector<KSP> copy_ksp(copy.size(), nullptr);
  std::vector<PC> pcs{pc};
  for (std::size_t k = 0; k < copy.size(); ++k) {
    check(MatDuplicate(A, MAT_COPY_VALUES, &copy[k]), "MatDuplicate");
    copy_ksp[k] = amg(copy[k]);
    pcs.emplace_back();
    check(KSPGetPC(copy_ksp[k], &pcs.back()), "KSPGetPC");
  }
  // The V-cycle first: the hierarchy's matrices PETSc hands out below share hypre's
  // arrays.
  Vec b = nullptr, x = nullptr;
  check(MatCreateVecs(A, &x, &b), "MatCreateVecs");
  check(VecSet(b, 1.0), "VecSet");
  const double vcycle = best_cpu(repeat,
                                 [&] {
                                   for (int k = 0; k < cycles; ++k)
                                     check(PCApply(pc, b, x), "PCApply");
                                 }) /
                        cycles;
  const double vcycle_copies = best_cpu(repeat,
                                        [&] {
                                          for (int k = 0; k < cycles; ++k)
                                            for (PC p : pcs) check(PCApply(p, b, x), "PCApply");
                                        }) /
                               (cycles * double(pcs.size()));
  for (auto& k : copy_ksp) check(KSPDestroy(&k), "KSPDestroy");
  for (auto& m : copy) check(MatDestroy(&m), "MatDestroy");
  // PETSc returns the levels (nl of them, the finest included) coarsest first, and only the
  // nl - 1 coarse operators and interpolations: their last entries are not set.
  PetscInt nl = 0, ni = 0;
  Mat* ops = nullptr;
  Mat* interps = nullptr;
  check(PCGetCoarseOperators(pc, &nl, &ops), "PCGetCoarseOperators");
  check(PCGetInterpolations(pc, &ni, &interps), "PCGetInterpolations");
  PetscInt n0 = 0, nc = 0;
  check(MatGetSize(A, &n0, &nc), "MatGetSize");
  const double nnz0 = double(nonzeros(A));
  double rows = double(n0), nnz_ops = nnz0, nnz_p = 0, bytes = csr_bytes(A);
  double touched = 3 * nnz0;
  for (PetscInt l = 0; l + 1 < nl; ++l) {
    PetscInt m = 0;
    check(MatGetSize(ops[l], &m, &nc), "MatGetSize");
    rows += double(m);
    const double z = double(nonzeros(ops[l]));
    nnz_ops += z;
    touched += 3 * z;
    bytes += csr_bytes(ops[l]);
  }
  for (PetscInt l = 0; l + 1 < ni; ++l) {
    const double z = double(nonzeros(interps[l]));
    nnz_p += z;
    touched += 2 * z;
    bytes += csr_bytes(interps[l]);
  }
  if (per_level) {
    // Level k >= 1 is ops[nl - 1 - k]; the interpolation from level k + 1 to k is
    // interps[nl - 2 - k].
    for (PetscInt k = 0; k < nl; ++k) {
      const Mat Ak = k == 0 ? A : ops[nl - 1 - k];
      PetscInt m = 0;
      check(MatGetSize(Ak, &m, &nc), "MatGetSize");
      std::printf("      level %d: %d rows, %.0f nonzeros, %.2f MB", int(k), int(m),
                  double(nonzeros(Ak)), csr_bytes(Ak) / 1048576.0);
      if (k + 1 < nl) {
        const Mat P = interps[nl - 2 - k];
        std::printf("; P: %.0f nonzeros, %.2f MB", double(nonzeros(P)), csr_bytes(P) / 1048576.0);
      }
      std::printf("\n");
    }
  }
  for (PetscInt l = 0; l + 1 < nl; ++l) check(MatDestroy(&ops[l]), "MatDestroy");
  for (PetscInt l = 0; l + 1 < ni; ++l) check(MatDestroy(&interps[l]), "MatDestroy");
  check(PetscFree(ops), "PetscFree");
  check(PetscFree(interps), "PetscFree");

  std::printf("    %-22s %3d %6.3f %6.3f %8.1f %8.3f %10.3f %8.2f %10.2f\n", setting.label.c_str(),
              int(nl), rows / double(n0), nnz_ops / nnz0, bytes / 1048576.0, setup, 1e3 * vcycle,
              1e9 * vcycle / touched, 1e9 * vcycle_copies / touched);
  (void)nnz_p;
  std::fflush(stdout);
  check(VecDestroy(&x), "VecDestroy");
  check(VecDestroy(&b), "VecDestroy");
  check(KSPDestroy(&ksp), "KSPDestroy");
  for (const auto& n : names) check(PetscOptionsClearValue(nullptr, n.c_str()), "ClearValue");
  for (const auto& n : defaults) check(PetscOptionsClearValue(nullptr, n.c_str()), "ClearValue");
}

void matrix_rows(Mat A, const char* label, const std::vector<Setting>& settings, int repeat,
                 int cycles, int copies) {
  PetscInt n = 0, nc = 0;
  check(MatGetSize(A, &n, &nc), "MatGetSize");
  const double nnz = double(nonzeros(A));
  Vec x = nullptr, y = nullptr;
  check(MatCreateVecs(A, &x, &y), "MatCreateVecs");
  check(VecSet(x, 1.0), "VecSet");
  std::vector<Mat> all{A};
  for (int k = 1; k < copies; ++k) {
    all.emplace_back();
    check(MatDuplicate(A, MAT_COPY_VALUES, &all.back()), "MatDuplicate");
  }
  // About 2e8 nonzeros per measurement; on A, then on the copies in turn.
  const int calls = std::max(10, int(2e8 / nnz / double(copies)));
  const double mult = best_cpu(repeat,
                               [&] {
                                 for (int k = 0; k < calls * copies; ++k)
                                   check(MatMult(A, x, y), "MatMult");
                               }) /
                      (calls * copies);
  const double mult_copies = best_cpu(repeat,
                                      [&] {
                                        for (int k = 0; k < calls; ++k)
                                          for (Mat M : all) check(MatMult(M, x, y), "MatMult");
                                      }) /
                             (calls * copies);
  for (std::size_t k = 1; k < all.size(); ++k) check(MatDestroy(&all[k]), "MatDestroy");
  check(VecDestroy(&x), "VecDestroy");
  check(VecDestroy(&y), "VecDestroy");
  std::printf("%-24s %9d %10.0f %8.2f %9.0f %8.3f %10.3f\n", label, int(n), nnz,
              csr_bytes(A) / 1048576.0, mean_distance(A), 1e9 * mult / nnz,
              1e9 * mult_copies / nnz);
  std::printf("    %-22s %3s %6s %6s %8s %8s %10s %8s %10s\n", "BoomerAMG setting", "lev", "grid",
              "oper", "hier MB", "setup s", "V-cycle ms", "ns/nnz", "copies");
  for (const auto& s : settings) amg_row(A, s, repeat, cycles, copies);
  std::fflush(stdout);
}

/// The machine's memory hierarchy as this process sees it: a STREAM-like triad
/// a = b + s c over three arrays of `mb` MB together, in GB/s of the bytes it moves (24 per
/// entry; the same arrays again and again, so that what fits a cache stays there).
void stream_rows(int repeat) {
  std::printf("%-12s %10s\n", "triad MB", "GB/s");
  for (const double mb : {0.375, 1.5, 3.0, 6.0, 24.0, 48.0, 96.0, 192.0, 384.0}) {
    const auto n = std::size_t(mb * 1048576.0 / 24.0);
    std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
    const int calls = std::max(3, int(4e9 / (24.0 * double(n))));
    const double t = best_cpu(repeat, [&] {
      for (int k = 0; k < calls; ++k) {
        const double scale = 1.0 + 1e-9 * k;
        for (std::size_t i = 0; i < n; ++i) a[i] = b[i] + scale * c[i];
      }
    });
    volatile double sink = a[n / 2];
    (void)sink;
    std::printf("%-12.3f %10.2f\n", mb, 24.0 * double(n) * calls / t * 1e-9);
    std::fflush(stdout);
  }
}

int run(int argc, char** argv) {
  int repeat = 3, cycles = 20, bs = 1, copies = 1;
  bool reorder = false, stream = false;
  std::vector<Setting> settings;
  std::vector<std::string> files, petsc_args;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
      return argv[++i];
    };
    if (a == "--help" || a == "-h") {
      std::printf("usage: seam-bench velocity_amg [--repeat 3] [--cycles 20] [--rcm] [--bs 2]\n"
                  "  [--copies K] [--stream] [--per-level]\n"
                  "  [--setting 'label|-u_pc_hypre_boomeramg_... value']... J.bin ...\n");
      return 0;
    } else if (a == "--repeat") {
      repeat = std::stoi(value());
    } else if (a == "--cycles") {
      cycles = std::stoi(value());
    } else if (a == "--copies") {
      copies = std::max(1, std::stoi(value()));
    } else if (a == "--bs") {
      bs = std::stoi(value());
    } else if (a == "--per-level") {
      per_level = true;
    } else if (a == "--stream") {
      stream = true;
    } else if (a == "--rcm") {
      reorder = true;
    } else if (a == "--setting") {
      settings.push_back(parse_setting(value()));
    } else if (a == "--") {
      for (++i; i < argc; ++i) petsc_args.emplace_back(argv[i]);
    } else {
      files.push_back(a);
    }
  }
  if (stream) stream_rows(repeat);
  if (files.empty() && stream) return 0;
  if (files.empty()) throw std::runtime_error("no matrix file given (seam-bench velocity_amg -h)");
  if (settings.empty()) settings.push_back({"seam's default", {}});
  seam::la::Session session(argc, argv, petsc_args);
  std::printf("%-24s %9s %10s %8s %9s %8s %10s\n", "matrix (velocity block)", "rows", "nonzeros",
              "CSR MB", "mean|i-j|", "MatMult ns/nnz", "copies");
  for (const auto& file : files) {
    PetscViewer viewer = nullptr;
    check(PetscViewerBinaryOpen(PETSC_COMM_SELF, file.c_str(), FILE_MODE_READ, &viewer),
          ("opening " + file).c_str());
    Mat J = nullptr;
    check(MatCreate(PETSC_COMM_SELF, &J), "MatCreate");
    check(MatSetType(J, MATSEQAIJ), "MatSetType");
    check(MatLoad(J, viewer), ("reading " + file).c_str());
    check(PetscViewerDestroy(&viewer), "PetscViewerDestroy");
    Mat A = velocity_block(J);
    check(MatDestroy(&J), "MatDestroy");
    if (bs > 1) check(MatSetBlockSize(A, bs), "MatSetBlockSize");
    const auto name = file.substr(file.find_last_of('/') + 1);
    matrix_rows(A, name.c_str(), settings, repeat, cycles, copies);
    if (reorder) {
      Mat B = rcm(A);
      matrix_rows(B, (name + " RCM").c_str(), settings, repeat, cycles, copies);
      check(MatDestroy(&B), "MatDestroy");
    }
    check(MatDestroy(&A), "MatDestroy");
  }
  return 0;
}

const seam::bench::Register reg{"velocity_amg",
                                "BoomerAMG on a fluid velocity block: cost per nonzero", &run};

} // namespace
