#pragma once
// The brute-force check of a distributed mesh against the whole mesh (built identically on every
// rank): the owned cells cover the mesh exactly once, the ghosts are exactly the cells sharing a
// node with an owned cell, nodes, coordinates, regions and the global node numbering match the
// whole mesh, and no rank holds more than its cells, their ghost layer and the interface cells
// (the memory assertion). Used for the rank-0 path and for the chunked reader.
#include "parallel_test_support.hpp"
#include "seam/mesh/distribute.hpp"
#include "seam/parallel/exchange.hpp"

#include <gtest/gtest.h>

#include <climits>
#include <cstdio>
#include <set>

namespace seam::parallel::test {

using mesh::CellRole;
using mesh::DistributedMesh;

struct Reference {
  std::vector<int> part;               // global cell -> rank assembling it, from the ranks' parts
  std::vector<std::int64_t> number;    // global node -> global number, from its owner
  std::vector<std::int64_t> held;      // expected held cells here, sorted
  std::int64_t n_own = 0, n_layer = 0; // owned cells and ghost-layer cells here
};

// What every rank should hold, from the owned cells that the ranks report (so the partition
// itself is not taken from the code under test's internals).
inline Reference reference(const mesh::Mesh& g, const DistributedMesh& d,
                           const std::vector<std::string>& interfaces) {
  Reference ref;
  std::vector<std::int64_t> own;
  for (std::int32_t c = 0; c < d.n_cells(); ++c)
    if (d.cell_role[c] == CellRole::owned) own.push_back(d.cell_gid[c]);
  std::vector<std::int64_t> offsets;
  const auto all = allgatherv<std::int64_t>(world(), own, offsets);
  ref.part.assign(g.n_cells(), -1);
  for (int r = 0; r < size(); ++r)
    for (auto k = offsets[r]; k < offsets[r + 1]; ++k) {
      EXPECT_EQ(ref.part[all[k]], -1) << "cell " << all[k] << " owned twice";
      ref.part[all[k]] = r;
    }
  EXPECT_EQ(std::count(ref.part.begin(), ref.part.end(), -1), 0) << "cells owned by no rank";

  // One layer: every cell sharing a node with an owned cell (brute force over node sets).
  std::vector<char> own_node(g.n_nodes(), 0);
  for (std::int32_t c = 0; c < g.n_cells(); ++c)
    if (ref.part[c] == rank())
      for (auto n : g.cell(c)) own_node[n] = 1;
  std::set<std::int64_t> held;
  for (std::int32_t c = 0; c < g.n_cells(); ++c) {
    const auto nodes = g.cell(c);
    if (ref.part[c] == rank()) {
      ++ref.n_own;
      held.insert(c);
    } else if (std::any_of(nodes.begin(), nodes.end(), [&](auto n) { return own_node[n]; })) {
      ++ref.n_layer;
      held.insert(c);
    }
  }
  for (const auto& r : g.regions)
    if (std::find(interfaces.begin(), interfaces.end(), r.name) != interfaces.end())
      held.insert(r.facet_cell.begin(), r.facet_cell.end());
  ref.held.assign(held.begin(), held.end());

  // Owner = smallest rank among the node's cells; numbers from the owners' own reports.
  std::vector<std::int64_t> pairs; // (gid, number) of owned nodes
  for (std::int32_t n = 0; n < d.n_nodes(); ++n)
    if (d.node_owner[n] == rank()) pairs.insert(pairs.end(), {d.node_gid[n], d.node_index[n]});
  const auto numbers = allgatherv<std::int64_t>(world(), pairs, offsets);
  ref.number.assign(g.n_nodes(), -1);
  std::vector<char> used(g.n_nodes(), 0);
  for (std::size_t k = 0; k < numbers.size(); k += 2) {
    EXPECT_EQ(ref.number[numbers[k]], -1) << "node " << numbers[k] << " owned twice";
    ref.number[numbers[k]] = numbers[k + 1];
    EXPECT_EQ(used[numbers[k + 1]], 0) << "number " << numbers[k + 1] << " used twice";
    used[numbers[k + 1]] = 1;
  }
  EXPECT_EQ(std::count(ref.number.begin(), ref.number.end(), -1), 0) << "nodes owned by none";
  return ref;
}

inline void check_regions(const mesh::Mesh& g, const DistributedMesh& d) {
  ASSERT_EQ(d.mesh.regions.size(), g.regions.size());
  std::vector<std::int32_t> cell_local(g.n_cells(), -1), node_local(g.n_nodes(), -1);
  for (std::int32_t c = 0; c < d.n_cells(); ++c) cell_local[d.cell_gid[c]] = c;
  for (std::int32_t n = 0; n < d.n_nodes(); ++n) node_local[d.node_gid[n]] = n;
  for (std::size_t i = 0; i < g.regions.size(); ++i) {
    const auto &gr = g.regions[i], &lr = d.mesh.regions[i];
    EXPECT_EQ(lr.name, gr.name);
    EXPECT_EQ(lr.dim, gr.dim);
    EXPECT_EQ(lr.tag, gr.tag);
    std::vector<std::int32_t> cells, facet_cell, nodes;
    std::vector<std::int8_t> facet_local;
    for (auto c : gr.cells)
      if (cell_local[c] >= 0) cells.push_back(cell_local[c]);
    for (std::size_t k = 0; k < gr.facet_cell.size(); ++k)
      if (cell_local[gr.facet_cell[k]] >= 0) {
        facet_cell.push_back(cell_local[gr.facet_cell[k]]);
        facet_local.push_back(gr.facet_local[k]);
      }
    for (auto n : gr.nodes)
      if (node_local[n] >= 0) nodes.push_back(node_local[n]);
    EXPECT_EQ(lr.cells, cells) << gr.name;
    EXPECT_EQ(lr.facet_cell, facet_cell) << gr.name;
    EXPECT_EQ(lr.facet_local, facet_local) << gr.name;
    EXPECT_EQ(lr.nodes, nodes) << gr.name;
    EXPECT_TRUE(std::is_sorted(lr.cells.begin(), lr.cells.end()));
    EXPECT_TRUE(std::is_sorted(lr.facet_cell.begin(), lr.facet_cell.end()));
  }
}

/// Checks every rank's part `d` of the whole mesh `g` (built or read on every rank): every rank
/// holds at most (own + layer) * 1.1 + interface-only cells, and at most max_held_fraction of g.
inline void check_part(const mesh::Mesh& g, const DistributedMesh& d,
                       const std::vector<std::string>& interfaces, double max_held_fraction = 1.0) {
  ASSERT_NO_THROW(d.mesh.check());
  EXPECT_EQ(d.n_global_cells, g.n_cells());
  EXPECT_EQ(d.n_global_nodes, g.n_nodes());
  ASSERT_EQ(d.cell_gid.size(), static_cast<std::size_t>(d.n_cells()));
  ASSERT_EQ(d.node_gid.size(), static_cast<std::size_t>(d.n_nodes()));
  // Monotone local numbering.
  EXPECT_TRUE(std::adjacent_find(d.cell_gid.begin(), d.cell_gid.end(), std::greater_equal<>()) ==
              d.cell_gid.end());
  EXPECT_TRUE(std::adjacent_find(d.node_gid.begin(), d.node_gid.end(), std::greater_equal<>()) ==
              d.node_gid.end());

  const Reference ref = reference(g, d, interfaces);
  if (::testing::Test::HasFailure()) return; // no collective follows
  EXPECT_EQ(d.cell_gid, ref.held);
  const auto held = static_cast<double>(d.n_cells());
  EXPECT_EQ(d.count(CellRole::owned), ref.n_own);
  EXPECT_EQ(d.count(CellRole::ghost), ref.n_layer);
  EXPECT_LE(held,
            1.1 * static_cast<double>(ref.n_own + ref.n_layer) + d.count(CellRole::interface));
  EXPECT_LE(held, max_held_fraction * g.n_cells()) << "rank " << rank();
  if (max_held_fraction < 1.0)
    std::printf("   rank %d: %lld owned + %lld ghost cells, holds %d of %d cells (%.3f)\n", rank(),
                static_cast<long long>(ref.n_own), static_cast<long long>(ref.n_layer), d.n_cells(),
                g.n_cells(), held / g.n_cells());

  // Cells: same type, same nodes, right owner and role.
  std::vector<char> node_used(d.n_nodes(), 0);
  for (std::int32_t c = 0; c < d.n_cells(); ++c) {
    const auto gc = static_cast<std::int32_t>(d.cell_gid[c]);
    EXPECT_EQ(d.mesh.cell_type[c], g.cell_type[gc]);
    const auto ln = d.mesh.cell(c), gn = g.cell(gc);
    ASSERT_EQ(ln.size(), gn.size());
    for (std::size_t k = 0; k < ln.size(); ++k) {
      EXPECT_EQ(d.node_gid[ln[k]], gn[k]);
      node_used[ln[k]] = 1;
    }
    EXPECT_EQ(d.cell_owner[c], ref.part[gc]);
    EXPECT_EQ(d.cell_role[c] == CellRole::owned, ref.part[gc] == rank());
  }
  EXPECT_EQ(std::count(node_used.begin(), node_used.end(), 0), 0) << "nodes of no held cell";

  // Nodes: coordinates bit for bit, owner = smallest rank of the node's cells, the owner's
  // number, owned numbers contiguous per rank.
  std::vector<int> owner(g.n_nodes(), INT_MAX);
  for (std::int32_t c = 0; c < g.n_cells(); ++c)
    for (auto n : g.cell(c)) owner[n] = std::min(owner[n], ref.part[c]);
  ASSERT_EQ(d.node_offsets.size(), static_cast<std::size_t>(size()) + 1);
  for (std::int32_t n = 0; n < d.n_nodes(); ++n) {
    const auto gn = static_cast<std::int32_t>(d.node_gid[n]);
    for (int a = 0; a < g.dim; ++a) EXPECT_EQ(d.mesh.node(n)[a], g.node(gn)[a]);
    EXPECT_EQ(d.node_owner[n], owner[gn]);
    EXPECT_EQ(d.node_index[n], ref.number[gn]);
    const auto o = static_cast<std::size_t>(d.node_owner[n]);
    EXPECT_GE(d.node_index[n], d.node_offsets[o]);
    EXPECT_LT(d.node_index[n], d.node_offsets[o + 1]);
  }
  EXPECT_EQ(d.node_offsets.back(), g.n_nodes());
  check_regions(g, d);
}

} // namespace seam::parallel::test
