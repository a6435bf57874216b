#include "seam/parallel/surface_part.hpp"

#include "seam/common/error.hpp"
#include "seam/parallel/exchange.hpp"

#include <algorithm>
#include <bit>
#include <numeric>

namespace seam::parallel {

SurfacePart extract_part(int dim, std::span<const double> all_coords,
                         std::span<const local_index> offsets,
                         std::span<const local_index> connectivity,
                         std::span<const local_index> facets) {
  SurfacePart p;
  p.dim = dim;
  p.facet_ids.reserve(facets.size());
  for (const local_index f : facets) {
    p.facet_ids.push_back(f);
    for (local_index k = offsets[f]; k < offsets[f + 1]; ++k) p.node_ids.push_back(connectivity[k]);
  }
  std::sort(p.node_ids.begin(), p.node_ids.end());
  p.node_ids.erase(std::unique(p.node_ids.begin(), p.node_ids.end()), p.node_ids.end());
  for (const local_index f : facets) {
    for (local_index k = offsets[f]; k < offsets[f + 1]; ++k) {
      const auto it = std::lower_bound(p.node_ids.begin(), p.node_ids.end(), connectivity[k]);
      p.connectivity.push_back(static_cast<local_index>(it - p.node_ids.begin()));
    }
    p.offsets.push_back(static_cast<local_index>(p.connectivity.size()));
  }
  p.coords.reserve(p.node_ids.size() * dim);
  for (const global_index n : p.node_ids)
    for (int d = 0; d < dim; ++d) p.coords.push_back(all_coords[n * dim + d]);
  return p;
}

void facet_centroids(const SurfacePart& part, std::vector<double>& out) {
  const int dim = part.dim;
  out.assign(static_cast<std::size_t>(part.n_facets()) * dim, 0.0);
  for (local_index f = 0; f < part.n_facets(); ++f) {
    const local_index b = part.offsets[f], e = part.offsets[f + 1];
    for (local_index k = b; k < e; ++k)
      for (int d = 0; d < dim; ++d) out[f * dim + d] += part.coords[part.connectivity[k] * dim + d];
    for (int d = 0; d < dim; ++d) out[f * dim + d] /= std::max<local_index>(e - b, 1);
  }
}

namespace {

// Wire format, one 8-byte word per item: facet id, node count n, then n times (node id, dim
// coordinates as bit copies of the doubles).
using Word = std::int64_t;

Word as_word(double v) {
  return std::bit_cast<Word>(v);
}
double as_double(Word w) {
  return std::bit_cast<double>(w);
}

} // namespace

SurfacePart send_facets(MPI_Comm comm, const SurfacePart& part,
                        std::span<const std::int64_t> send_offsets,
                        std::span<const local_index> send_facets, ExchangeStats* stats) {
  int size = 1, rank = 0;
  MPI_Comm_size(comm, &size);
  MPI_Comm_rank(comm, &rank);
  bool bad = send_offsets.size() != static_cast<std::size_t>(size) + 1 || send_offsets[0] != 0 ||
             send_offsets[size] != static_cast<std::int64_t>(send_facets.size());
  for (const local_index f : send_facets) bad |= f < 0 || f >= part.n_facets();
  // One Allreduce for the check and the dimension (max and -min over the ranks with facets).
  const bool has = part.n_facets() > 0;
  int v[3] = {bad ? 1 : 0, has ? part.dim : 0, has ? -part.dim : -4};
  MPI_Allreduce(MPI_IN_PLACE, v, 3, MPI_INT, MPI_MAX, comm);
  SEAM_CHECK(!v[0] && (v[1] == 0 || v[1] == -v[2]), InputError,
             "parallel: send_facets needs size + 1 offsets over valid facets, and one dimension "
             "on all ranks",
             v[0] && !bad ? " (on another rank)" : "");
  const int dim = v[1] > 0 ? v[1] : part.dim;
  const int words_per_node = 1 + dim;

  std::vector<std::int64_t> word_offsets(size + 1, 0);
  for (int r = 0; r < size; ++r) {
    std::int64_t n = 0;
    for (std::int64_t k = send_offsets[r]; k < send_offsets[r + 1]; ++k) {
      const local_index f = send_facets[k];
      n += 2 + (part.offsets[f + 1] - part.offsets[f]) * words_per_node;
    }
    word_offsets[r + 1] = word_offsets[r] + n;
  }
  std::vector<Word> buffer(word_offsets[size]);
  std::size_t w = 0;
  for (const local_index f : send_facets) {
    buffer[w++] = part.facet_ids[f];
    buffer[w++] = part.offsets[f + 1] - part.offsets[f];
    for (local_index k = part.offsets[f]; k < part.offsets[f + 1]; ++k) {
      const local_index n = part.connectivity[k];
      buffer[w++] = part.node_ids[n];
      for (int d = 0; d < dim; ++d) buffer[w++] = as_word(part.coords[n * dim + d]);
    }
  }
  std::vector<std::int64_t> recv_offsets;
  const std::vector<Word> recv = alltoallv<Word>(comm, buffer, word_offsets, recv_offsets);

  // Facets in order of global id; nodes deduplicated by global id.
  struct Header {
    global_index id;
    std::size_t at; // word index of the node count
  };
  std::vector<Header> headers;
  std::vector<std::pair<global_index, std::size_t>> nodes; // (node id, word index of its record)
  for (std::size_t i = 0; i < recv.size();) {
    headers.push_back({recv[i], i + 1});
    const auto n = static_cast<std::size_t>(recv[i + 1]);
    for (std::size_t k = 0; k < n; ++k)
      nodes.emplace_back(recv[i + 2 + k * words_per_node], i + 2 + k * words_per_node);
    i += 2 + n * words_per_node;
  }
  std::sort(headers.begin(), headers.end(),
            [](const Header& a, const Header& b) { return a.id < b.id; });
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end(),
                          [](const auto& a, const auto& b) { return a.first == b.first; }),
              nodes.end());

  SurfacePart out;
  out.dim = dim;
  out.node_ids.reserve(nodes.size());
  out.coords.reserve(nodes.size() * dim);
  for (const auto& [id, at] : nodes) {
    out.node_ids.push_back(id);
    for (int d = 0; d < dim; ++d) out.coords.push_back(as_double(recv[at + 1 + d]));
  }
  out.facet_ids.reserve(headers.size());
  for (const auto& h : headers) {
    out.facet_ids.push_back(h.id);
    const auto n = static_cast<std::size_t>(recv[h.at]);
    for (std::size_t k = 0; k < n; ++k) {
      const global_index id = recv[h.at + 1 + k * words_per_node];
      const auto it = std::lower_bound(out.node_ids.begin(), out.node_ids.end(), id);
      out.connectivity.push_back(static_cast<local_index>(it - out.node_ids.begin()));
    }
    out.offsets.push_back(static_cast<local_index>(out.connectivity.size()));
  }
  if (stats) {
    stats->facets_sent = static_cast<std::int64_t>(send_facets.size()) -
                         (send_offsets[rank + 1] - send_offsets[rank]);
    stats->bytes_sent = static_cast<std::int64_t>(
        (word_offsets[size] - (word_offsets[rank + 1] - word_offsets[rank])) * sizeof(Word));
    stats->facets_received = out.n_facets();
  }
  return out;
}

SurfacePart migrate(MPI_Comm comm, const SurfacePart& part, std::span<const int> dest,
                    ExchangeStats* stats) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  const bool bad =
      dest.size() != part.facet_ids.size() ||
      std::any_of(dest.begin(), dest.end(), [size](int r) { return r < 0 || r >= size; });
  check_collectively(comm, bad,
                     "parallel: migrate needs one destination rank in [0, size) per facet");
  // Counting sort of the facets by destination (stable: each rank's order is kept).
  std::vector<std::int64_t> offsets(size + 1, 0);
  for (const int r : dest) ++offsets[r + 1];
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  std::vector<local_index> order(dest.size());
  std::vector<std::int64_t> next(offsets.begin(), offsets.end() - 1);
  for (std::size_t f = 0; f < dest.size(); ++f)
    order[next[dest[f]]++] = static_cast<local_index>(f);
  return send_facets(comm, part, offsets, order, stats);
}

} // namespace seam::parallel
