#pragma once
// Surfaces and references for the parallel tests: every rank generates the same whole surface
// (small), keeps its part of it, and compares distributed results with serial references.
#include "seam/parallel/distributed_search.hpp"
#include "seam/parallel/surface_part.hpp"
#include "seam/search/traversal.hpp"
#include "unit/search/surfaces.hpp"

#include <mpi.h>

#include <algorithm>
#include <numeric>
#include <vector>

namespace seam::parallel::test {

using search::test::Mesh;

inline MPI_Comm world() {
  return MPI_COMM_WORLD;
}
inline int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}
inline int size() {
  int s = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &s);
  return s;
}

/// Facets f of `mesh` with f % size == rank (an input distribution unrelated to geometry).
inline SurfacePart round_robin_part(const Mesh& mesh) {
  std::vector<local_index> mine;
  const local_index n = static_cast<local_index>(mesh.offsets.size() - 1);
  for (local_index f = rank(); f < n; f += size()) mine.push_back(f);
  return extract_part(mesh.dim, mesh.coords, mesh.offsets, mesh.conn, mine);
}

/// Facets in contiguous blocks of ids (another unrelated input distribution).
inline SurfacePart block_part(const Mesh& mesh) {
  const local_index n = static_cast<local_index>(mesh.offsets.size() - 1);
  const local_index b = static_cast<local_index>(std::int64_t(n) * rank() / size());
  const local_index e = static_cast<local_index>(std::int64_t(n) * (rank() + 1) / size());
  std::vector<local_index> mine(e - b);
  std::iota(mine.begin(), mine.end(), b);
  return extract_part(mesh.dim, mesh.coords, mesh.offsets, mesh.conn, mine);
}

/// The part's node coordinates taken again from the (moved) whole mesh.
inline void refresh_coords(SurfacePart& part, const Mesh& mesh) {
  for (local_index n = 0; n < part.n_nodes(); ++n)
    for (int d = 0; d < part.dim; ++d)
      part.coords[n * part.dim + d] = mesh.coords[part.node_ids[n] * part.dim + d];
}

/// All-pairs reference on the whole surfaces with the same volumes and inflation.
inline std::vector<GlobalPair> brute_force_pairs(const Mesh& slave, const Mesh& master,
                                                 double inflation) {
  search::TreeOptions o;
  o.inflation = inflation;
  const search::Tree ts(slave.view(), o), tm(master.view(), o);
  std::vector<GlobalPair> out;
  for (const auto& p : search::find_pairs_brute_force(ts, tm)) out.push_back({p.slave, p.master});
  std::sort(out.begin(), out.end());
  return out;
}

/// The centroids of a part's facets, its ids and a parts array: what an Rcb call needs.
struct Points {
  std::vector<double> x;
  std::vector<int> parts;
  explicit Points(const SurfacePart& p) : parts(p.facet_ids.size()) { facet_centroids(p, x); }
};

} // namespace seam::parallel::test
