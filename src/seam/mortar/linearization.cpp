#include "seam/mortar/linearization.hpp"

#include <algorithm>
#include <cmath>

#include "seam/common/error.hpp"
#include "seam/mortar/linearization_pair.hpp"
#include "seam/mortar/normals.hpp"

namespace seam::mortar {

namespace {

using ad::FacetT;

template <class S, int Dim>
Eigen::Matrix<S, Dim, max_facet_nodes>
seed_columns(const Eigen::Matrix<double, Dim, max_facet_nodes>& x, int n, int first) {
  Eigen::Matrix<S, Dim, max_facet_nodes> r = Eigen::Matrix<S, Dim, max_facet_nodes>::Zero();
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < Dim; ++a) r(a, i) = S::variable(x(a, i), first + Dim * i + a);
  return r;
}

template <class S>
void copy_gradient(const S& x, int n_variables, std::vector<double>& out, std::size_t entry) {
  std::copy_n(x.gradient.begin(), n_variables,
              out.begin() +
                  static_cast<std::ptrdiff_t>(entry * static_cast<std::size_t>(n_variables)));
}

template <int Dim, int N>
void run_pair(const SlaveFacet<Dim>& slave, const Facet<Dim>& master, const PairOptions& options,
              const ad::CoefficientLinearization* coefficients, PairLinearization& out) {
  using S = Dual<N>;
  const int ns = slave.facet.n_nodes;
  const int nm = master.n_nodes;
  const ad::FacetT<S, Dim> sf = ad::seed<S>(slave.facet, 0);
  const ad::FacetT<S, Dim> mf = ad::seed<S>(master, Dim * ns);
  // The slave's dual coefficients with their derivatives come from a dual number over the
  // slave coordinates only (Dim * ns variables), not over all pair variables.
  ad::SlaveFacetT<S, Dim> st;
  st.facet = sf;
  st.normals = seed_columns<S, Dim>(slave.normals, ns, Dim * (ns + nm));
  st.multiplier = slave.basis.multiplier;
  st.modification = basis_modification(sf.type, st.multiplier);
  if (st.multiplier == Multiplier::dual) {
    SEAM_ASSERT(coefficients && coefficients->n == ns);
    st.A.resize(ns, ns);
    for (int j = 0; j < ns; ++j)
      for (int k = 0; k < ns; ++k) {
        S a(coefficients->A(j, k));
        std::copy_n(coefficients->gradient.begin() + (j * ns + k) * coefficients->n_variables,
                    coefficients->n_variables, a.gradient.begin());
        st.A(j, k) = a;
      }
  }
  const ad::PairContributionT<S> c = ad::integrate_pair_t<S>(st, mf, options);

  out.dim = Dim;
  out.n_slave = ns;
  out.n_master = nm;
  out.n_variables = ad::pair_variable_count(Dim, ns, nm);
  PairContribution& v = out.values;
  v = detail::empty_contribution(ns, nm);
  v.n_cells = c.n_cells;
  v.area = c.area;
  v.n_projection_failures = c.n_projection_failures;
  const auto nv = static_cast<std::size_t>(out.n_variables);
  out.D_gradient.resize(static_cast<std::size_t>(ns * ns) * nv);
  out.M_gradient.resize(static_cast<std::size_t>(ns * nm) * nv);
  out.gap_gradient.resize(static_cast<std::size_t>(ns) * nv);
  for (int j = 0; j < ns; ++j) {
    for (int k = 0; k < ns; ++k) {
      v.D(j, k) = c.D(j, k).value;
      copy_gradient(c.D(j, k), out.n_variables, out.D_gradient,
                    static_cast<std::size_t>(j * ns + k));
    }
    for (int l = 0; l < nm; ++l) {
      v.M(j, l) = c.M(j, l).value;
      copy_gradient(c.M(j, l), out.n_variables, out.M_gradient,
                    static_cast<std::size_t>(j * nm + l));
    }
    v.weighted_gap(j) = c.weighted_gap(j).value;
    copy_gradient(c.weighted_gap(j), out.n_variables, out.gap_gradient,
                  static_cast<std::size_t>(j));
  }
}

template <int K, int Dim>
void coefficients_with(const Facet<Dim>& facet, double modification,
                       ad::CoefficientLinearization& out) {
  using S = Dual<K>;
  const int n = facet.n_nodes;
  SEAM_ASSERT(Dim * n <= K);
  const ad::SmallMatrixT<S> A = ad::dual_coefficients_t(ad::seed<S, Dim>(facet, 0), modification);
  out.n = n;
  out.n_variables = Dim * n;
  out.A.resize(n, n);
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < n; ++k) {
      out.A(j, k) = A(j, k).value;
      std::copy_n(A(j, k).gradient.begin(), out.n_variables,
                  out.gradient.begin() + (j * n + k) * out.n_variables);
    }
}

