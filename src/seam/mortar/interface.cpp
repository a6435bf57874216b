#include "seam/mortar/interface.hpp"

#include <algorithm>
#include <numeric>

#include "seam/common/error.hpp"
#include "seam/mortar/normals.hpp"

namespace seam::mortar {

namespace {

template <int Dim>
SlaveFacet<Dim> prepare_slave(const FacetSet& slave, local_index f,
                              const std::vector<double>& nodal_normals, Multiplier multiplier) {
  SlaveFacet<Dim> sf;
  sf.facet = gather_facet<Dim>(slave, f);
  const auto nodes = slave.facet_nodes(f);
  for (int i = 0; i < sf.facet.n_nodes; ++i) {
    const auto base = static_cast<std::size_t>(nodes[static_cast<std::size_t>(i)]) * Dim;
    for (int a = 0; a < Dim; ++a)
      sf.normals(a, i) = nodal_normals[base + static_cast<std::size_t>(a)];
  }
  sf.basis = make_slave_basis(sf.facet, multiplier);
  return sf;
}

template <int Dim>
void assemble(const FacetSet& slave, const FacetSet& master,
              std::span<const CandidatePair> candidates, const MortarOptions& options,
              std::span<const char> bound, MortarOperators& ops) {
  // Visit the candidates grouped by slave facet so that each slave facet's normals and dual
  // coefficients are computed once.
  std::vector<std::size_t> order(candidates.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return candidates[a].slave < candidates[b].slave;
  });
  SlaveFacet<Dim> sf;
  local_index current = -1;
  unsigned bound_mask = 0;
  SmallMatrix R;
  for (const std::size_t index : order) {
    const CandidatePair pair = candidates[index];
    if (pair.slave != current) {
      current = pair.slave;
      sf = prepare_slave<Dim>(slave, current, ops.nodal_normals, options.multiplier);
      bound_mask = 0;
      if (!bound.empty()) {
        const auto nodes = slave.facet_nodes(current);
        for (std::size_t i = 0; i < nodes.size(); ++i)
          if (bound[static_cast<std::size_t>(nodes[i])] != 0) bound_mask |= 1U << i;
      }
      if (bound_mask != 0) R = boundary_transformation(sf.facet.n_nodes, bound_mask);
    }
    const Facet<Dim> mf = gather_facet<Dim>(master, pair.master);
    PairContribution c = integrate_pair(sf, mf, options.pair_options(pair.slave, pair.master));
    ops.n_projection_failures += c.n_projection_failures;
    if (c.n_cells == 0) continue;
    if (bound_mask != 0) {
      // D, M and the weighted gap are linear in Phi, so Phi^ = R Phi is applied to the rows
      // of the pair's blocks; the pair kernels stay unaware of the modification.
      const int ns = c.n_slave, nm = c.n_master;
      const SmallMatrix D = R * c.D.topLeftCorner(ns, ns);
      const SmallMatrix M = R * c.M.topLeftCorner(ns, nm);
      const NodalVector gap = c.weighted_gap;
      c.D.topLeftCorner(ns, ns) = D;
      c.M.topLeftCorner(ns, nm) = M;
      c.weighted_gap.head(ns) = R * gap.head(ns);
    }
    ++ops.n_pairs_integrated;
    ops.n_integration_cells += c.n_cells;
    ops.slave_facet_cells[static_cast<std::size_t>(pair.slave)] += c.n_cells;
    ops.integrated_area += c.area;
    const auto s_nodes = slave.facet_nodes(pair.slave);
    const auto m_nodes = master.facet_nodes(pair.master);
    for (int j = 0; j < c.n_slave; ++j) {
      if (((bound_mask >> j) & 1U) != 0) continue; // no multiplier, no row
      const local_index row = s_nodes[static_cast<std::size_t>(j)];
      for (int k = 0; k < c.n_slave; ++k) {
        // Dual: only the diagonal (and bound columns) is accumulated; skip structural zeros.
        if (c.D(j, k) != 0.0)
          ops.D.push_back({row, s_nodes[static_cast<std::size_t>(k)], c.D(j, k)});
      }
      for (int l = 0; l < c.n_master; ++l) {
        ops.M.push_back({row, m_nodes[static_cast<std::size_t>(l)], c.M(j, l)});
      }
      ops.weighted_gap[static_cast<std::size_t>(row)] += c.weighted_gap(j);
    }
  }
}

// Rows of T for all slave facet nodes; an edge node shared by two facets must get the same
// row from both.
std::vector<Triplet> transformation_triplets(const FacetSet& slave, Multiplier multiplier) {
  bool any_modified = false;
  for (const fem::CellType type : slave.types) {
    any_modified = any_modified || basis_modification(type, multiplier) != 0.0;
  }
  if (!any_modified) return {};
  std::vector<Triplet> t;
  for (local_index f = 0; f < slave.n_facets(); ++f) {
    const fem::CellType type = slave.types[static_cast<std::size_t>(f)];
    const SmallMatrix T = transformation_matrix(type, basis_modification(type, multiplier));
    const auto nodes = slave.facet_nodes(f);
    for (int i = 0; i < T.rows(); ++i) {
      for (int k = 0; k < T.cols(); ++k) {
        if (T(i, k) != 0.0) {
          t.push_back(
              {nodes[static_cast<std::size_t>(i)], nodes[static_cast<std::size_t>(k)], T(i, k)});
        }
      }
    }
  }
  std::sort(t.begin(), t.end(), [](const Triplet& a, const Triplet& b) {
    return a.row != b.row ? a.row < b.row : a.col < b.col;
  });
  std::vector<Triplet> unique;
  for (const Triplet& x : t) {
    if (!unique.empty() && unique.back().row == x.row && unique.back().col == x.col) {
      SEAM_CHECK(unique.back().value == x.value, InputError, "slave node ", x.row,
                 " lies on facets with different quadratic basis modifications (mixed "
                 "quad8/quad9 or tri6 facets along one edge); use one quadratic facet type");
      continue;
    }
    unique.push_back(x);
  }
  return unique;
}

} // namespace

