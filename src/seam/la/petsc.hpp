#pragma once
// RAII wrappers over PETSc handles. Each owns its handle: copy is deleted, move is kept.
// PETSc errors are turned into C++ exceptions (no PETSc traceback reaches the user).
#include <petscksp.h>

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace seam::la {

/// Throws seam::InternalError with PETSc's message when `ierr` is non-zero.
void check(PetscErrorCode ierr, const char* what);

/// PetscInitialize/PetscFinalize for the lifetime of the object. `petsc_args` are the options
/// a user passed after `--` on the command line. Installs an error handler that returns error
/// codes quietly, so that errors become exceptions.
class Session {
public:
  Session(int& argc, char**& argv, const std::vector<std::string>& petsc_args);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
};

/// A distributed vector with optional ghost entries (VecCreateGhost).
class Vector {
public:
  Vector() = default;
  /// n_owned local entries; `ghosts` are global indices of extra entries kept locally.
  Vector(MPI_Comm comm, PetscInt n_owned, std::span<const PetscInt> ghosts = {});
  ~Vector();
  Vector(Vector&& o) noexcept
      : v_(o.v_), remote_rows_(std::move(o.remote_rows_)),
        remote_values_(std::move(o.remote_values_)), remote_insert_(o.remote_insert_) {
    o.v_ = nullptr;
  }
  Vector& operator=(Vector&& o) noexcept;
  Vector(const Vector&) = delete;
  Vector& operator=(const Vector&) = delete;

  Vec get() const { return v_; }
  Vector duplicate() const;
  void copy_from(const Vector& src);
  void zero();
  /// Entries of rows owned by another rank are kept until assemble().
  void add_values(std::span<const PetscInt> rows, std::span<const double> values);
  void set_values(std::span<const PetscInt> rows, std::span<const double> values);
  /// Collective. Sends the kept entries to their owners, which add (or insert) them in rank
  /// order and then in the order they were given, so that a sum rounds the same in every run.
  void assemble();
  /// Owned + ghost entries become consistent with their owners (forward scatter).
  void update_ghosts();
  /// Ghost contributions are added to their owners (reverse scatter, ADD).
  void accumulate_ghosts();
  double norm() const;
  double dot(const Vector& o) const;
  void axpy(double a, const Vector& x);
  void scale(double a);
  PetscInt owned_size() const;
  PetscInt global_size() const;
  PetscInt owned_begin() const;

  /// Read access to the local form: owned entries first, then ghosts.
  class LocalView {
  public:
    LocalView(const Vector& v, bool write);
    ~LocalView();
    LocalView(const LocalView&) = delete;
    LocalView& operator=(const LocalView&) = delete;
    std::span<double> values() const { return {data_, static_cast<std::size_t>(n_)}; }

  private:
    Vec local_ = nullptr;
    Vec owner_ = nullptr;
    double* data_ = nullptr;
    PetscInt n_ = 0;
    bool write_;
  };

private:
  void keep_remote(std::span<const PetscInt> rows, std::span<const double> values, bool insert);

  Vec v_ = nullptr;
  std::vector<PetscInt> remote_rows_;
  std::vector<double> remote_values_;
  bool remote_insert_ = false;
};

/// Chosen entries of a distributed vector (global indices, the same or different on every
/// rank), brought to each rank that asks for them by one VecScatter: the rank receives only
/// its entries, not the whole vector.
class Gather {
public:
  Gather() = default;
  /// Collective. `indices`: the global entries this rank wants, in the order it wants them,
  /// from vectors laid out like `layout`.
  Gather(const Vector& layout, std::span<const PetscInt> indices);
  ~Gather();
  Gather(Gather&& o) noexcept;
  Gather& operator=(Gather&& o) noexcept;
  Gather(const Gather&) = delete;
  Gather& operator=(const Gather&) = delete;

  /// Collective. The wanted entries of `v` (the layout given at construction), in order.
  void operator()(const Vector& v, std::vector<double>& out) const;
  std::size_t size() const { return n_; }

private:
  VecScatter scatter_ = nullptr;
  Vec local_ = nullptr;
  std::size_t n_ = 0;
};

/// A distributed AIJ matrix with exact preallocation.
class Matrix {
public:
  Matrix() = default;
  /// Square matrix with n_owned local rows/cols; d_nnz/o_nnz per owned row as in
  /// MatMPIAIJSetPreallocation.
  Matrix(MPI_Comm comm, PetscInt n_owned, std::span<const PetscInt> d_nnz,
         std::span<const PetscInt> o_nnz, PetscInt block_size);
  ~Matrix();
  Matrix(Matrix&& o) noexcept
      : m_(o.m_), sum_source_(o.sum_source_), sum_source_state_(o.sum_source_state_),
        sum_state_(o.sum_state_), sum_same_pattern_(o.sum_same_pattern_) {
    o.m_ = nullptr;
  }
  Matrix& operator=(Matrix&& o) noexcept;
  Matrix(const Matrix&) = delete;
  Matrix& operator=(const Matrix&) = delete;

  Mat get() const { return m_; }
  /// Takes ownership of a PETSc matrix.
  static Matrix adopt(Mat m) {
    Matrix out;
    out.m_ = m;
    return out;
  }
  /// P^T A P as a new matrix.
  static Matrix ptap(const Matrix& A, const Matrix& P);
  /// A B as a new matrix.
  static Matrix multiply(const Matrix& A, const Matrix& B);
  /// A B as a new matrix for an A with few nonzeros (a contact condensation's rows): each
  /// rank fetches only the rows of B that the columns of its rows of A name
  /// (MatCreateSubMatrices), where MatMatMult on several ranks copies all its rows of B
  /// (MatMPIAIJGetLocalMat) in the symbolic and again in the numeric product. The pattern is
  /// MatMatMult's (structural zeros kept); each entry sums its terms in the order of A's
  /// columns, on any number of ranks. Collective.
  static Matrix multiply_sparse_left(const Matrix& A, const Matrix& B);
  /// The same product as triplets (global rows and columns, this rank's rows of A B, one per
  /// entry), appended to ci, cj, cv: several products and entries summed by one from_triplets
  /// instead of MatAXPY with different patterns. Collective.
  static void append_product(const Matrix& A, const Matrix& B, std::vector<PetscInt>& ci,
                             std::vector<PetscInt>& cj, std::vector<double>& cv);
  /// A matrix with n_owned local rows (and n_owned local columns, or n_owned_cols if given)
  /// from coordinate triplets in global indices (any rank may give entries of any row;
  /// repeated entries are summed). Collective.
  static Matrix from_triplets(MPI_Comm comm, PetscInt n_owned, std::span<const PetscInt> rows,
                              std::span<const PetscInt> cols, std::span<const double> values,
                              PetscInt n_owned_cols = -1);
  /// New values for a matrix made by from_triplets, in the order of its triplets (the same
  /// count; repeated entries are summed). The pattern is kept, so a direct solver reuses its
  /// symbolic factorization. Collective.
  void set_triplet_values(std::span<const double> values);
  /// A copy of this matrix (pattern and values).
  Matrix copy() const;
  /// y = this x, and y = this^T x.
  void mult(const Vector& x, Vector& y) const;
  void mult_transpose(const Vector& x, Vector& y) const;
  /// this = a * this; this += a * X (X with the same nonzero pattern).
  void scale(double a);
  void axpy(double a, const Matrix& X);
  /// this += a * X for any pattern of X (the pattern of this grows as needed).
  void axpy_any_pattern(double a, const Matrix& X);
  /// this = A + B, in place when this matrix was last made by assign_sum from the same A (its
  /// pattern unchanged since) and B's nonzeros lie in its pattern: A's values are copied
  /// (MatCopy, a memcpy when the patterns are equal) and B's added (MatAXPY,
  /// SUBSET_NONZERO_PATTERN), so the matrix object, its pattern and any preconditioner that
  /// refers to it stay. Otherwise this becomes a new matrix with the union of the patterns.
  /// Returns whether the pattern was reused. Collective.
  bool assign_sum(const Matrix& A, const Matrix& B);
  /// Adds `values` to the diagonal (entries may be new).
  void add_diagonal(const Vector& values);
  void zero();
  /// Dense block K (rows.size() x cols.size(), row-major) added at global (rows, cols).
  void add_values(std::span<const PetscInt> rows, std::span<const PetscInt> cols,
                  std::span<const double> values);
  void assemble();
  /// Zero rows and columns of `rows` (owned global indices), unit diagonal. With `x` and `b`
  /// given, b becomes the right-hand side of the system whose solution has x's values in
  /// those rows: b_free -= A_free,rows x_rows and b_rows = x_rows (inhomogeneous constraints).
  void zero_rows_columns(std::span<const PetscInt> rows, const Vector* x = nullptr,
                         Vector* b = nullptr);
  void set_near_null_space(const Vector& coordinates);
  /// The block size and near-null space of `from` (same row layout) on this matrix, unless it
  /// has its own near-null space already: a condensed system (T^T K T, contact) is formed with
  /// block size 1 and no near-null space, and GAMG would then aggregate it as a scalar problem
  /// whose only near-null vector is the constant (docs/parallel.md, "GAMG on the condensed
  /// system"). Collective.
  void share_near_null_space(const Matrix& from);

private:
  /// Whether every nonzero of X (owned rows) lies in this matrix's pattern. Collective.
  bool holds_pattern_of(const Matrix& X) const;

  Mat m_ = nullptr;
  /// assign_sum: the id and nonzero state of the A this matrix's pattern was made from, and
  /// this matrix's nonzero state and whether its pattern equals A's then.
  PetscInt64 sum_source_ = -1;
  PetscObjectState sum_source_state_ = -1, sum_state_ = -1;
  bool sum_same_pattern_ = false;
};

/// Adds dense element matrices to an assembled AIJ matrix by nodes: blocks of the matrix's
/// block size bs (the dimension), each node's bs dofs consecutive from a multiple of bs (seam's
/// numbering). For every block it searches the column once in the first of its bs rows (they
/// share their columns) and adds the bs x bs values straight into the owned rows
/// (MatSeqAIJGetArray of the diagonal and off-diagonal parts), where MatSetValues searches
/// every entry. Rows of other ranks go through MatSetValues (PETSc's stash); a block outside
/// the pattern, or dofs not in this layout, too, after the arrays are returned. For one pass
/// of insertions into a matrix nothing else writes to meanwhile: finish() (or the destructor)
/// returns the arrays; then Matrix::assemble() as after add_values.
class BlockAdder {
public:
  explicit BlockAdder(Matrix& m);
  ~BlockAdder();
  BlockAdder(const BlockAdder&) = delete;
  BlockAdder& operator=(const BlockAdder&) = delete;
  /// K (dofs.size() squared, row-major) added at (dofs, dofs), as Matrix::add_values.
  void add(std::span<const PetscInt> dofs, std::span<const double> values);
  /// Returns the arrays and inserts the deferred blocks. Collective only as MatSetValues is.
  void finish();

private:
  /// One part (diagonal or off-diagonal columns) of the owned rows in CSR form.
  struct Part {
    Mat mat = nullptr;
    const PetscInt *ia = nullptr, *ja = nullptr;
    double* values = nullptr;
    PetscInt n_rows = 0;
  };
  /// The position in `p` of local column `col` in local row `row`, or -1.
  static PetscInt find(const Part& p, PetscInt row, PetscInt col);
  void release();
  /// Keeps the entries (rows x cols, row-major with the given row stride) for finish().
  void defer(std::span<const PetscInt> rows, std::span<const PetscInt> cols, const double* values,
             std::size_t stride);

  Mat m_ = nullptr;
  PetscInt bs_ = 1, row_begin_ = 0, row_end_ = 0, col_begin_ = 0, col_end_ = 0;
  Part diag_, off_;
  const PetscInt* col_map_ = nullptr; ///< global column of each off-diagonal column (sorted)
  PetscInt n_col_map_ = 0;
  bool direct_ = false; ///< the arrays are held: blocks go straight into them
  std::vector<PetscInt> deferred_rows_, deferred_cols_; ///< one entry each
  std::vector<double> deferred_values_;
};

enum class SolverKind { direct, iterative };

/// KSP wrapper: MUMPS LU (direct) or GMRES + GAMG with the rigid-body near-null space
/// (iterative); PETSc command-line options override either.
class LinearSolver {
public:
  LinearSolver(MPI_Comm comm, SolverKind kind);
  ~LinearSolver();
  LinearSolver(const LinearSolver&) = delete;
  LinearSolver& operator=(const LinearSolver&) = delete;
  /// The preconditioner of the velocity block A of set_fields: one BoomerAMG V-cycle (hypre;
  /// l1-scaled Jacobi smoothing, HMIS coarsening, extended+i interpolation) or block Jacobi
  /// ILU(0) per rank.
  enum class VelocityBlock { amg, ilu };
  /// A saddle-point system [A B^T; C D] (velocity | pressure) for the iterative kind: FGMRES
  /// preconditioned by PCFIELDSPLIT's lower-triangular Schur factorization with the
  /// SIMPLE-type Schur approximation S = D - C diag(A)^-1 B^T assembled (selfp): `velocity` on
  /// A, one BoomerAMG V-cycle (hypre) on S (Elman, Silvester & Wathen 2014, ch. 9).
  /// `first`/`second`: the owned global rows of each field. Options with the prefixes
  /// -fieldsplit_u_, -fieldsplit_p_ and -pc_fieldsplit_ override the defaults. Collective.
  void set_fields(std::span<const PetscInt> first, std::span<const PetscInt> second,
                  VelocityBlock velocity);
  /// y ~ S^-1 x on the Schur block of set_fields (Vecs laid out as its pressure rows).
  using SchurApply = std::function<void(Vec x, Vec y)>;
  /// Replaces set_fields' selfp approximation and its BoomerAMG cycle by `apply`, a PCSHELL on
  /// the Schur block (whose operator stays PCFIELDSPLIT's matrix-free Schur complement; its
  /// preconditioning matrix is the pressure block). Call after set_fields. Collective.
  void set_schur_preconditioner(SchurApply apply);
  /// The monolithic fluid-structure system (structure | fluid | fluid mesh) for the iterative
  /// kind: FGMRES preconditioned by a multiplicative (block Gauss-Seidel) PCFIELDSPLIT over
  /// the three fields: GAMG with the rigid-body near-null space `modes` (mode-major over the
  /// owned structure rows) on the structure block, on the fluid block the fluid's Schur
  /// fieldsplit (as set_fields; the pressure rows found as the zero diagonal of the
  /// Taylor-Hood block), one BoomerAMG V-cycle on the mesh block. Options with the prefixes
  /// -fieldsplit_s_, -fieldsplit_f_, -fieldsplit_m_ override the defaults. Collective.
  void set_fsi_fields(std::span<const PetscInt> structure, std::span<const PetscInt> fluid,
                      std::span<const PetscInt> mesh, std::span<const double> modes,
                      VelocityBlock velocity);
  /// A saddle point [K B^T; C E] assembled as one AIJ matrix whose rows per rank are the
  /// `n_first` owned rows of K, then the `n_second` owned multiplier rows, for the iterative
  /// kind: FGMRES preconditioned by PCFIELDSPLIT's lower-triangular Schur factorization (fields
  /// u | lm): GAMG on K with the near-null space and block size of `K` (the displacement
  /// block, whose rows are those of the u field), on the Schur block the assembled
  /// approximation S = E - C diag(K)^-1 B^T (selfp) with block Jacobi ILU(0). The first call
  /// sets the fields, later calls (the same layout) nothing; the direct kind ignores it.
  /// Options with the prefixes -fieldsplit_u_, -fieldsplit_lm_ and -pc_fieldsplit_ override
  /// the defaults. Collective.
  void set_saddle_point_fields(PetscInt n_first, PetscInt n_second, const Matrix& K);
  SolverKind kind() const { return kind_; }
  /// The relative tolerance of the next solves, unless the command line set -ksp_rtol. The
  /// direct kind: that of the next GMRES over a kept factorization (allow_factor_reuse), not
  /// below factor_reuse_rtol.
  void set_relative_tolerance(double rtol);
  /// Keeps the preconditioner (GAMG's hierarchy, a factorization) from one solve to the next
  /// although the matrix changes (PCSetReusePreconditioner), until rebuild_preconditioner()
  /// or a solve with the kept one needs more than 2 n_0 + 20 Krylov iterations (n_0: those
  /// of the solve that built it, scaled by the decades of the relative tolerances): then the
  /// next solve builds it anew; a kept one that does not converge is rebuilt at once and the
  /// solve repeated. -ksp_reuse_preconditioner on the command line overrides the switch
  /// (true: PETSc's reuse without rebuilds, false: none).
  /// The iterative kind only: a kept factorization would be a wrong solve.
  void keep_preconditioner(bool on) { keep_ = on; }
  /// The next solve builds the preconditioner from its matrix.
  void rebuild_preconditioner() { stale_ = true; }
  /// The direct kind: the next solve may take the factorization of an earlier solve (whose
  /// matrix differs) as the preconditioner of GMRES, right-preconditioned, to the relative
  /// residual of set_relative_tolerance, never below factor_reuse_rtol = 1e-13 (that one if
  /// none was set; a factorization itself reaches 1e-14 to 4e-14 on the hex20 torus),
  /// instead of factoring its own matrix: the solve of the new matrix at the cost of a few
  /// triangular solves. The caller allows it where
  /// the new matrix differs little from the factored one (Newton corrections of a load step
  /// whose contact statuses have not changed since the factorization). A GMRES that needs
  /// more than factor_reuse_max_iterations is abandoned and the matrix factored; one that
  /// needs more than factor_reuse_refactor_iterations converges, but the next solve factors
  /// anew. -ksp_reuse_preconditioner or -factor_reuse false on the command line turn it off.
  void allow_factor_reuse(bool on) { reuse_allowed_ = on; }
  static constexpr int factor_reuse_max_iterations = 20;
  static constexpr int factor_reuse_refactor_iterations = 8;
  static constexpr double factor_reuse_rtol = 1e-13;
  /// Whether the last solve set up its preconditioner (factored its matrix).
  bool last_solve_built() const { return last_built_; }
  /// Preconditioner set-ups since construction.
  int preconditioner_builds() const { return builds_; }
  /// The direct kind: symbolic analyses since construction. A factorization of a matrix whose
  /// nonzero pattern differs from that of the last one (or another matrix) orders and analyses
  /// it anew before factoring it.
  int symbolic_analyses() const { return analyses_; }
  /// The direct kind: MUMPS's fill-reducing ordering of the next analysis, ICNTL(7): "default"
  /// (7, MUMPS's choice: PORD's nested dissection with Debian's MUMPS, which has neither METIS
  /// nor SCOTCH), "qamd" (6), or "command line" when -mat_mumps_icntl_7 was given. The default
  /// is kept unless the pattern changes at consecutive factorizations and a set-up with an
  /// analysis costs more than ordering_trial_seconds and more than twice one without (or none
  /// without was seen): then one analysis
  /// is made with QAMD, and QAMD is kept if its set-up cost less than 0.8 of the default's
  /// (CPU seconds of the set-up, the largest over the ranks). Decided once per solver.
  std::string ordering() const;
  static constexpr double ordering_trial_seconds = 0.05;
  /// The choice's state (decided, QAMD, analyses in a row, the measured costs), for a
  /// checkpoint, and its restoration at a restart, so that the restarted run orders its
  /// matrices as the uninterrupted one (bit for bit). Ignored with the ordering on the command
  /// line or a state of another size.
  std::vector<double> ordering_state() const;
  void restore_ordering_state(std::span<const double> state);
  /// A sentence saying that the last solve changed the ordering, and why, once; else empty.
  std::string take_ordering_note() { return std::exchange(ordering_note_, {}); }
  /// Solves A x = b. Returns false if the solver did not converge (the caller cuts the step).
  bool solve(const Matrix& A, const Vector& b, Vector& x);
  /// The same with the preconditioner built from P instead of A.
  bool solve(const Matrix& A, const Matrix& P, const Vector& b, Vector& x);
  int last_iterations() const { return iterations_; }

private:
  /// One KSPSolve; `reuse`: with the preconditioner kept. Returns whether it converged.
  bool solve_once(const Matrix& A, const Matrix& P, const Vector& b, Vector& x, bool reuse);
  /// allow_factor_reuse: GMRES on A preconditioned by the kept factorization, to the relative
  /// tolerance of set_relative_tolerance (factor_reuse_rtol unless set). Returns whether it
  /// converged within factor_reuse_max_iterations.
  bool solve_reusing_factors(const Matrix& A, const Vector& b, Vector& x);
  /// The direct kind: KSPSetUp of a fresh factorization of P, timed, with the ordering chosen
  /// by ordering(). Returns false if it failed (a zero pivot: the caller cuts the step).
  bool set_up_factorization(const Matrix& P);
  /// After a set-up that took `cost` CPU seconds, with or without an analysis: ordering().
  void choose_ordering(bool analysed, double cost);
  /// After KSPSolve on `ksp` returned `ierr`: its iterations kept, whether it converged.
  bool finish_solve(KSP ksp, PetscErrorCode ierr);
  double relative_tolerance() const;

  KSP ksp_ = nullptr;
  KSP reuse_ksp_ = nullptr; ///< the direct kind: GMRES sharing ksp_'s PC (allow_factor_reuse)
  SolverKind kind_;
  SchurApply schur_apply_;
  bool schur_installed_ = false; ///< the PCSHELL sits on the Schur block
  bool saddle_fields_ = false;   ///< set_saddle_point_fields has set the fields
  int iterations_ = 0;
  bool keep_ = false;
  bool stale_ = true;           ///< the next solve builds the preconditioner
  bool user_reuse_set_ = false; ///< -ksp_reuse_preconditioner given: PETSc decides alone
  int builds_ = 0;
  bool last_built_ = false;
  bool reuse_allowed_ = false;
  bool reuse_enabled_ = true;             ///< -factor_reuse false turns it off
  double reuse_rtol_ = factor_reuse_rtol; ///< set_relative_tolerance, the direct kind
  int first_iterations_ = 0; ///< Krylov iterations of the solve that built the kept one
  double first_rtol_ = 0.0;  ///< and its relative tolerance
  // The ordering of the direct kind (ordering()).
  bool ordering_auto_ = false; ///< no -mat_mumps_icntl_7 on the command line
  bool qamd_ = false;          ///< the next analysis orders with QAMD
  bool ordering_decided_ = false;
  int analyses_ = 0;
  int analyses_in_row_ = 0;                ///< consecutive fresh set-ups with an analysis
  Mat analysed_ = nullptr;                 ///< the matrix of the last analysis (held by the PC)
  PetscObjectState analysed_state_ = 0;    ///< and its nonzero state then
  double analysed_cost_[2] = {-1.0, -1.0}; ///< set-up CPU seconds with an analysis: default, QAMD
  double numeric_cost_ = -1.0;             ///< without one, default ordering
  std::string ordering_note_;
  std::string ordering_option_; ///< -[prefix]mat_mumps_icntl_7
};

} // namespace seam::la