template <int Dim> void validate_pair(const SlaveFacet<Dim>& slave, const Facet<Dim>& master) {
  SEAM_CHECK(is_interface_facet(slave.facet.type, Dim) && is_interface_facet(master.type, Dim) &&
                 slave.facet.n_nodes == fem::n_nodes(slave.facet.type) &&
                 master.n_nodes == fem::n_nodes(master.type),
             InputError, "linearize_pair: the facets are not ", Dim,
             "D interface facets with their full node count");
}

void linearize_pair_2d(const SlaveFacet<2>& slave, const Facet<2>& master,
                       const PairOptions& options, const ad::CoefficientLinearization* coefficients,
                       PairLinearization& out) {
  if (ad::pair_variable_count(2, slave.facet.n_nodes, master.n_nodes) <= 12) {
    run_pair<2, 12>(slave, master, options, coefficients, out);
  } else {
    run_pair<2, 18>(slave, master, options, coefficients, out);
  }
}

} // namespace

void linearize_pair(const SlaveFacet<2>& slave, const Facet<2>& master, const PairOptions& options,
                    PairLinearization& out) {
  validate_pair(slave, master);
  static thread_local ad::CoefficientLinearization coefficients;
  const bool dual = slave.basis.multiplier == Multiplier::dual;
  if (dual)
    ad::linearize_coefficients<2>(
        slave.facet, basis_modification(slave.facet.type, slave.basis.multiplier), coefficients);
  linearize_pair_2d(slave, master, options, dual ? &coefficients : nullptr, out);
}

void linearize_pair(const SlaveFacet<3>& slave, const Facet<3>& master, const PairOptions& options,
                    PairLinearization& out) {
  validate_pair(slave, master);
  static thread_local ad::CoefficientLinearization coefficients;
  const bool dual = slave.basis.multiplier == Multiplier::dual;
  if (dual)
    ad::linearize_coefficients<3>(
        slave.facet, basis_modification(slave.facet.type, slave.basis.multiplier), coefficients);
  ad::linearize_pair_3d(slave, master, options, dual ? &coefficients : nullptr, out);
}

namespace ad {

template <int Dim>
void linearize_coefficients(const Facet<Dim>& facet, double modification,
                            CoefficientLinearization& out) {
  with_facet_width(Dim * facet.n_nodes,
                   [&]<int K>() { coefficients_with<K>(facet, modification, out); });
}
template void linearize_coefficients(const Facet<2>&, double, CoefficientLinearization&);
template void linearize_coefficients(const Facet<3>&, double, CoefficientLinearization&);

} // namespace ad

NodeFacets node_facets(const FacetSet& facets) {
  validate(facets, "slave");
  NodeFacets r;
  const auto n = static_cast<std::size_t>(facets.n_nodes());
  r.offsets.assign(n + 1, 0);
  for (const local_index node : facets.nodes) ++r.offsets[static_cast<std::size_t>(node) + 1];
  for (std::size_t i = 0; i < n; ++i) r.offsets[i + 1] += r.offsets[i];
  r.facets.resize(facets.nodes.size());
  std::vector<local_index> fill(r.offsets.begin(), r.offsets.end() - 1);
  for (local_index f = 0; f < facets.n_facets(); ++f) {
    for (const local_index node : facets.facet_nodes(f))
      r.facets[static_cast<std::size_t>(fill[static_cast<std::size_t>(node)]++)] = f;
  }
  return r;
}

