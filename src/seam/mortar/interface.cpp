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
              MortarOperators& ops) {
  // Visit the candidates grouped by slave facet so that each slave facet's normals and dual
  // coefficients are computed once.
  std::vector<std::size_t> order(candidates.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return candidates[a].slave < candidates[b].slave;
  });
  SlaveFacet<Dim> sf;
  local_index current = -1;
  for (const std::size_t index : order) {
    const CandidatePair pair = candidates[index];
    if (pair.slave != current) {
      current = pair.slave;
      sf = prepare_slave<Dim>(slave, current, ops.nodal_normals, options.multiplier);
    }
    const Facet<Dim> mf = gather_facet<Dim>(master, pair.master);
    const PairContribution c = integrate_pair(sf, mf, options.pair);
    ops.n_projection_failures += c.n_projection_failures;
    if (c.n_cells == 0) continue;
    ++ops.n_pairs_integrated;
    ops.n_integration_cells += c.n_cells;
    ops.integrated_area += c.area;
    const auto s_nodes = slave.facet_nodes(pair.slave);
    const auto m_nodes = master.facet_nodes(pair.master);
    for (int j = 0; j < c.n_slave; ++j) {
      const local_index row = s_nodes[static_cast<std::size_t>(j)];
      for (int k = 0; k < c.n_slave; ++k) {
        // Dual: only the diagonal is accumulated; skip the structural zeros.
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

void compress(std::vector<Triplet>& triplets) {
  std::sort(triplets.begin(), triplets.end(), [](const Triplet& a, const Triplet& b) {
    return a.row != b.row ? a.row < b.row : a.col < b.col;
  });
  std::size_t out = 0;
  for (std::size_t i = 0; i < triplets.size(); ++i) {
    if (out > 0 && triplets[out - 1].row == triplets[i].row &&
        triplets[out - 1].col == triplets[i].col) {
      triplets[out - 1].value += triplets[i].value;
    } else {
      triplets[out++] = triplets[i];
    }
  }
  triplets.resize(out);
}

MortarOperators assemble_mortar_operators(const FacetSet& slave, const FacetSet& master,
                                          std::span<const CandidatePair> candidates,
                                          const MortarOptions& options) {
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
  MortarOperators ops;
  ops.dim = slave.dim;
  ops.multiplier = options.multiplier;
  ops.n_candidates = static_cast<local_index>(candidates.size());
  ops.nodal_normals = averaged_nodal_normals(slave);
  ops.weighted_gap.assign(static_cast<std::size_t>(slave.n_nodes()), 0.0);
  if (slave.dim == 2) {
    assemble<2>(slave, master, candidates, options, ops);
  } else {
    assemble<3>(slave, master, candidates, options, ops);
  }
  compress(ops.D);
  compress(ops.M);
  ops.T = transformation_triplets(slave, options.multiplier);
  return ops;
}

} // namespace seam::mortar
