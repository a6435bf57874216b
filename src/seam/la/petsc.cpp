#include "seam/la/petsc.hpp"

#include "seam/common/error.hpp"
#include "seam/common/timer.hpp"

#include <dlfcn.h>
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <set>
#include <string>

namespace seam::la {

namespace {

// The specific message of the last PETSc error (PETSc's own text, e.g. which entry of a
// matrix was out of range); the error code alone only names the class of error.
thread_local std::string last_petsc_message;

PetscErrorCode capture_error(MPI_Comm, int line, const char* function, const char* file,
                             PetscErrorCode n, PetscErrorType p, const char* message, void*) {
  if (p == PETSC_ERROR_INITIAL)
    last_petsc_message = std::string(message ? message : "") + " [" + (function ? function : "") +
                         " " + (file ? file : "") + ":" + std::to_string(line) + "]";
  return n;
}

// One BLAS thread per MPI rank. A threaded OpenBLAS runs its level-1 routines (ddot, daxpy,
// dnrm2: PETSc's VecTDot, VecAXPY, VecNorm) on several threads above n = 10,000, and on a
// machine whose cores the ranks (or other jobs) already occupy each such call waits for its
// threads: DFG 2D-1 with PCD on 203,998 dofs, whose pressure vectors (22.7k) cross that size,
// took 46.4 s of CPU against 41.7 s with one thread (docs/fluid.md, "PCD's cost on the finest
// mesh"). The
// library is asked through its own entry point, if it is the one loaded; a thread count the
// user set in the environment is left alone.
void single_threaded_blas() {
  if (std::getenv("OPENBLAS_NUM_THREADS") != nullptr || std::getenv("OMP_NUM_THREADS") != nullptr)
    return;
  void* symbol = dlsym(RTLD_DEFAULT, "openblas_set_num_threads");
  if (symbol == nullptr) return;
  void (*set_threads)(int) = nullptr;
  std::memcpy(&set_threads, &symbol, sizeof symbol);
  set_threads(1);
}

} // namespace

void check(PetscErrorCode ierr, const char* what) {
  if (ierr == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(ierr, &text, nullptr);
  std::string detail;
  std::swap(detail, last_petsc_message);
  SEAM_THROW(InternalError, "PETSc error in ", what, ": ", text ? text : "unknown error", " (code ",
             static_cast<int>(ierr), "): ", detail);
}

Session::Session(int& argc, char**& argv, const std::vector<std::string>& petsc_args) {
  // Options after `--` go to PETSc; seam's own arguments never reach its parser.
  int pargc = 1;
  char* pargv0 = argc > 0 ? argv[0] : nullptr;
  char** pargv = &pargv0;
  single_threaded_blas();
  check(PetscInitialize(&pargc, &pargv, nullptr, nullptr), "PetscInitialize");
  PetscPushErrorHandler(capture_error, nullptr);
  // MUMPS reserves 20 % over its analysis estimate for pivots it delays; saddle points with a
  // zero multiplier block (frictional stick rows with standard multipliers) delay more and
  // stopped with INFO(1) = -9 (workspace too small). User options below still override it.
  std::string opts = "-no_signal_handler -mat_mumps_icntl_14 100";
  for (const auto& a : petsc_args) opts += " " + a;
  check(PetscOptionsInsertString(nullptr, opts.c_str()), "reading PETSc options");
}

Session::~Session() {
  PetscFinalize();
}

Vector::Vector(MPI_Comm comm, PetscInt n_owned, std::span<const PetscInt> ghosts) {
  check(VecCreateGhost(comm, n_owned, PETSC_DECIDE, static_cast<PetscInt>(ghosts.size()),
                       ghosts.data(), &v_),
        "VecCreateGhost");
}

Vector::~Vector() {
  if (v_) VecDestroy(&v_);
}

Vector& Vector::operator=(Vector&& o) noexcept {
  if (this != &o) {
    if (v_) VecDestroy(&v_);
    v_ = o.v_;
    o.v_ = nullptr;
    remote_rows_ = std::move(o.remote_rows_);
    remote_values_ = std::move(o.remote_values_);
    remote_insert_ = o.remote_insert_;
  }
  return *this;
}

Vector Vector::duplicate() const {
  Vector out;
  check(VecDuplicate(v_, &out.v_), "VecDuplicate");
  check(VecSet(out.v_, 0.0), "VecSet");
  return out;
}

void Vector::copy_from(const Vector& src) {
  check(VecCopy(src.v_, v_), "VecCopy");
}
void Vector::zero() {
  check(VecSet(v_, 0.0), "VecSet");
}

// PETSc's VecAssemblyEnd adds the stashed entries of other ranks in the order their messages
// arrive (MPI_Waitsome), so that on three or more ranks an entry that two ranks contribute to
// rounds differently from run to run. Vector therefore keeps such entries itself and sends them
// in assemble() with one MPI_Alltoallv, whose result is in rank order.
void Vector::keep_remote(std::span<const PetscInt> rows, std::span<const double> values,
                         bool insert) {
  PetscInt lo = 0, hi = 0;
  check(VecGetOwnershipRange(v_, &lo, &hi), "VecGetOwnershipRange");
  if (!remote_rows_.empty())
    SEAM_CHECK(remote_insert_ == insert, InternalError,
               "Vector: added and inserted values without an assemble() between them");
  remote_insert_ = insert;
  const InsertMode mode = insert ? INSERT_VALUES : ADD_VALUES;
  std::size_t k = 0;
  while (k < rows.size()) {
    // A run of owned rows goes to PETSc at once; the others are kept.
    std::size_t end = k;
    while (end < rows.size() && rows[end] >= lo && rows[end] < hi) ++end;
    if (end > k)
      check(VecSetValues(v_, static_cast<PetscInt>(end - k), rows.data() + k, values.data() + k,
                         mode),
            "VecSetValues");
    for (; end < rows.size() && !(rows[end] >= lo && rows[end] < hi); ++end) {
      if (rows[end] < 0) continue; // PETSc's convention: a negative row is ignored
      remote_rows_.push_back(rows[end]);
      remote_values_.push_back(values[end]);
    }
    k = end;
  }
}

void Vector::add_values(std::span<const PetscInt> rows, std::span<const double> values) {
  keep_remote(rows, values, false);
}

void Vector::set_values(std::span<const PetscInt> rows, std::span<const double> values) {
  keep_remote(rows, values, true);
}

void Vector::assemble() {
  MPI_Comm comm = MPI_COMM_NULL;
  check(PetscObjectGetComm(reinterpret_cast<PetscObject>(v_), &comm), "PetscObjectGetComm");
  int size = 1;
  MPI_Comm_size(comm, &size);
  if (size > 1) {
    const PetscInt* ranges = nullptr;
    check(VecGetOwnershipRanges(v_, &ranges), "VecGetOwnershipRanges");
    // The kept entries by owner, each owner's in the order they were given.
    const std::size_t n = remote_rows_.size();
    std::vector<int> owner(n), send_count(size, 0), send_displ(size, 0);
    for (std::size_t k = 0; k < n; ++k) {
      owner[k] =
          static_cast<int>(std::upper_bound(ranges, ranges + size + 1, remote_rows_[k]) - ranges) -
          1;
      ++send_count[owner[k]];
    }
    for (int r = 1; r < size; ++r) send_displ[r] = send_displ[r - 1] + send_count[r - 1];
    std::vector<PetscInt> send_rows(n);
    std::vector<double> send_values(n);
    {
      std::vector<int> next(send_displ);
      for (std::size_t k = 0; k < n; ++k) {
        const int at = next[owner[k]]++;
        send_rows[at] = remote_rows_[k];
        send_values[at] = remote_values_[k];
      }
    }
    std::vector<int> recv_count(size), recv_displ(size, 0);
    MPI_Alltoall(send_count.data(), 1, MPI_INT, recv_count.data(), 1, MPI_INT, comm);
    for (int r = 1; r < size; ++r) recv_displ[r] = recv_displ[r - 1] + recv_count[r - 1];
    const int n_recv = recv_displ[size - 1] + recv_count[size - 1];
    std::vector<PetscInt> recv_rows(n_recv);
    std::vector<double> recv_values(n_recv);
    MPI_Alltoallv(send_rows.data(), send_count.data(), send_displ.data(), MPIU_INT,
                  recv_rows.data(), recv_count.data(), recv_displ.data(), MPIU_INT, comm);
    MPI_Alltoallv(send_values.data(), send_count.data(), send_displ.data(), MPI_DOUBLE,
                  recv_values.data(), recv_count.data(), recv_displ.data(), MPI_DOUBLE, comm);
    int insert = remote_insert_ && n > 0 ? 1 : 0;
    MPI_Allreduce(MPI_IN_PLACE, &insert, 1, MPI_INT, MPI_MAX, comm);
    if (n_recv > 0)
      check(VecSetValues(v_, n_recv, recv_rows.data(), recv_values.data(),
                         insert ? INSERT_VALUES : ADD_VALUES),
            "VecSetValues");
  } else {
    SEAM_CHECK(remote_rows_.empty(), InternalError, "Vector: row ",
               remote_rows_.empty() ? 0 : remote_rows_.front(), " out of range");
  }
  remote_rows_.clear();
  remote_values_.clear();
  remote_insert_ = false;
  check(VecAssemblyBegin(v_), "VecAssemblyBegin");
  check(VecAssemblyEnd(v_), "VecAssemblyEnd");
}

void Vector::update_ghosts() {
  check(VecGhostUpdateBegin(v_, INSERT_VALUES, SCATTER_FORWARD), "VecGhostUpdateBegin");
  check(VecGhostUpdateEnd(v_, INSERT_VALUES, SCATTER_FORWARD), "VecGhostUpdateEnd");
}

void Vector::accumulate_ghosts() {
  check(VecGhostUpdateBegin(v_, ADD_VALUES, SCATTER_REVERSE), "VecGhostUpdateBegin");
  check(VecGhostUpdateEnd(v_, ADD_VALUES, SCATTER_REVERSE), "VecGhostUpdateEnd");
}

double Vector::norm() const {
  PetscReal n = 0;
  check(VecNorm(v_, NORM_2, &n), "VecNorm");
  return n;
}

double Vector::dot(const Vector& o) const {
  PetscScalar d = 0;
  check(VecDot(v_, o.v_, &d), "VecDot");
  return d;
}

void Vector::axpy(double a, const Vector& x) {
  check(VecAXPY(v_, a, x.v_), "VecAXPY");
}
void Vector::scale(double a) {
  check(VecScale(v_, a), "VecScale");
}

PetscInt Vector::owned_size() const {
  PetscInt n = 0;
  check(VecGetLocalSize(v_, &n), "VecGetLocalSize");
  return n;
}

PetscInt Vector::global_size() const {
  PetscInt n = 0;
  check(VecGetSize(v_, &n), "VecGetSize");
  return n;
}

PetscInt Vector::owned_begin() const {
  PetscInt lo = 0, hi = 0;
  check(VecGetOwnershipRange(v_, &lo, &hi), "VecGetOwnershipRange");
  return lo;
}

Gather::Gather(const Vector& layout, std::span<const PetscInt> indices) : n_(indices.size()) {
  IS from = nullptr;
  check(ISCreateGeneral(PETSC_COMM_SELF, static_cast<PetscInt>(indices.size()), indices.data(),
                        PETSC_COPY_VALUES, &from),
        "ISCreateGeneral");
  check(VecCreateSeq(PETSC_COMM_SELF, static_cast<PetscInt>(indices.size()), &local_),
        "VecCreateSeq");
  check(VecScatterCreate(layout.get(), from, local_, nullptr, &scatter_), "VecScatterCreate");
  check(ISDestroy(&from), "ISDestroy");
}

Gather::~Gather() {
  if (scatter_) VecScatterDestroy(&scatter_);
  if (local_) VecDestroy(&local_);
}

Gather::Gather(Gather&& o) noexcept : scatter_(o.scatter_), local_(o.local_), n_(o.n_) {
  o.scatter_ = nullptr;
  o.local_ = nullptr;
  o.n_ = 0;
}

Gather& Gather::operator=(Gather&& o) noexcept {
  if (this != &o) {
    this->~Gather();
    scatter_ = o.scatter_;
    local_ = o.local_;
    n_ = o.n_;
    o.scatter_ = nullptr;
    o.local_ = nullptr;
    o.n_ = 0;
  }
  return *this;
}

void Gather::operator()(const Vector& v, std::vector<double>& out) const {
  check(VecScatterBegin(scatter_, v.get(), local_, INSERT_VALUES, SCATTER_FORWARD),
        "VecScatterBegin");
  check(VecScatterEnd(scatter_, v.get(), local_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
  const double* a = nullptr;
  check(VecGetArrayRead(local_, &a), "VecGetArrayRead");
  out.assign(a, a + n_);
  VecRestoreArrayRead(local_, &a);
}

Vector::LocalView::LocalView(const Vector& v, bool write) : owner_(v.v_), write_(write) {
  check(VecGhostGetLocalForm(owner_, &local_), "VecGhostGetLocalForm");
  check(VecGetLocalSize(local_, &n_), "VecGetLocalSize");
  check(VecGetArray(local_, &data_), "VecGetArray");
}

Vector::LocalView::~LocalView() {
  VecRestoreArray(local_, &data_);
  VecGhostRestoreLocalForm(owner_, &local_);
  if (write_) {
    // Writes through the local form do not touch the global vector's state counter; a
    // get/restore pair on it bumps the counter so cached norms are not reused.
    double* a = nullptr;
    VecGetArray(owner_, &a);
    VecRestoreArray(owner_, &a);
  }
}

Matrix::Matrix(MPI_Comm comm, PetscInt n_owned, std::span<const PetscInt> d_nnz,
               std::span<const PetscInt> o_nnz, PetscInt block_size) {
  check(MatCreate(comm, &m_), "MatCreate");
  check(MatSetSizes(m_, n_owned, n_owned, PETSC_DETERMINE, PETSC_DETERMINE), "MatSetSizes");
  check(MatSetType(m_, MATAIJ), "MatSetType");
  check(MatSetBlockSize(m_, block_size), "MatSetBlockSize");
  check(MatSeqAIJSetPreallocation(m_, 0, d_nnz.data()), "MatSeqAIJSetPreallocation");
  check(MatMPIAIJSetPreallocation(m_, 0, d_nnz.data(), 0, o_nnz.data()),
        "MatMPIAIJSetPreallocation");
  check(MatSetOption(m_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "MatSetOption");
  check(MatSetOption(m_, MAT_KEEP_NONZERO_PATTERN, PETSC_TRUE), "MatSetOption");
}

Matrix::~Matrix() {
  if (m_) MatDestroy(&m_);
}

Matrix& Matrix::operator=(Matrix&& o) noexcept {
  if (this != &o) {
    if (m_) MatDestroy(&m_);
    m_ = o.m_;
    o.m_ = nullptr;
    sum_source_ = o.sum_source_;
    sum_source_state_ = o.sum_source_state_;
    sum_state_ = o.sum_state_;
    sum_same_pattern_ = o.sum_same_pattern_;
  }
  return *this;
}

Matrix Matrix::ptap(const Matrix& A, const Matrix& P) {
  Mat C = nullptr;
  check(MatPtAP(A.m_, P.m_, MAT_INITIAL_MATRIX, 2.0, &C), "MatPtAP");
  return adopt(C);
}

Matrix Matrix::multiply(const Matrix& A, const Matrix& B) {
  Mat C = nullptr;
  check(MatMatMult(A.m_, B.m_, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &C), "MatMatMult");
  return adopt(C);
}

Matrix Matrix::multiply_sparse_left(const Matrix& A, const Matrix& B) {
  PetscInt m = 0, n = 0;
  check(MatGetLocalSize(A.m_, &m, nullptr), "MatGetLocalSize");
  check(MatGetLocalSize(B.m_, nullptr, &n), "MatGetLocalSize");
  std::vector<PetscInt> ci, cj;
  std::vector<double> cv;
  append_product(A, B, ci, cj, cv);
  return from_triplets(PetscObjectComm(reinterpret_cast<PetscObject>(A.m_)), m, ci, cj, cv, n);
}

void Matrix::append_product(const Matrix& A, const Matrix& B, std::vector<PetscInt>& ci,
                            std::vector<PetscInt>& cj, std::vector<double>& cv) {
  // This rank's rows of A that have entries, with their (sorted global) columns and values.
  PetscInt lo = 0, hi = 0, n_cols = 0;
  check(MatGetOwnershipRange(A.m_, &lo, &hi), "MatGetOwnershipRange");
  check(MatGetSize(B.m_, nullptr, &n_cols), "MatGetSize");
  std::vector<PetscInt> a_rows, a_offsets{0}, a_cols;
  std::vector<double> a_values;
  for (PetscInt i = lo; i < hi; ++i) {
    PetscInt nc = 0;
    const PetscInt* c = nullptr;
    const PetscScalar* v = nullptr;
    check(MatGetRow(A.m_, i, &nc, &c, &v), "MatGetRow");
    if (nc > 0) {
      a_rows.push_back(i);
      a_cols.insert(a_cols.end(), c, c + nc);
      a_values.insert(a_values.end(), v, v + nc);
      a_offsets.push_back(static_cast<PetscInt>(a_cols.size()));
    }
    check(MatRestoreRow(A.m_, i, &nc, &c, &v), "MatRestoreRow");
  }
  // The rows of B they name, all columns (a stride over every column: PETSc then keeps the
  // global column numbers and builds no map over them).
  std::vector<PetscInt> needed(a_cols);
  std::sort(needed.begin(), needed.end());
  needed.erase(std::unique(needed.begin(), needed.end()), needed.end());
  IS rows = nullptr, cols = nullptr;
  check(ISCreateGeneral(PETSC_COMM_SELF, static_cast<PetscInt>(needed.size()), needed.data(),
                        PETSC_COPY_VALUES, &rows),
        "ISCreateGeneral");
  check(ISCreateStride(PETSC_COMM_SELF, n_cols, 0, 1, &cols), "ISCreateStride");
  Mat* sub = nullptr;
  check(MatCreateSubMatrices(B.m_, 1, &rows, &cols, MAT_INITIAL_MATRIX, &sub),
        "MatCreateSubMatrices");
  ISDestroy(&rows);
  ISDestroy(&cols);
  // Row i of A B: the terms A_ic B_cj in the order of c, then summed per column j in that
  // order (a stable sort by j).
  std::vector<std::pair<PetscInt, double>> terms;
  for (std::size_t r = 0; r < a_rows.size(); ++r) {
    terms.clear();
    for (auto k = a_offsets[r]; k < a_offsets[r + 1]; ++k) {
      const auto at = std::lower_bound(needed.begin(), needed.end(), a_cols[k]) - needed.begin();
      PetscInt nc = 0;
      const PetscInt* c = nullptr;
      const PetscScalar* v = nullptr;
      check(MatGetRow(sub[0], static_cast<PetscInt>(at), &nc, &c, &v), "MatGetRow");
      for (PetscInt e = 0; e < nc; ++e) terms.emplace_back(c[e], a_values[k] * v[e]);
      check(MatRestoreRow(sub[0], static_cast<PetscInt>(at), &nc, &c, &v), "MatRestoreRow");
    }
    std::stable_sort(terms.begin(), terms.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    for (std::size_t e = 0; e < terms.size();) {
      double sum = 0.0;
      const PetscInt j = terms[e].first;
      for (; e < terms.size() && terms[e].first == j; ++e) sum += terms[e].second;
      ci.push_back(a_rows[r]);
      cj.push_back(j);
      cv.push_back(sum);
    }
  }
  check(MatDestroySubMatrices(1, &sub), "MatDestroySubMatrices");
}

Matrix Matrix::from_triplets(MPI_Comm comm, PetscInt n_owned, std::span<const PetscInt> rows,
                             std::span<const PetscInt> cols, std::span<const double> values,
                             PetscInt n_owned_cols) {
  Matrix out;
  check(MatCreate(comm, &out.m_), "MatCreate");
  check(MatSetSizes(out.m_, n_owned, n_owned_cols < 0 ? n_owned : n_owned_cols, PETSC_DETERMINE,
                    PETSC_DETERMINE),
        "MatSetSizes");
  check(MatSetType(out.m_, MATAIJ), "MatSetType");
  // MatSetPreallocationCOO may reorder its index arrays: hand it copies.
  std::vector<PetscInt> i(rows.begin(), rows.end()), j(cols.begin(), cols.end());
  check(MatSetPreallocationCOO(out.m_, static_cast<PetscCount>(i.size()), i.data(), j.data()),
        "MatSetPreallocationCOO");
  check(MatSetValuesCOO(out.m_, values.data(), INSERT_VALUES), "MatSetValuesCOO");
  return out;
}

void Matrix::set_triplet_values(std::span<const double> values) {
  check(MatSetValuesCOO(m_, values.data(), INSERT_VALUES), "MatSetValuesCOO");
}

Matrix Matrix::copy() const {
  Mat m = nullptr;
  check(MatDuplicate(m_, MAT_COPY_VALUES, &m), "MatDuplicate");
  return adopt(m);
}

void Matrix::mult(const Vector& x, Vector& y) const {
  check(MatMult(m_, x.get(), y.get()), "MatMult");
}

void Matrix::mult_transpose(const Vector& x, Vector& y) const {
  check(MatMultTranspose(m_, x.get(), y.get()), "MatMultTranspose");
}

void Matrix::scale(double a) {
  check(MatScale(m_, a), "MatScale");
}

void Matrix::axpy(double a, const Matrix& X) {
  check(MatAXPY(m_, a, X.m_, SAME_NONZERO_PATTERN), "MatAXPY");
}

void Matrix::axpy_any_pattern(double a, const Matrix& X) {
  check(MatSetOption(m_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE), "MatSetOption");
  check(MatAXPY(m_, a, X.m_, DIFFERENT_NONZERO_PATTERN), "MatAXPY");
}

bool Matrix::holds_pattern_of(const Matrix& X) const {
  PetscInt lo = 0, hi = 0;
  check(MatGetOwnershipRange(X.m_, &lo, &hi), "MatGetOwnershipRange");
  bool holds = true;
  for (PetscInt i = lo; i < hi && holds; ++i) {
    PetscInt nx = 0, n = 0;
    const PetscInt *cx = nullptr, *c = nullptr;
    check(MatGetRow(X.m_, i, &nx, &cx, nullptr), "MatGetRow");
    if (nx > 0) {
      check(MatGetRow(m_, i, &n, &c, nullptr), "MatGetRow");
      // Both rows are sorted by global column.
      PetscInt k = 0;
      for (PetscInt e = 0; e < nx && holds; ++e) {
        while (k < n && c[k] < cx[e]) ++k;
        holds = k < n && c[k] == cx[e];
      }
      check(MatRestoreRow(m_, i, &n, &c, nullptr), "MatRestoreRow");
    }
    check(MatRestoreRow(X.m_, i, &nx, &cx, nullptr), "MatRestoreRow");
  }
  int local = holds ? 1 : 0, all = 0;
  MPI_Comm comm = MPI_COMM_NULL;
  check(PetscObjectGetComm(reinterpret_cast<PetscObject>(m_), &comm), "PetscObjectGetComm");
  MPI_Allreduce(&local, &all, 1, MPI_INT, MPI_MIN, comm);
  return all == 1;
}

bool Matrix::assign_sum(const Matrix& A, const Matrix& B) {
  PetscObjectId id = 0;
  PetscObjectState a_state = 0, state = 0;
  check(PetscObjectGetId(reinterpret_cast<PetscObject>(A.m_), &id), "PetscObjectGetId");
  check(MatGetNonzeroState(A.m_, &a_state), "MatGetNonzeroState");
  if (m_) check(MatGetNonzeroState(m_, &state), "MatGetNonzeroState");
  // The decision is the same on every rank: the states and ids are collective, and
  // holds_pattern_of reduces over the ranks.
  if (m_ && id == sum_source_ && a_state == sum_source_state_ && state == sum_state_ &&
      holds_pattern_of(B)) {
    if (sum_same_pattern_) {
      check(MatCopy(A.m_, m_, SAME_NONZERO_PATTERN), "MatCopy");
    } else {
      check(MatZeroEntries(m_), "MatZeroEntries");
      check(MatAXPY(m_, 1.0, A.m_, SUBSET_NONZERO_PATTERN), "MatAXPY");
    }
    check(MatAXPY(m_, 1.0, B.m_, SUBSET_NONZERO_PATTERN), "MatAXPY");
    check(MatGetNonzeroState(m_, &sum_state_), "MatGetNonzeroState");
    return true;
  }
  // The union pattern is built directly: a copy of A followed by MatAXPY with a different
  // pattern would hold three matrices of A's size at once (A, the copy and the sum MatAXPY
  // builds before it replaces the copy), the peak of a contact run (docs/performance.md).
  Mat C = nullptr;
  check(MatCreate(PetscObjectComm(reinterpret_cast<PetscObject>(A.m_)), &C), "MatCreate");
  PetscInt lo = 0, hi = 0, clo = 0, chi = 0, m = 0, n = 0;
  check(MatGetOwnershipRange(A.m_, &lo, &hi), "MatGetOwnershipRange");
  check(MatGetOwnershipRangeColumn(A.m_, &clo, &chi), "MatGetOwnershipRangeColumn");
  check(MatGetLocalSize(A.m_, &m, &n), "MatGetLocalSize");
  check(MatSetSizes(C, m, n, PETSC_DETERMINE, PETSC_DETERMINE), "MatSetSizes");
  check(MatSetBlockSizesFromMats(C, A.m_, A.m_), "MatSetBlockSizesFromMats");
  check(MatSetType(C, MATAIJ), "MatSetType");
  std::vector<PetscInt> d_nnz(static_cast<std::size_t>(m), 0), o_nnz(d_nnz), cols;
  std::vector<double> vals;
  // Row i of A + B, merged by column (MatGetRow gives sorted global columns); `emit` sees the
  // merged columns and values.
  const auto merged_row = [&](PetscInt i, auto&& emit) {
    PetscInt na = 0, nb = 0;
    const PetscInt *ca = nullptr, *cb = nullptr;
    const PetscScalar *va = nullptr, *vb = nullptr;
    check(MatGetRow(A.m_, i, &na, &ca, &va), "MatGetRow");
    check(MatGetRow(B.m_, i, &nb, &cb, &vb), "MatGetRow");
    cols.clear();
    vals.clear();
    PetscInt a = 0, b = 0;
    while (a < na || b < nb) {
      if (b == nb || (a < na && ca[a] < cb[b])) {
        cols.push_back(ca[a]);
        vals.push_back(va[a++]);
      } else if (a == na || cb[b] < ca[a]) {
        cols.push_back(cb[b]);
        vals.push_back(vb[b++]);
      } else {
        cols.push_back(ca[a]);
        vals.push_back(va[a++] + vb[b++]);
      }
    }
    check(MatRestoreRow(B.m_, i, &nb, &cb, &vb), "MatRestoreRow");
    check(MatRestoreRow(A.m_, i, &na, &ca, &va), "MatRestoreRow");
    emit();
  };
  for (PetscInt i = lo; i < hi; ++i)
    merged_row(i, [&] {
      for (PetscInt c : cols)
        ++(c >= clo && c < chi ? d_nnz : o_nnz)[static_cast<std::size_t>(i - lo)];
    });
  check(MatSeqAIJSetPreallocation(C, 0, d_nnz.data()), "MatSeqAIJSetPreallocation");
  check(MatMPIAIJSetPreallocation(C, 0, d_nnz.data(), 0, o_nnz.data()),
        "MatMPIAIJSetPreallocation");
  for (PetscInt i = lo; i < hi; ++i)
    merged_row(i, [&] {
      check(MatSetValues(C, 1, &i, static_cast<PetscInt>(cols.size()), cols.data(), vals.data(),
                         INSERT_VALUES),
            "MatSetValues");
    });
  check(MatAssemblyBegin(C, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(C, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  *this = adopt(C);
  MatInfo a_info, info;
  check(MatGetInfo(A.m_, MAT_GLOBAL_SUM, &a_info), "MatGetInfo");
  check(MatGetInfo(m_, MAT_GLOBAL_SUM, &info), "MatGetInfo");
  sum_same_pattern_ = a_info.nz_used == info.nz_used;
  sum_source_ = id;
  sum_source_state_ = a_state;
  check(MatGetNonzeroState(m_, &sum_state_), "MatGetNonzeroState");
  return false;
}

void Matrix::add_diagonal(const Vector& values) {
  check(MatSetOption(m_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE), "MatSetOption");
  check(MatDiagonalSet(m_, values.get(), ADD_VALUES), "MatDiagonalSet");
}

void Matrix::zero() {
  check(MatZeroEntries(m_), "MatZeroEntries");
}

void Matrix::add_values(std::span<const PetscInt> rows, std::span<const PetscInt> cols,
                        std::span<const double> values) {
  check(MatSetValues(m_, static_cast<PetscInt>(rows.size()), rows.data(),
                     static_cast<PetscInt>(cols.size()), cols.data(), values.data(), ADD_VALUES),
        "MatSetValues");
}

void Matrix::assemble() {
  check(MatAssemblyBegin(m_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(m_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
}

void Matrix::zero_rows_columns(std::span<const PetscInt> rows, const Vector* x, Vector* b) {
  check(MatZeroRowsColumns(m_, static_cast<PetscInt>(rows.size()), rows.data(), 1.0,
                           x ? x->get() : nullptr, b ? b->get() : nullptr),
        "MatZeroRowsColumns");
}

void Matrix::set_near_null_space(const Vector& coordinates) {
  // MatNullSpaceCreateRigidBody takes the spatial dimension from the vector's block size: a
  // copy with the matrix's block size (the dimension) gives all 3 (2D) or 6 (3D) rigid-body
  // modes, not just the constant vector.
  PetscInt bs = 1, n = 0;
  check(MatGetBlockSize(m_, &bs), "MatGetBlockSize");
  check(VecGetLocalSize(coordinates.get(), &n), "VecGetLocalSize");
  MPI_Comm comm = MPI_COMM_NULL;
  check(PetscObjectGetComm(reinterpret_cast<PetscObject>(m_), &comm), "PetscObjectGetComm");
  Vec blocked = nullptr;
  check(VecCreate(comm, &blocked), "VecCreate");
  check(VecSetSizes(blocked, n, PETSC_DECIDE), "VecSetSizes");
  check(VecSetBlockSize(blocked, bs), "VecSetBlockSize");
  check(VecSetType(blocked, VECSTANDARD), "VecSetType");
  check(VecCopy(coordinates.get(), blocked), "VecCopy");
  MatNullSpace nsp = nullptr;
  check(MatNullSpaceCreateRigidBody(blocked, &nsp), "MatNullSpaceCreateRigidBody");
  check(MatSetNearNullSpace(m_, nsp), "MatSetNearNullSpace");
  check(MatNullSpaceDestroy(&nsp), "MatNullSpaceDestroy");
  check(VecDestroy(&blocked), "VecDestroy");
}

void Matrix::share_near_null_space(const Matrix& from) {
  MatNullSpace own = nullptr, nsp = nullptr;
  check(MatGetNearNullSpace(m_, &own), "MatGetNearNullSpace");
  check(MatGetNearNullSpace(from.m_, &nsp), "MatGetNearNullSpace");
  if (own || !nsp) return;
  PetscInt bs = 1, own_bs = 1;
  check(MatGetBlockSize(from.m_, &bs), "MatGetBlockSize");
  check(MatGetBlockSize(m_, &own_bs), "MatGetBlockSize");
  if (own_bs != bs) check(MatSetBlockSize(m_, bs), "MatSetBlockSize");
  check(MatSetNearNullSpace(m_, nsp), "MatSetNearNullSpace");
}

BlockAdder::BlockAdder(Matrix& m) : m_(m.get()) {
  check(MatGetBlockSize(m_, &bs_), "MatGetBlockSize");
  check(MatGetOwnershipRange(m_, &row_begin_, &row_end_), "MatGetOwnershipRange");
  check(MatGetOwnershipRangeColumn(m_, &col_begin_, &col_end_), "MatGetOwnershipRangeColumn");
  PetscBool assembled = PETSC_FALSE, seq = PETSC_FALSE, mpi = PETSC_FALSE;
  check(MatAssembled(m_, &assembled), "MatAssembled");
  check(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(m_), MATSEQAIJ, &seq),
        "PetscObjectTypeCompare");
  check(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(m_), MATMPIAIJ, &mpi),
        "PetscObjectTypeCompare");
  // Before its first assembly an MPIAIJ matrix keeps global column indices off the diagonal
  // block: then every block goes through MatSetValues.
  if (!assembled || !(seq || mpi)) return;
  if (mpi) {
    check(MatMPIAIJGetSeqAIJ(m_, &diag_.mat, &off_.mat, &col_map_), "MatMPIAIJGetSeqAIJ");
    PetscInt rows = 0;
    check(MatGetLocalSize(off_.mat, &rows, &n_col_map_), "MatGetLocalSize");
    if (n_col_map_ > 0 && !col_map_) return;
    for (PetscInt k = 1; k < n_col_map_; ++k)
      if (col_map_[k] <= col_map_[k - 1]) return;
  } else {
    diag_.mat = m_;
  }
  for (Part* p : {&diag_, &off_}) {
    if (!p->mat) continue;
    PetscBool done = PETSC_FALSE;
    check(MatGetRowIJ(p->mat, 0, PETSC_FALSE, PETSC_FALSE, &p->n_rows, &p->ia, &p->ja, &done),
          "MatGetRowIJ");
    SEAM_CHECK(done, InternalError, "MatGetRowIJ gave no row structure");
    check(MatSeqAIJGetArray(p->mat, &p->values), "MatSeqAIJGetArray");
  }
  direct_ = true;
}

BlockAdder::~BlockAdder() {
  try {
    if (direct_) release();
  } catch (...) {
    // A destructor does not throw; finish() reports the error where it can be handled.
  }
}

void BlockAdder::release() {
  for (Part* p : {&diag_, &off_}) {
    if (!p->mat) continue;
    PetscBool done = PETSC_FALSE;
    check(MatSeqAIJRestoreArray(p->mat, &p->values), "MatSeqAIJRestoreArray");
    check(MatRestoreRowIJ(p->mat, 0, PETSC_FALSE, PETSC_FALSE, &p->n_rows, &p->ia, &p->ja, &done),
          "MatRestoreRowIJ");
  }
  direct_ = false;
}

void BlockAdder::finish() {
  if (direct_) release();
  for (std::size_t k = 0; k < deferred_values_.size(); ++k)
    check(MatSetValues(m_, 1, &deferred_rows_[k], 1, &deferred_cols_[k], &deferred_values_[k],
                       ADD_VALUES),
          "MatSetValues");
  deferred_rows_.clear();
  deferred_cols_.clear();
  deferred_values_.clear();
}

void BlockAdder::defer(std::span<const PetscInt> rows, std::span<const PetscInt> cols,
                       const double* values, std::size_t stride) {
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t j = 0; j < cols.size(); ++j) {
      deferred_rows_.push_back(rows[i]);
      deferred_cols_.push_back(cols[j]);
      deferred_values_.push_back(values[i * stride + j]);
    }
}

PetscInt BlockAdder::find(const Part& p, PetscInt row, PetscInt col) {
  // The columns of a row of an assembled SeqAIJ matrix are sorted.
  const PetscInt* begin = p.ja + p.ia[row];
  const PetscInt* end = p.ja + p.ia[row + 1];
  const PetscInt* at = std::lower_bound(begin, end, col);
  return at != end && *at == col ? static_cast<PetscInt>(at - p.ja) : -1;
}

void BlockAdder::add(std::span<const PetscInt> dofs, std::span<const double> values) {
  const auto nd = dofs.size();
  const auto bs = static_cast<std::size_t>(bs_);
  bool blocked = direct_ && nd % bs == 0;
  for (std::size_t a = 0; blocked && a < nd; a += bs) {
    blocked = dofs[a] % bs_ == 0;
    for (std::size_t i = 1; blocked && i < bs; ++i) blocked = dofs[a + i] == dofs[a] + PetscInt(i);
  }
  if (!blocked) {
    if (direct_) {
      defer(dofs, dofs, values.data(), nd);
    } else {
      check(MatSetValues(m_, PetscInt(nd), dofs.data(), PetscInt(nd), dofs.data(), values.data(),
                         ADD_VALUES),
            "MatSetValues");
    }
    return;
  }
  for (std::size_t a = 0; a < nd; a += bs) {
    const PetscInt row = dofs[a];
    const double* block_rows = values.data() + a * nd;
    if (row < row_begin_ || row >= row_end_) {
      // Another rank's rows: PETSc's stash, which leaves the arrays alone.
      check(MatSetValues(m_, bs_, &dofs[a], PetscInt(nd), dofs.data(), block_rows, ADD_VALUES),
            "MatSetValues");
      continue;
    }
    const PetscInt lr = row - row_begin_;
    for (std::size_t b = 0; b < nd; b += bs) {
      const PetscInt col = dofs[b];
      const Part* part = &diag_;
      PetscInt lc = col - col_begin_;
      if (col < col_begin_ || col >= col_end_) {
        part = &off_;
        const PetscInt* at = std::lower_bound(col_map_, col_map_ + n_col_map_, col);
        lc = at != col_map_ + n_col_map_ && *at == col ? PetscInt(at - col_map_) : -1;
      }
      PetscInt first = lc < 0 || !part->mat ? -1 : find(*part, lr, lc);
      // The block's bs columns must follow each other in the row.
      if (first >= 0 &&
          (first + bs_ > part->ia[lr + 1] || part->ja[first + bs_ - 1] != lc + bs_ - 1))
        first = -1;
      if (first < 0) {
        defer(dofs.subspan(a, bs), dofs.subspan(b, bs), block_rows + b, nd);
        continue;
      }
      const PetscInt offset = first - part->ia[lr];
      for (std::size_t i = 0; i < bs; ++i) {
        const PetscInt r = lr + PetscInt(i);
        // The rows of a node share their columns; otherwise search this row.
        PetscInt at = part->ia[r] + offset;
        if (at + bs_ > part->ia[r + 1] || part->ja[at] != lc ||
            part->ja[at + bs_ - 1] != lc + bs_ - 1) {
          at = find(*part, r, lc);
          if (at < 0 || at + bs_ > part->ia[r + 1] || part->ja[at + bs_ - 1] != lc + bs_ - 1) {
            defer(dofs.subspan(a + i, 1), dofs.subspan(b, bs), block_rows + i * nd + b, nd);
            continue;
          }
        }
        const double* v = block_rows + i * nd + b;
        double* target = part->values + at;
        for (std::size_t j = 0; j < bs; ++j) target[j] += v[j];
      }
    }
  }
}

namespace {

// The options this process wrote as defaults: a later solver may replace them, where an option
// of the command line stays.
std::set<std::string>& own_defaults() {
  static std::set<std::string> names;
  return names;
}

// A default for an option of the database that the command line did not set.
void default_option(const char* name, const char* value) {
  PetscBool set = PETSC_FALSE;
  check(PetscOptionsHasName(nullptr, nullptr, name, &set), "PetscOptionsHasName");
  if (set && !own_defaults().contains(name)) return;
  check(PetscOptionsSetValue(nullptr, name, value), "PetscOptionsSetValue");
  own_defaults().insert(name);
}

/// An option of the database set for a scope and restored after it, unless the command line
/// gave it (then the user's value stays).
class ScopedOption {
public:
  ScopedOption(const char* name, const char* value) : name_(name) {
    PetscBool set = PETSC_FALSE;
    check(PetscOptionsHasName(nullptr, nullptr, name, &set), "PetscOptionsHasName");
    if (set) return;
    check(PetscOptionsSetValue(nullptr, name, value), "PetscOptionsSetValue");
    own_ = true;
  }
  ~ScopedOption() {
    if (own_) PetscOptionsClearValue(nullptr, name_);
  }
  ScopedOption(const ScopedOption&) = delete;
  ScopedOption& operator=(const ScopedOption&) = delete;

private:
  const char* name_;
  bool own_ = false;
};

/// The Galerkin products of GAMG's set-up on several ranks (P^T A P per level). PETSc 3.18's
/// "allatonce", which seam used for its low memory, took 4.2 times the time of one rank's
/// product at np 2 and made two ranks slower than one on the 2e6-dof contact cube; most of the
/// memory of the faster algorithms is the intermediate data they keep with the product for a
/// later numeric phase, which GAMG never asks for (it rebuilds its hierarchy): freed
/// (-mat_product_clear), "nonscalable" costs 7 % more memory than "allatonce" at 0.42 of its
/// time (docs/performance.md, "The largest contact problem of the machine"). "nonscalable"
/// keeps an array over the coarse level's global columns on each rank: up to 5e7 rows of A
/// (a few times 1e6 coarse columns, tens of MB), "scalable" beyond.
struct GalerkinOptions {
  std::optional<ScopedOption> via, clear;
};
void galerkin_options(KSP ksp, const Mat A, GalerkinOptions& options) {
  PC pc = nullptr;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  PetscBool gamg = PETSC_FALSE;
  check(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCGAMG, &gamg),
        "PetscObjectTypeCompare");
  int size = 1;
  MPI_Comm_size(PetscObjectComm(reinterpret_cast<PetscObject>(A)), &size);
  if (!gamg || size == 1) return;
  PetscInt rows = 0;
  check(MatGetSize(A, &rows, nullptr), "MatGetSize");
  options.via.emplace("-matptap_via", rows <= 50000000 ? "nonscalable" : "scalable");
  // Reusing the interpolation runs the numeric phase of the kept products again.
  PetscBool reuse = PETSC_FALSE;
  check(PetscOptionsGetBool(nullptr, nullptr, "-pc_gamg_reuse_interpolation", &reuse, nullptr),
        "PetscOptionsGetBool");
  if (!reuse) options.clear.emplace("-mat_product_clear", "true");
}

// The option MUMPS reads its ordering from at an analysis of the factorization of `ksp`'s PC.
std::string ordering_option(KSP ksp) {
  const char* prefix = nullptr;
  check(KSPGetOptionsPrefix(ksp, &prefix), "KSPGetOptionsPrefix");
  return std::string("-") + (prefix ? prefix : "") + "mat_mumps_icntl_7";
}

} // namespace

LinearSolver::LinearSolver(MPI_Comm comm, SolverKind kind) : kind_(kind) {
  check(KSPCreate(comm, &ksp_), "KSPCreate");
  PC pc = nullptr;
  check(KSPGetPC(ksp_, &pc), "KSPGetPC");
  if (kind == SolverKind::direct) {
    check(KSPSetType(ksp_, KSPPREONLY), "KSPSetType");
    check(PCSetType(pc, PCLU), "PCSetType");
    check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
  } else {
    check(KSPSetType(ksp_, KSPGMRES), "KSPSetType");
    check(KSPGMRESSetRestart(ksp_, 200), "KSPGMRESSetRestart");
    check(PCSetType(pc, PCGAMG), "PCSetType");
    check(KSPSetTolerances(ksp_, 1e-10, 1e-50, PETSC_DEFAULT, 2000), "KSPSetTolerances");
    // GAMG's Galerkin products P^T A P on several ranks: see galerkin_options() below.
  }
  check(KSPSetFromOptions(ksp_), "KSPSetFromOptions");
  PetscBool set = PETSC_FALSE;
  check(PetscOptionsHasName(nullptr, nullptr, "-ksp_reuse_preconditioner", &set),
        "PetscOptionsHasName");
  user_reuse_set_ = set;
  PetscBool reuse = PETSC_TRUE;
  check(PetscOptionsGetBool(nullptr, nullptr, "-factor_reuse", &reuse, nullptr),
        "PetscOptionsGetBool");
  reuse_enabled_ = reuse == PETSC_TRUE && !user_reuse_set_;
  if (kind == SolverKind::direct) {
    // GMRES over the factorization of ksp_ (its PC, shared): right-preconditioned, so that
    // the tolerance applies to the true residual b - A x.
    check(KSPCreate(comm, &reuse_ksp_), "KSPCreate");
    check(KSPSetType(reuse_ksp_, KSPGMRES), "KSPSetType");
    check(KSPGMRESSetRestart(reuse_ksp_, factor_reuse_max_iterations), "KSPGMRESSetRestart");
    check(KSPSetPCSide(reuse_ksp_, PC_RIGHT), "KSPSetPCSide");
    check(KSPSetNormType(reuse_ksp_, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
    check(KSPSetTolerances(reuse_ksp_, factor_reuse_rtol, 1e-300, PETSC_DEFAULT,
                           factor_reuse_max_iterations),
          "KSPSetTolerances");
    check(KSPSetPC(reuse_ksp_, pc), "KSPSetPC");
    ordering_option_ = ordering_option(ksp_);
    PetscBool ordered = PETSC_FALSE;
    check(PetscOptionsHasName(nullptr, nullptr, ordering_option_.c_str(), &ordered),
          "PetscOptionsHasName");
    ordering_auto_ = !ordered;
  }
}

namespace {

// The defaults of a velocity | pressure Schur fieldsplit whose option prefix is `prefix`
// ("-fieldsplit_" for the fluid alone) and whose blocks are named u and p.
void schur_defaults(const std::string& prefix, const std::string& u, const std::string& p,
                    LinearSolver::VelocityBlock velocity) {
  const auto set = [](const std::string& name, const char* value) {
    default_option(name.c_str(), value);
  };
  for (const auto& block : {u, p}) set(prefix + block + "_ksp_type", "preonly");
  const std::string pu = prefix + u + "_pc_";
  if (velocity == LinearSolver::VelocityBlock::amg) {
    set(pu + "type", "hypre");
    set(pu + "hypre_type", "boomeramg");
    set(pu + "hypre_boomeramg_relax_type_all", "l1scaled-Jacobi");
    set(pu + "hypre_boomeramg_coarsen_type", "HMIS");
    set(pu + "hypre_boomeramg_interp_type", "ext+i");
  } else {
    set(pu + "type", "bjacobi");
  }
  set(prefix + p + "_pc_type", "hypre");
  set(prefix + p + "_pc_hypre_type", "boomeramg");
}

// An index set of the owned global rows `rows`.
IS index_set(MPI_Comm comm, std::span<const PetscInt> rows) {
  IS is = nullptr;
  check(ISCreateGeneral(comm, static_cast<PetscInt>(rows.size()), rows.data(), PETSC_COPY_VALUES,
                        &is),
        "ISCreateGeneral");
  return is;
}

// FGMRES (restart 200; AMG cycles in the blocks are not fixed linear operators) with a
// PCFIELDSPLIT preconditioner on `ksp`; returns the preconditioner and sets `comm`.
PC fieldsplit_pc(KSP ksp, MPI_Comm& comm) {
  check(PetscObjectGetComm(reinterpret_cast<PetscObject>(ksp), &comm), "PetscObjectGetComm");
  check(KSPSetType(ksp, KSPFGMRES), "KSPSetType");
  check(KSPGMRESSetRestart(ksp, 200), "KSPGMRESSetRestart");
  PC pc = nullptr;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  check(PCSetType(pc, PCFIELDSPLIT), "PCSetType");
  return pc;
}

// A Schur fieldsplit of two fields, lower-triangular factorization, with the assembled
// approximation S = A11 - A10 diag(A00)^-1 A01 (selfp) as the Schur block's matrix.
void lower_schur_selfp(PC pc) {
  check(PCFieldSplitSetType(pc, PC_COMPOSITE_SCHUR), "PCFieldSplitSetType");
  check(PCFieldSplitSetSchurFactType(pc, PC_FIELDSPLIT_SCHUR_FACT_LOWER),
        "PCFieldSplitSetSchurFactType");
  check(PCFieldSplitSetSchurPre(pc, PC_FIELDSPLIT_SCHUR_PRE_SELFP, nullptr),
        "PCFieldSplitSetSchurPre");
}

} // namespace

void LinearSolver::set_fields(std::span<const PetscInt> first, std::span<const PetscInt> second,
                              VelocityBlock velocity) {
  SEAM_CHECK(kind_ == SolverKind::iterative, InternalError,
             "a fieldsplit preconditioner for the direct solver");
  MPI_Comm comm = PETSC_COMM_WORLD;
  PC pc = fieldsplit_pc(ksp_, comm);
  const std::span<const PetscInt> rows[2] = {first, second};
  const char* names[2] = {"u", "p"};
  for (int k = 0; k < 2; ++k) {
    IS is = index_set(comm, rows[k]);
    check(PCFieldSplitSetIS(pc, names[k], is), "PCFieldSplitSetIS");
    check(ISDestroy(&is), "ISDestroy");
  }
  lower_schur_selfp(pc);
  // The blocks' solvers are only reachable after the set-up; their defaults go to the
  // options database, where the command line wins. Measured on DFG 2D-1 and 2D-3
  // (docs/fluid.md, "Solving"): the selfp Schur approximation is a pressure Laplacian-like
  // matrix, on which one BoomerAMG V-cycle does better than ILU(0); on the velocity block
  // BoomerAMG with l1-scaled Jacobi smoothing keeps the iterations per Newton step from
  // growing under refinement of the steady problem, where ILU(0)'s grow (146, 302, 1078).
  schur_defaults("-fieldsplit_", "u", "p", velocity);
  check(KSPSetFromOptions(ksp_), "KSPSetFromOptions");
}

namespace {

PetscErrorCode apply_schur_shell(PC pc, Vec x, Vec y) {
  void* context = nullptr;
  PetscCall(PCShellGetContext(pc, &context));
  try {
    (*static_cast<const LinearSolver::SchurApply*>(context))(x, y);
  } catch (const std::exception& e) {
    SETERRQ(PETSC_COMM_SELF, PETSC_ERR_LIB, "%s", e.what());
  }
  return 0;
}

} // namespace

void LinearSolver::set_schur_preconditioner(SchurApply apply) {
  schur_apply_ = std::move(apply);
  PC pc = nullptr;
  check(KSPGetPC(ksp_, &pc), "KSPGetPC");
  // The pressure block (zero for Taylor-Hood) as the preconditioning matrix: nothing is
  // assembled for the Schur block, and no PC is built on it before the shell replaces it.
  check(PCFieldSplitSetSchurPre(pc, PC_FIELDSPLIT_SCHUR_PRE_A11, nullptr),
        "PCFieldSplitSetSchurPre");
  default_option("-fieldsplit_p_pc_type", "none");
  schur_installed_ = false;
}

void LinearSolver::set_fsi_fields(std::span<const PetscInt> structure,
                                  std::span<const PetscInt> fluid, std::span<const PetscInt> mesh,
                                  std::span<const double> modes, VelocityBlock velocity) {
  SEAM_CHECK(kind_ == SolverKind::iterative, InternalError,
             "a fieldsplit preconditioner for the direct solver");
  MPI_Comm comm = PETSC_COMM_WORLD;
  PC pc = fieldsplit_pc(ksp_, comm);
  // The structure's near-null space, orthonormalized (MatNullSpaceCreate wants it so), goes
  // with its index set: PCFIELDSPLIT gives it to the block's matrix, where GAMG finds it.
  const auto n_s = static_cast<PetscInt>(structure.size());
  const std::size_t n_modes = structure.empty() ? 0 : modes.size() / structure.size();
  long long counts[2] = {static_cast<long long>(n_s), static_cast<long long>(n_modes)};
  MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPI_LONG_LONG, MPI_MAX, comm);
  const bool any_structure = counts[0] > 0;
  const auto n_modes_all = static_cast<std::size_t>(counts[1]);
  std::vector<Vec> vecs(n_modes_all, nullptr);
  for (std::size_t k = 0; k < n_modes_all; ++k) {
    check(VecCreateMPI(comm, n_s, PETSC_DETERMINE, &vecs[k]), "VecCreateMPI");
    PetscScalar* v = nullptr;
    check(VecGetArray(vecs[k], &v), "VecGetArray");
    for (PetscInt q = 0; q < n_s; ++q) v[q] = modes[k * structure.size() + q];
    check(VecRestoreArray(vecs[k], &v), "VecRestoreArray");
    for (std::size_t l = 0; l < k; ++l) {
      PetscScalar dot = 0.0;
      check(VecDot(vecs[k], vecs[l], &dot), "VecDot");
      check(VecAXPY(vecs[k], -dot, vecs[l]), "VecAXPY");
    }
    check(VecNormalize(vecs[k], nullptr), "VecNormalize");
  }
  MatNullSpace nsp = nullptr;
  if (any_structure)
    check(MatNullSpaceCreate(comm, PETSC_FALSE, static_cast<PetscInt>(vecs.size()), vecs.data(),
                             &nsp),
          "MatNullSpaceCreate");
  for (auto& v : vecs) check(VecDestroy(&v), "VecDestroy");
  const std::span<const PetscInt> rows[3] = {structure, fluid, mesh};
  const char* names[3] = {"s", "f", "m"};
  for (int k = 0; k < 3; ++k) {
    IS is = index_set(comm, rows[k]);
    if (k == 0 && nsp)
      check(PetscObjectCompose(reinterpret_cast<PetscObject>(is), "nearnullspace",
                               reinterpret_cast<PetscObject>(nsp)),
            "PetscObjectCompose");
    check(PCFieldSplitSetIS(pc, names[k], is), "PCFieldSplitSetIS");
    check(ISDestroy(&is), "ISDestroy");
  }
  if (nsp) check(MatNullSpaceDestroy(&nsp), "MatNullSpaceDestroy");
  check(PCFieldSplitSetType(pc, PC_COMPOSITE_MULTIPLICATIVE), "PCFieldSplitSetType");
  // The blocks' defaults (docs/fsi.md, "Linear solvers"); the command line wins.
  for (const char* name :
       {"-fieldsplit_s_ksp_type", "-fieldsplit_f_ksp_type", "-fieldsplit_m_ksp_type"})
    default_option(name, "preonly");
  // GAMG's default Chebyshev/Jacobi smoothing converged slowly on the thin flag of FSI1
  // (214 FGMRES iterations per Newton step, 126 with SOR; docs/fsi.md).
  default_option("-fieldsplit_s_pc_type", "gamg");
  default_option("-fieldsplit_s_mg_levels_pc_type", "sor");
  default_option("-fieldsplit_m_pc_type", "hypre");
  default_option("-fieldsplit_m_pc_hypre_type", "boomeramg");
  default_option("-fieldsplit_f_pc_type", "fieldsplit");
  default_option("-fieldsplit_f_pc_fieldsplit_detect_saddle_point", "true");
  default_option("-fieldsplit_f_pc_fieldsplit_type", "schur");
  default_option("-fieldsplit_f_pc_fieldsplit_schur_fact_type", "lower");
  default_option("-fieldsplit_f_pc_fieldsplit_schur_precondition", "selfp");
  schur_defaults("-fieldsplit_f_fieldsplit_", "0", "1", velocity);
  check(KSPSetFromOptions(ksp_), "KSPSetFromOptions");
}

void LinearSolver::set_saddle_point_fields(PetscInt n_first, PetscInt n_second, const Matrix& K) {
  if (kind_ != SolverKind::iterative || saddle_fields_) return;
  saddle_fields_ = true;
  MPI_Comm comm = PETSC_COMM_WORLD;
  PC pc = fieldsplit_pc(ksp_, comm);
  PetscInt first = 0, mine = n_first + n_second;
  MPI_Exscan(&mine, &first, 1, MPIU_INT, MPI_SUM, comm);
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0) first = 0;
  PetscInt bs = 1;
  check(MatGetBlockSize(K.get(), &bs), "MatGetBlockSize");
  MatNullSpace nsp = nullptr;
  check(MatGetNearNullSpace(K.get(), &nsp), "MatGetNearNullSpace");
  const PetscInt starts[2] = {first, first + n_first}, sizes[2] = {n_first, n_second};
  const char* names[2] = {"u", "lm"};
  for (int k = 0; k < 2; ++k) {
    IS is = nullptr;
    check(ISCreateStride(comm, sizes[k], starts[k], 1, &is), "ISCreateStride");
    if (k == 0) {
      // The displacement block keeps the nodes' block size and rigid-body modes for GAMG.
      if (n_first % bs == 0) check(ISSetBlockSize(is, bs), "ISSetBlockSize");
      if (nsp)
        check(PetscObjectCompose(reinterpret_cast<PetscObject>(is), "nearnullspace",
                                 reinterpret_cast<PetscObject>(nsp)),
              "PetscObjectCompose");
    }
    check(PCFieldSplitSetIS(pc, names[k], is), "PCFieldSplitSetIS");
    check(ISDestroy(&is), "ISDestroy");
  }
  lower_schur_selfp(pc);
  for (const char* name : {"-fieldsplit_u_ksp_type", "-fieldsplit_lm_ksp_type"})
    default_option(name, "preonly");
  default_option("-fieldsplit_u_pc_type", "gamg");
  default_option("-fieldsplit_lm_pc_type", "bjacobi");
  check(KSPSetFromOptions(ksp_), "KSPSetFromOptions");
}

void LinearSolver::set_relative_tolerance(double rtol) {
  if (kind_ == SolverKind::direct) {
    reuse_rtol_ = std::max(rtol, factor_reuse_rtol);
    return;
  }
  PetscBool set = PETSC_FALSE;
  check(PetscOptionsHasName(nullptr, nullptr, "-ksp_rtol", &set), "PetscOptionsHasName");
  if (!set)
    check(KSPSetTolerances(ksp_, rtol, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT),
          "KSPSetTolerances");
}

LinearSolver::~LinearSolver() {
  if (reuse_ksp_) KSPDestroy(&reuse_ksp_);
  if (ksp_) KSPDestroy(&ksp_);
}

bool LinearSolver::solve(const Matrix& A, const Vector& b, Vector& x) {
  return solve(A, A, b, x);
}

double LinearSolver::relative_tolerance() const {
  PetscReal rtol = 0.0;
  check(KSPGetTolerances(ksp_, &rtol, nullptr, nullptr, nullptr), "KSPGetTolerances");
  return rtol;
}

bool LinearSolver::solve_once(const Matrix& A, const Matrix& P, const Vector& b, Vector& x,
                              bool reuse) {
  PC pc = nullptr;
  check(KSPGetPC(ksp_, &pc), "KSPGetPC");
  if (!user_reuse_set_)
    check(PCSetReusePreconditioner(pc, reuse ? PETSC_TRUE : PETSC_FALSE),
          "PCSetReusePreconditioner");
  check(KSPSetOperators(ksp_, A.get(), P.get()), "KSPSetOperators");
  if (!reuse) ++builds_;
  last_built_ = !reuse;
  if (!reuse && kind_ == SolverKind::direct && !set_up_factorization(P)) return false;
  if (!reuse) {
    // GAMG's hierarchy is built here, its Galerkin products with the options above only.
    GalerkinOptions options;
    galerkin_options(ksp_, P.get(), options);
    if (options.via && KSPSetUp(ksp_)) return false;
  }
  if (schur_apply_ && !schur_installed_) {
    // The Schur block's solver exists after PCFIELDSPLIT's set-up; the shell stays on it
    // through later set-ups (PCFIELDSPLIT reads the block's options once).
    if (KSPSetUp(ksp_)) return false;
    KSP* blocks = nullptr;
    PetscInt n_blocks = 0;
    check(PCFieldSplitGetSubKSP(pc, &n_blocks, &blocks), "PCFieldSplitGetSubKSP");
    PC schur = nullptr;
    check(KSPGetPC(blocks[n_blocks - 1], &schur), "KSPGetPC");
    check(PetscFree(blocks), "PetscFree");
    check(PCSetType(schur, PCSHELL), "PCSetType");
    check(PCShellSetContext(schur, &schur_apply_), "PCShellSetContext");
    check(PCShellSetApply(schur, apply_schur_shell), "PCShellSetApply");
    check(PCShellSetName(schur, "seam Schur preconditioner"), "PCShellSetName");
    schur_installed_ = true;
  }
  return finish_solve(ksp_, KSPSolve(ksp_, b.get(), x.get()));
}

bool LinearSolver::set_up_factorization(const Matrix& P) {
  PetscObjectState state = 0;
  check(MatGetNonzeroState(P.get(), &state), "MatGetNonzeroState");
  // What PCSetUp compares: the matrix (the PC holds a reference to it) and its nonzero state.
  const bool analysed = P.get() != analysed_ || state != analysed_state_;
  std::optional<ScopedOption> ordering;
  // (ScopedOption keeps the name's pointer: the member outlives it.)
  if (ordering_auto_ && qamd_) ordering.emplace(ordering_option_.c_str(), "6");
  const double start = cpu_seconds();
  const PetscErrorCode ierr = KSPSetUp(ksp_);
  double cost = cpu_seconds() - start;
  MPI_Allreduce(MPI_IN_PLACE, &cost, 1, MPI_DOUBLE, MPI_MAX,
                PetscObjectComm(reinterpret_cast<PetscObject>(ksp_)));
  if (ierr) {
    analysed_ = nullptr; // PCSetUp analyses again after a failure
    return false;
  }
  if (analysed) {
    ++analyses_;
    analysed_ = P.get();
    analysed_state_ = state;
  }
  choose_ordering(analysed, cost);
  return true;
}

void LinearSolver::choose_ordering(bool analysed, double cost) {
  if (!ordering_auto_) return;
  if (!analysed) {
    analyses_in_row_ = 0;
    if (!qamd_) numeric_cost_ = cost;
    return;
  }
  ++analyses_in_row_;
  analysed_cost_[qamd_ ? 1 : 0] = cost;
  if (ordering_decided_) return;
  if (!qamd_) {
    // The pattern changes from one factorization to the next and its analysis dominates: the
    // next analysis tries QAMD (its analysis is one pass of approximate minimum degree; PORD's
    // nested dissection took 0.72 s against QAMD's 0.016 s on the 200 rings' matrix, whose
    // factorization takes 0.06 s with either: docs/performance.md).
    // Set-ups below ordering_trial_seconds are not worth a trial (small problems keep the
    // default, so that their runs and restarts are what they were).
    if (analyses_in_row_ >= 2 && cost > ordering_trial_seconds &&
        (numeric_cost_ < 0.0 || cost > 2.0 * numeric_cost_))
      qamd_ = true;
    return;
  }
  ordering_decided_ = true;
  char text[320];
  if (analysed_cost_[1] < 0.8 * analysed_cost_[0]) {
    std::snprintf(text, sizeof text,
                  "the matrix pattern changes at every factorization: MUMPS orders it with QAMD "
                  "from here (analysis and factorization %.3g s against %.3g s with the default "
                  "ordering)",
                  analysed_cost_[1], analysed_cost_[0]);
  } else {
    qamd_ = false;
    std::snprintf(text, sizeof text,
                  "the matrix pattern changes at every factorization; MUMPS's default ordering "
                  "is kept (analysis and factorization %.3g s against %.3g s with QAMD)",
                  analysed_cost_[0], analysed_cost_[1]);
  }
  ordering_note_ = text;
}

std::vector<double> LinearSolver::ordering_state() const {
  return {ordering_decided_ ? 1.0 : 0.0,
          qamd_ ? 1.0 : 0.0,
          static_cast<double>(analyses_in_row_),
          analysed_cost_[0],
          analysed_cost_[1],
          numeric_cost_};
}

void LinearSolver::restore_ordering_state(std::span<const double> state) {
  if (!ordering_auto_ || state.size() != 6) return;
  ordering_decided_ = state[0] != 0.0;
  qamd_ = state[1] != 0.0;
  analyses_in_row_ = static_cast<int>(state[2]);
  analysed_cost_[0] = state[3];
  analysed_cost_[1] = state[4];
  numeric_cost_ = state[5];
}

std::string LinearSolver::ordering() const {
  if (kind_ != SolverKind::direct) return "";
  if (!ordering_auto_) return "command line";
  return qamd_ ? "qamd" : "default";
}

bool LinearSolver::finish_solve(KSP ksp, PetscErrorCode ierr) {
  if (ierr) return false; // e.g. a zero pivot in the factorization: the caller cuts the step
  KSPConvergedReason reason;
  check(KSPGetConvergedReason(ksp, &reason), "KSPGetConvergedReason");
  PetscInt its = 0;
  check(KSPGetIterationNumber(ksp, &its), "KSPGetIterationNumber");
  iterations_ = static_cast<int>(its);
  return reason > 0;
}

bool LinearSolver::solve_reusing_factors(const Matrix& A, const Vector& b, Vector& x) {
  PC pc = nullptr;
  check(KSPGetPC(ksp_, &pc), "KSPGetPC");
  check(PCSetReusePreconditioner(pc, PETSC_TRUE), "PCSetReusePreconditioner");
  check(KSPSetOperators(reuse_ksp_, A.get(), A.get()), "KSPSetOperators");
  check(
      KSPSetTolerances(reuse_ksp_, reuse_rtol_, 1e-300, PETSC_DEFAULT, factor_reuse_max_iterations),
      "KSPSetTolerances");
  last_built_ = false;
  const PetscErrorCode ierr = KSPSolve(reuse_ksp_, b.get(), x.get());
  check(PCSetReusePreconditioner(pc, PETSC_FALSE), "PCSetReusePreconditioner");
  return finish_solve(reuse_ksp_, ierr);
}

bool LinearSolver::solve(const Matrix& A, const Matrix& P, const Vector& b, Vector& x) {
  if (kind_ == SolverKind::direct) {
    const bool reuse = reuse_allowed_ && reuse_enabled_ && !stale_ && A.get() == P.get();
    reuse_allowed_ = false;
    if (reuse) {
      if (solve_reusing_factors(A, b, x)) {
        // Converged, but slowly: the factorization is too far from the matrices now.
        stale_ = iterations_ > factor_reuse_refactor_iterations;
        return true;
      }
      x.zero(); // abandoned: the matrix is factored
    }
    const bool ok = solve_once(A, P, b, x, false);
    stale_ = !ok;
    return ok;
  }
  if (!keep_ || user_reuse_set_) return solve_once(A, P, b, x, false);
  const double rtol = relative_tolerance();
  if (stale_) {
    const bool ok = solve_once(A, P, b, x, false);
    stale_ = !ok;
    first_iterations_ = iterations_;
    first_rtol_ = rtol;
    return ok;
  }
  const bool ok = solve_once(A, P, b, x, true);
  // The iterations a fresh preconditioner would need at this tolerance: those of the first
  // solve, scaled by the decades of reduction asked for.
  const double decades = std::log10(std::max(rtol, 1e-300));
  const double first_decades = std::log10(std::max(first_rtol_, 1e-300));
  const double expected =
      first_iterations_ * std::max(1.0, first_decades < 0.0 ? decades / first_decades : 1.0);
  if (ok && iterations_ <= 2.0 * expected + 20.0) return true;
  stale_ = true;
  if (ok) return true; // converged, but slowly: the next solve builds it anew
  x.zero();
  return solve(A, P, b, x);
}

} // namespace seam::la