namespace {

// One facet's unit normal at the node `node` with derivatives with respect to the facet's
// nodal coordinates (Dim * n_nodes <= K variables).
template <int Dim, int K>
void add_facet_normal_with(const Facet<Dim>& facet, std::span<const local_index> nodes,
                           local_index node, NodalNormalLinearization& out,
                           std::array<double, 3>& sum) {
  using S = Dual<K>;
  const auto it = std::find(nodes.begin(), nodes.end(), node);
  SEAM_ASSERT(it != nodes.end());
  const int i = static_cast<int>(it - nodes.begin());
  const ad::FacetT<S, Dim> fs = ad::seed<S>(facet, 0);
  const ad::Vector<S, Dim> u = ad::unit_normal_at_node(fs, i);
  const auto n = static_cast<std::size_t>(out.nodes.size());
  for (int k = 0; k < facet.n_nodes; ++k) {
    const auto position = static_cast<std::size_t>(
        std::lower_bound(out.nodes.begin(), out.nodes.end(), nodes[static_cast<std::size_t>(k)]) -
        out.nodes.begin());
    for (int a = 0; a < Dim; ++a) {
      for (int b = 0; b < Dim; ++b) {
        out.jacobian[static_cast<std::size_t>(a) * Dim * n + Dim * position +
                     static_cast<std::size_t>(b)] +=
            u(a).gradient[static_cast<std::size_t>(Dim * k + b)];
      }
    }
  }
  for (int a = 0; a < Dim; ++a) sum[static_cast<std::size_t>(a)] += u(a).value;
}

template <int Dim>
void add_facet_normal(const FacetSet& facets, local_index f, local_index node,
                      NodalNormalLinearization& out, std::array<double, 3>& sum) {
  const Facet<Dim> facet = gather_facet<Dim>(facets, f);
  const auto nodes = facets.facet_nodes(f);
  ad::with_facet_width(Dim * facet.n_nodes, [&]<int K>() {
    add_facet_normal_with<Dim, K>(facet, nodes, node, out, sum);
  });
}

} // namespace

void linearize_nodal_normal(const FacetSet& facets, local_index node,
                            std::span<const local_index> adjacent, NodalNormalLinearization& out) {
  const int dim = facets.dim;
  out.dim = dim;
  out.nodes.clear();
  for (const local_index f : adjacent) {
    for (const local_index k : facets.facet_nodes(f)) out.nodes.push_back(k);
  }
  std::sort(out.nodes.begin(), out.nodes.end());
  out.nodes.erase(std::unique(out.nodes.begin(), out.nodes.end()), out.nodes.end());
  const std::size_t width = static_cast<std::size_t>(dim) * out.nodes.size();
  out.jacobian.assign(static_cast<std::size_t>(dim) * width, 0.0);
  std::array<double, 3> sum{};
  for (const local_index f : adjacent) {
    if (dim == 2) {
      add_facet_normal<2>(facets, f, node, out, sum);
    } else {
      add_facet_normal<3>(facets, f, node, out, sum);
    }
  }
  double length = 0.0;
  for (int a = 0; a < dim; ++a)
    length += sum[static_cast<std::size_t>(a)] * sum[static_cast<std::size_t>(a)];
  length = std::sqrt(length);
  SEAM_CHECK(length > min_normal_sum, InputError, "slave node ", node,
             ": the normals of its facets cancel (the surface folds back onto itself)");
  for (int a = 0; a < dim; ++a)
    out.normal[static_cast<std::size_t>(a)] = sum[static_cast<std::size_t>(a)] / length;
  // dn = (I - n n^T) ds / |s| (the derivative of the normalization).
  for (std::size_t v = 0; v < width; ++v) {
    double n_dot_ds = 0.0;
    for (int a = 0; a < dim; ++a)
      n_dot_ds += out.normal[static_cast<std::size_t>(a)] *
                  out.jacobian[static_cast<std::size_t>(a) * width + v];
    for (int a = 0; a < dim; ++a) {
      double& entry = out.jacobian[static_cast<std::size_t>(a) * width + v];
      entry = (entry - out.normal[static_cast<std::size_t>(a)] * n_dot_ds) / length;
    }
  }
}

