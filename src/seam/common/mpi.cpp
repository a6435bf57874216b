#include "seam/common/mpi.hpp"

namespace seam {

int Comm::rank() const {
  int r = 0;
  MPI_Comm_rank(comm_, &r);
  return r;
}

int Comm::size() const {
  int s = 1;
  MPI_Comm_size(comm_, &s);
  return s;
}

namespace {
template <class T> T reduce(MPI_Comm comm, T v, MPI_Datatype type, MPI_Op op) {
  T out{};
  MPI_Allreduce(&v, &out, 1, type, op, comm);
  return out;
}
} // namespace

double Comm::sum(double v) const {
  return reduce(comm_, v, MPI_DOUBLE, MPI_SUM);
}
double Comm::max(double v) const {
  return reduce(comm_, v, MPI_DOUBLE, MPI_MAX);
}
double Comm::min(double v) const {
  return reduce(comm_, v, MPI_DOUBLE, MPI_MIN);
}
std::int64_t Comm::sum(std::int64_t v) const {
  return reduce(comm_, v, MPI_INT64_T, MPI_SUM);
}
std::int64_t Comm::max(std::int64_t v) const {
  return reduce(comm_, v, MPI_INT64_T, MPI_MAX);
}
int Comm::sum(int v) const {
  return reduce(comm_, v, MPI_INT, MPI_SUM);
}
int Comm::max(int v) const {
  return reduce(comm_, v, MPI_INT, MPI_MAX);
}

void Comm::sum_in_place(std::span<double> v) const {
  if (!v.empty())
    MPI_Allreduce(MPI_IN_PLACE, v.data(), static_cast<int>(v.size()), MPI_DOUBLE, MPI_SUM, comm_);
}

bool Comm::any(bool v) const {
  return reduce(comm_, v ? 1 : 0, MPI_INT, MPI_MAX) != 0;
}

void Comm::barrier() const {
  MPI_Barrier(comm_);
}

void Comm::broadcast(std::string& s, int root) const {
  std::vector<char> buf(s.begin(), s.end());
  broadcast(buf, root);
  s.assign(buf.begin(), buf.end());
}

} // namespace seam
