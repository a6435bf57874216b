#include "seam/mesh/partition.hpp"

#include "seam/common/error.hpp"

#include <metis.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace seam::mesh {

double cell_weight(int n_cell_nodes, double node_share_sum) {
  return n_cell_nodes * node_share_sum;
}

int integer_weight(double weight, double global_sum) {
  // 16 resolves the share of a node in a tetrahedral mesh (1/23 of 4) to a few per cent.
  const double scale = std::min(16.0, 0x1p30 / std::max(global_sum, 1.0));
  return std::max(1, static_cast<int>(std::lround(weight * scale)));
}

std::vector<int> partition_cells(const Mesh& mesh, int n_parts) {
  const std::int32_t n_cells = mesh.n_cells();
  SEAM_CHECK(n_parts >= 1, InputError, "cannot partition a mesh into ", n_parts, " parts");
  SEAM_CHECK(n_parts <= n_cells, InputError, "cannot partition a mesh of ", n_cells, " cells into ",
             n_parts, " parts (more parts than cells)");
  std::vector<int> part(static_cast<std::size_t>(n_cells), 0);
  if (n_parts == 1) return part;

  // The dual graph only needs the corner nodes: two cells sharing a facet share its corners,
  // and high-order nodes would make METIS' node-to-cell lists longer without adding edges.
  std::vector<idx_t> eptr{0}, eind;
  eptr.reserve(static_cast<std::size_t>(n_cells) + 1);
  for (std::int32_t c = 0; c < n_cells; ++c) {
    const auto nodes = mesh.cell(c);
    const int n_v = fem::n_vertices(mesh.cell_type[c]);
    for (int i = 0; i < n_v; ++i) eind.push_back(static_cast<idx_t>(nodes[i]));
    eptr.push_back(static_cast<idx_t>(eind.size()));
  }
  SEAM_CHECK(eind.size() <= static_cast<std::size_t>(std::numeric_limits<idx_t>::max()), InputError,
             "mesh too large for 32-bit METIS indices");

  // Cell weights (cell_weight): the nodes' shares need the number of cells around each node.
  std::vector<std::int32_t> around(static_cast<std::size_t>(mesh.n_nodes()), 0);
  for (std::int32_t c = 0; c < n_cells; ++c)
    for (auto n : mesh.cell(c)) ++around[n];
  std::vector<double> weight(static_cast<std::size_t>(n_cells), 0.0);
  double total = 0.0;
  for (std::int32_t c = 0; c < n_cells; ++c) {
    double shares = 0.0;
    for (auto n : mesh.cell(c)) shares += 1.0 / around[n];
    weight[c] = cell_weight(static_cast<int>(mesh.cell(c).size()), shares);
    total += weight[c];
  }
  std::vector<idx_t> vwgt(static_cast<std::size_t>(n_cells));
  for (std::int32_t c = 0; c < n_cells; ++c) vwgt[c] = integer_weight(weight[c], total);

  idx_t ne = n_cells, nn = mesh.n_nodes(), ncommon = mesh.dim == 2 ? 2 : 3, nparts = n_parts;
  idx_t objval = 0;
  std::array<idx_t, METIS_NOPTIONS> options{};
  METIS_SetDefaultOptions(options.data());
  options[METIS_OPTION_NUMBERING] = 0;
  options[METIS_OPTION_SEED] = 1; // reproducible partitions on every rank and every run
  std::vector<idx_t> epart(static_cast<std::size_t>(n_cells)), npart(static_cast<std::size_t>(nn));
  const int status =
      METIS_PartMeshDual(&ne, &nn, eptr.data(), eind.data(), vwgt.data(), nullptr, &ncommon,
                         &nparts, nullptr, options.data(), &objval, epart.data(), npart.data());
  SEAM_CHECK(status == METIS_OK, InternalError, "METIS_PartMeshDual failed with status ", status,
             " for ", n_cells, " cells and ", n_parts, " parts");
  for (std::size_t c = 0; c < part.size(); ++c) part[c] = static_cast<int>(epart[c]);
  return part;
}

NodeNumbering number_nodes(const Mesh& mesh, std::span<const int> cell_part, int n_parts) {
  SEAM_CHECK(n_parts >= 1, InputError, "number_nodes: ", n_parts, " parts");
  SEAM_CHECK(static_cast<std::int64_t>(cell_part.size()) == mesh.n_cells(), InputError,
             "number_nodes: ", cell_part.size(), " cell parts for ", mesh.n_cells(), " cells");
  const auto n_nodes = static_cast<std::size_t>(mesh.n_nodes());
  NodeNumbering out;
  out.owner.assign(n_nodes, std::numeric_limits<int>::max());
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c) {
    const int p = cell_part[c];
    SEAM_CHECK(p >= 0 && p < n_parts, InputError, "number_nodes: cell ", c, " is in part ", p,
               ", outside [0, ", n_parts, ")");
    for (auto n : mesh.cell(c)) {
      auto& o = out.owner[n];
      o = std::min(o, p);
    }
  }
  for (auto& o : out.owner)
    if (o == std::numeric_limits<int>::max()) o = 0;

  out.offsets.assign(static_cast<std::size_t>(n_parts) + 1, 0);
  for (auto o : out.owner) ++out.offsets[o + 1];
  for (std::size_t p = 0; p < static_cast<std::size_t>(n_parts); ++p)
    out.offsets[p + 1] += out.offsets[p];

  // Increasing mesh node index within each part.
  std::vector<std::int64_t> next(out.offsets.begin(), out.offsets.end() - 1);
  out.new_index.resize(n_nodes);
  out.old_index.resize(n_nodes);
  for (std::size_t n = 0; n < n_nodes; ++n) {
    const auto g = next[out.owner[n]]++;
    out.new_index[n] = g;
    out.old_index[g] = static_cast<std::int32_t>(n);
  }
  return out;
}

} // namespace seam::mesh