namespace {

template <int Dim>
void linearize_slave_facet_impl(const FacetSet& slave, const FacetSet& master,
                                const NodeFacets& adjacency, local_index slave_facet,
                                std::span<const local_index> master_facets,
                                const MortarOptions& options, SlaveFacetLinearization& out) {
  const auto facet_nodes = slave.facet_nodes(slave_facet);
  const int ns = static_cast<int>(facet_nodes.size());
  out.dim = Dim;
  out.n_slave = ns;
  out.multiplier = options.multiplier;
  out.n_pairs_integrated = 0;
  out.n_cells = 0;
  out.n_projection_failures = 0;
  out.area = 0.0;

  // Slave variables: the facet's nodes, then the rest of their normal patches.
  out.slave_nodes.assign(facet_nodes.begin(), facet_nodes.end());
  out.normals.resize(static_cast<std::size_t>(ns));
  for (int k = 0; k < ns; ++k) {
    const local_index node = facet_nodes[static_cast<std::size_t>(k)];
    NodalNormalLinearization& nl = out.normals[static_cast<std::size_t>(k)];
    linearize_nodal_normal(slave, node, adjacency.of(node), nl);
    for (const local_index other : nl.nodes) {
      if (std::find(facet_nodes.begin(), facet_nodes.end(), other) == facet_nodes.end())
        out.slave_nodes.push_back(other);
    }
  }
  std::sort(out.slave_nodes.begin() + ns, out.slave_nodes.end());
  out.slave_nodes.erase(std::unique(out.slave_nodes.begin() + ns, out.slave_nodes.end()),
                        out.slave_nodes.end());
  out.master_nodes.clear();
  for (const local_index f : master_facets) {
    for (const local_index node : master.facet_nodes(f)) {
      if (std::find(out.master_nodes.begin(), out.master_nodes.end(), node) ==
          out.master_nodes.end())
        out.master_nodes.push_back(node);
    }
  }
  const int n_us = static_cast<int>(out.slave_nodes.size());
  const int n_mn = out.n_master_nodes();
  const auto nv = static_cast<std::size_t>(out.n_variables());
  const auto slave_position = [&out](local_index node) {
    return static_cast<int>(std::find(out.slave_nodes.begin(), out.slave_nodes.end(), node) -
                            out.slave_nodes.begin());
  };

  // dn_k / d(slave variables), dense rows.
  out.normal_jacobian.assign(static_cast<std::size_t>(ns * Dim) * nv, 0.0);
  SlaveFacet<Dim> sf;
  sf.facet = gather_facet<Dim>(slave, slave_facet);
  sf.basis.multiplier = options.multiplier;
  for (int k = 0; k < ns; ++k) {
    const NodalNormalLinearization& nl = out.normals[static_cast<std::size_t>(k)];
    const std::size_t width = static_cast<std::size_t>(Dim) * nl.nodes.size();
    for (int a = 0; a < Dim; ++a) sf.normals(a, k) = nl.normal[static_cast<std::size_t>(a)];
    for (std::size_t i = 0; i < nl.nodes.size(); ++i) {
      const int u = slave_position(nl.nodes[i]);
      for (int a = 0; a < Dim; ++a) {
        for (int b = 0; b < Dim; ++b) {
          out.normal_jacobian[static_cast<std::size_t>(k * Dim + a) * nv +
                              static_cast<std::size_t>(Dim * u + b)] =
              nl.jacobian[static_cast<std::size_t>(a) * width + Dim * i +
                          static_cast<std::size_t>(b)];
        }
      }
    }
  }

  out.D.assign(static_cast<std::size_t>(ns * ns), 0.0);
  out.M.assign(static_cast<std::size_t>(ns * n_mn), 0.0);
  out.weighted_gap.assign(static_cast<std::size_t>(ns), 0.0);
  out.D_gradient.assign(static_cast<std::size_t>(ns * ns) * nv, 0.0);
  out.M_gradient.assign(static_cast<std::size_t>(ns * n_mn) * nv, 0.0);
  out.gap_gradient.assign(static_cast<std::size_t>(ns) * nv, 0.0);

  // The slave's dual coefficients and their derivatives serve all its master candidates.
  static thread_local ad::CoefficientLinearization coefficients;
  const bool dual = options.multiplier == Multiplier::dual;
  if (dual)
    ad::linearize_coefficients<Dim>(sf.facet, basis_modification(sf.facet.type, options.multiplier),
                                    coefficients);
  for (const local_index f : master_facets) {
    const Facet<Dim> mf = gather_facet<Dim>(master, f);
    const auto m_nodes = master.facet_nodes(f);
    validate_pair(sf, mf);
    if constexpr (Dim == 3) {
      ad::linearize_pair_3d(sf, mf, options.pair, dual ? &coefficients : nullptr, out.pair);
    } else {
      linearize_pair_2d(sf, mf, options.pair_options(slave_facet, f),
                        dual ? &coefficients : nullptr, out.pair);
    }
    const PairLinearization& p = out.pair;
    out.n_projection_failures += p.values.n_projection_failures;
    if (p.values.n_cells == 0) continue;
    ++out.n_pairs_integrated;
    out.n_cells += p.values.n_cells;
    out.area += p.values.area;
    const int nm = p.n_master;
    out.master_position.resize(static_cast<std::size_t>(nm));
    for (int l = 0; l < nm; ++l) {
      out.master_position[static_cast<std::size_t>(l)] =
          static_cast<int>(std::find(out.master_nodes.begin(), out.master_nodes.end(),
                                     m_nodes[static_cast<std::size_t>(l)]) -
                           out.master_nodes.begin());
    }
    // Chain one pair gradient into a slave-facet gradient row.
    const auto scatter = [&](std::span<const double> g, double* row) {
      for (int k = 0; k < ns; ++k)
        for (int a = 0; a < Dim; ++a) row[Dim * k + a] += g[static_cast<std::size_t>(Dim * k + a)];
      for (int l = 0; l < nm; ++l) {
        const int column = Dim * (n_us + out.master_position[static_cast<std::size_t>(l)]);
        for (int a = 0; a < Dim; ++a)
          row[column + a] += g[static_cast<std::size_t>(Dim * (ns + l) + a)];
      }
      for (int k = 0; k < ns; ++k) {
        for (int a = 0; a < Dim; ++a) {
          const double dn = g[static_cast<std::size_t>(Dim * (ns + nm + k) + a)];
          if (dn == 0.0) continue;
          const double* jac =
              out.normal_jacobian.data() + static_cast<std::size_t>(k * Dim + a) * nv;
          for (int v = 0; v < Dim * n_us; ++v) row[v] += dn * jac[v];
        }
      }
    };
    for (int j = 0; j < ns; ++j) {
      for (int k = 0; k < ns; ++k) {
        out.D[static_cast<std::size_t>(j * ns + k)] += p.values.D(j, k);
        scatter(p.dD(j, k), out.D_gradient.data() + static_cast<std::size_t>(j * ns + k) * nv);
      }
      for (int l = 0; l < nm; ++l) {
        const int column = out.master_position[static_cast<std::size_t>(l)];
        out.M[static_cast<std::size_t>(j * n_mn + column)] += p.values.M(j, l);
        scatter(p.dM(j, l),
                out.M_gradient.data() + static_cast<std::size_t>(j * n_mn + column) * nv);
      }
      out.weighted_gap[static_cast<std::size_t>(j)] += p.values.weighted_gap(j);
      scatter(p.dgap(j), out.gap_gradient.data() + static_cast<std::size_t>(j) * nv);
    }
  }
}

} // namespace

