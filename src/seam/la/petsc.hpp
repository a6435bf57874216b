#pragma once
// RAII wrappers over PETSc handles. Each owns its handle: copy is deleted, move is kept.
// PETSc errors are turned into C++ exceptions (no PETSc traceback reaches the user).
#include <petscksp.h>

#include <cstdint>
#include <span>
#include <string>
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
  Vector(Vector&& o) noexcept : v_(o.v_) { o.v_ = nullptr; }
  Vector& operator=(Vector&& o) noexcept;
  Vector(const Vector&) = delete;
  Vector& operator=(const Vector&) = delete;

  Vec get() const { return v_; }
  Vector duplicate() const;
  void copy_from(const Vector& src);
  void zero();
  void add_values(std::span<const PetscInt> rows, std::span<const double> values);
  void set_values(std::span<const PetscInt> rows, std::span<const double> values);
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
  Vec v_ = nullptr;
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
  Matrix(Matrix&& o) noexcept : m_(o.m_) { o.m_ = nullptr; }
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

private:
  Mat m_ = nullptr;
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
  /// The relative tolerance of the next solves, unless the command line set -ksp_rtol.
  void set_relative_tolerance(double rtol);
  /// Solves A x = b. Returns false if the solver did not converge (the caller cuts the step).
  bool solve(const Matrix& A, const Vector& b, Vector& x);
  /// The same with the preconditioner built from P instead of A.
  bool solve(const Matrix& A, const Matrix& P, const Vector& b, Vector& x);
  int last_iterations() const { return iterations_; }

private:
  KSP ksp_ = nullptr;
  SolverKind kind_;
  int iterations_ = 0;
};

} // namespace seam::la
