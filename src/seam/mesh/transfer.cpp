#include "seam/mesh/transfer.hpp"

#include "seam/common/error.hpp"

#include <algorithm>
#include <cstring>
#include <type_traits>

namespace seam::mesh {

namespace {

constexpr int tag = 7301;
constexpr std::size_t chunk = std::size_t{1} << 30; // bytes per MPI message, < INT_MAX

class Packer {
public:
  template <class T> void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* p = reinterpret_cast<const char*>(&v);
    bytes.insert(bytes.end(), p, p + sizeof(T));
  }
  template <class T> void array(const std::vector<T>& v) {
    value(static_cast<std::uint64_t>(v.size()));
    const auto* p = reinterpret_cast<const char*>(v.data());
    bytes.insert(bytes.end(), p, p + v.size() * sizeof(T));
  }
  void text(const std::string& s) {
    value(static_cast<std::uint64_t>(s.size()));
    bytes.insert(bytes.end(), s.begin(), s.end());
  }
  template <class T, class F> void list(const std::vector<T>& v, F&& each) {
    value(static_cast<std::uint64_t>(v.size()));
    for (const auto& e : v) each(e);
  }
  std::vector<char> bytes;
};

class Unpacker {
public:
  explicit Unpacker(const std::vector<char>& bytes) : bytes_(bytes) {}
  template <class T> void value(T& v) { take(&v, sizeof(T)); }
  template <class T> void array(std::vector<T>& v) {
    std::uint64_t n = 0;
    value(n);
    v.resize(n);
    take(v.data(), n * sizeof(T));
  }
  void text(std::string& s) {
    std::uint64_t n = 0;
    value(n);
    s.resize(n);
    take(s.data(), n);
  }
  template <class T, class F> void list(std::vector<T>& v, F&& each) {
    std::uint64_t n = 0;
    value(n);
    v.resize(n);
    for (auto& e : v) each(e);
  }

private:
  void take(void* dst, std::size_t n) {
    SEAM_CHECK(at_ + n <= bytes_.size(), InternalError, "mesh message truncated at byte ", at_);
    if (n) std::memcpy(dst, bytes_.data() + at_, n);
    at_ += n;
  }
  const std::vector<char>& bytes_;
  std::size_t at_ = 0;
};

// One field list for both directions keeps packing and unpacking in step.
template <class P, class R> void region_fields(P& p, R& r) {
  p.text(r.name);
  p.value(r.dim);
  p.value(r.tag);
  p.array(r.cells);
  p.array(r.facet_cell);
  p.array(r.facet_local);
  p.array(r.nodes);
}

template <class P, class M> void mesh_fields(P& p, M& m) {
  p.value(m.dim);
  p.array(m.x);
  p.array(m.cell_type);
  p.array(m.cell_offsets);
  p.array(m.cell_nodes);
  p.list(m.regions, [&](auto& r) { region_fields(p, r); });
}

template <class P, class D> void part_fields(P& p, D& d) {
  mesh_fields(p, d.mesh);
  p.array(d.node_gid);
  p.array(d.cell_gid);
  p.array(d.node_owner);
  p.array(d.node_index);
  p.array(d.cell_owner);
  p.array(d.cell_role);
  p.array(d.node_offsets);
  p.value(d.n_global_nodes);
  p.value(d.n_global_cells);
}

} // namespace

void broadcast_text(MPI_Comm comm, std::string& text) {
  std::uint64_t n = text.size();
  MPI_Bcast(&n, 1, MPI_UINT64_T, 0, comm);
  text.resize(n);
  if (n) MPI_Bcast(text.data(), static_cast<int>(n), MPI_CHAR, 0, comm);
}

void send_mesh(MPI_Comm comm, int dest, const DistributedMesh& part) {
  Packer p;
  part_fields(p, part);
  std::uint64_t n = p.bytes.size();
  MPI_Send(&n, 1, MPI_UINT64_T, dest, tag, comm);
  for (std::size_t at = 0; at < n; at += chunk)
    MPI_Send(p.bytes.data() + at, static_cast<int>(std::min(chunk, n - at)), MPI_BYTE, dest, tag,
             comm);
}

DistributedMesh receive_mesh(MPI_Comm comm, int source) {
  std::uint64_t n = 0;
  MPI_Recv(&n, 1, MPI_UINT64_T, source, tag, comm, MPI_STATUS_IGNORE);
  std::vector<char> bytes(n);
  for (std::size_t at = 0; at < n; at += chunk)
    MPI_Recv(bytes.data() + at, static_cast<int>(std::min(chunk, n - at)), MPI_BYTE, source, tag,
             comm, MPI_STATUS_IGNORE);
  DistributedMesh d;
  Unpacker u(bytes);
  part_fields(u, d);
  d.mesh.check();
  return d;
}

void broadcast_mesh(MPI_Comm comm, Mesh& mesh) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  Packer p;
  if (rank == 0) mesh_fields(p, mesh);
  std::uint64_t n = p.bytes.size();
  MPI_Bcast(&n, 1, MPI_UINT64_T, 0, comm);
  p.bytes.resize(n);
  for (std::size_t at = 0; at < n; at += chunk)
    MPI_Bcast(p.bytes.data() + at, static_cast<int>(std::min(chunk, n - at)), MPI_BYTE, 0, comm);
  if (rank == 0) return;
  mesh = Mesh{};
  Unpacker u(p.bytes);
  mesh_fields(u, mesh);
}

} // namespace seam::mesh