std::vector<Triplet> inverse_transformation(std::span<const Triplet> T) {
  std::vector<Triplet> inverse;
  inverse.reserve(T.size());
  for (std::size_t begin = 0; begin < T.size();) {
    std::size_t end = begin;
    while (end < T.size() && T[end].row == T[begin].row) ++end;
    const local_index node = T[begin].row;
    double diagonal = 0.0;
    for (std::size_t e = begin; e < end; ++e)
      if (T[e].col == node) diagonal = T[e].value;
    SEAM_ASSERT(diagonal != 0.0);
    for (std::size_t e = begin; e < end; ++e) {
      inverse.push_back(
          {node, T[e].col, T[e].col == node ? 1.0 / diagonal : -T[e].value / diagonal});
    }
    begin = end;
  }
  return inverse;
}

void compress(std::vector<Triplet>& triplets, local_index n_rows) {
  // Rows are node indices, dense in [0, n_rows): a counting sort by row is O(n), and each row
  // holds only a few dozen entries, which an insertion sort orders by column in cache. One
  // global comparison sort of all triplets was a third of the whole interface assembly.
  const auto rows = static_cast<std::size_t>(n_rows);
  std::vector<std::size_t> start(rows + 1, 0);
  for (const Triplet& t : triplets) {
    SEAM_ASSERT(t.row >= 0 && t.row < n_rows);
    ++start[static_cast<std::size_t>(t.row) + 1];
  }
  for (std::size_t r = 0; r < rows; ++r) start[r + 1] += start[r];
  std::vector<Triplet> bucketed(triplets.size());
  {
    std::vector<std::size_t> next(start.begin(), start.end() - 1);
    for (const Triplet& t : triplets) bucketed[next[static_cast<std::size_t>(t.row)]++] = t;
  }
  std::size_t out = 0;
  for (std::size_t r = 0; r < rows; ++r) {
    Triplet* const first = bucketed.data() + start[r];
    Triplet* const last = bucketed.data() + start[r + 1];
    for (Triplet* a = first + 1; a < last; ++a) {
      const Triplet x = *a;
      Triplet* b = a;
      for (; b > first && (b - 1)->col > x.col; --b) *b = *(b - 1);
      *b = x;
    }
    const std::size_t row_begin = out;
    for (Triplet* a = first; a < last; ++a) {
      if (out > row_begin && triplets[out - 1].col == a->col) {
        triplets[out - 1].value += a->value;
      } else {
        triplets[out++] = *a;
      }
    }
  }
  triplets.resize(out);
}

void compress(std::vector<Triplet>& triplets) {
  local_index n_rows = 0;
  for (const Triplet& t : triplets) n_rows = std::max(n_rows, t.row + 1);
  compress(triplets, n_rows);
}

MortarOperators assemble_mortar_operators(const FacetSet& slave, const FacetSet& master,
                                          std::span<const CandidatePair> candidates,
                                          const MortarOptions& options,
                                          std::span<const char> bound_slave_nodes) {
  validate(slave, "slave");
  validate(master, "master");
  SEAM_CHECK(slave.dim == master.dim, InputError, "slave facets are ", slave.dim,
             "D but master facets are ", master.dim, "D");
  for (const CandidatePair& pair : candidates) {
    SEAM_CHECK(pair.slave >= 0 && pair.slave < slave.n_facets() && pair.master >= 0 &&
                   pair.master < master.n_facets(),
               InputError, "candidate pair (", pair.slave, ", ", pair.master,
               ") is out of range: ", slave.n_facets(), " slave and ", master.n_facets(),
               " master facets");
  }
  SEAM_CHECK(bound_slave_nodes.empty() ||
                 bound_slave_nodes.size() == static_cast<std::size_t>(slave.n_nodes()),
             InputError, "bound slave node flags: ", bound_slave_nodes.size(), " values for ",
             slave.n_nodes(), " slave nodes");
  MortarOperators ops;
  ops.dim = slave.dim;
  ops.multiplier = options.multiplier;
  ops.n_candidates = static_cast<local_index>(candidates.size());
  ops.slave_facet_cells.assign(static_cast<std::size_t>(slave.n_facets()), 0);
  ops.nodal_normals = averaged_nodal_normals(slave);
  ops.weighted_gap.assign(static_cast<std::size_t>(slave.n_nodes()), 0.0);
  if (slave.dim == 2) {
    assemble<2>(slave, master, candidates, options, bound_slave_nodes, ops);
  } else {
    assemble<3>(slave, master, candidates, options, bound_slave_nodes, ops);
  }
  compress(ops.D, slave.n_nodes());
  compress(ops.M, slave.n_nodes());
  ops.T = transformation_triplets(slave, options.multiplier);
  ops.bound.assign(bound_slave_nodes.begin(), bound_slave_nodes.end());
  return ops;
}

} // namespace seam::mortar