void linearize_slave_facet(const FacetSet& slave, const FacetSet& master,
                           const NodeFacets& slave_facets_of_node, local_index slave_facet,
                           std::span<const local_index> master_facets, const MortarOptions& options,
                           SlaveFacetLinearization& out) {
  SEAM_CHECK(slave.dim == master.dim, InputError, "slave facets are ", slave.dim,
             "D but master facets are ", master.dim, "D");
  SEAM_CHECK(slave_facet >= 0 && slave_facet < slave.n_facets(), InputError, "slave facet ",
             slave_facet, " is out of range (", slave.n_facets(), " facets)");
  SEAM_CHECK(slave_facets_of_node.offsets.size() == static_cast<std::size_t>(slave.n_nodes()) + 1,
             InputError, "the node-to-facet adjacency does not match the slave facets");
  for (const local_index f : master_facets) {
    SEAM_CHECK(f >= 0 && f < master.n_facets(), InputError, "master facet ", f,
               " is out of range (", master.n_facets(), " facets)");
  }
  if (slave.dim == 2) {
    linearize_slave_facet_impl<2>(slave, master, slave_facets_of_node, slave_facet, master_facets,
                                  options, out);
  } else {
    linearize_slave_facet_impl<3>(slave, master, slave_facets_of_node, slave_facet, master_facets,
                                  options, out);
  }
}

} // namespace seam::mortar
