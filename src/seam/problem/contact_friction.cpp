// Frictional contact in the condensed semi-smooth Newton method (contact_constraint.hpp,
// contact/friction.hpp).
#include "seam/problem/contact_constraint.hpp"

#include "seam/common/error.hpp"
#include "seam/parallel/exchange.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

namespace seam::problem {

namespace {

/// A node whose prescribed components leave less than this share of its normal free cannot
/// move towards the other side (as in contact_constraint.cpp).
constexpr double min_free_normal = 0.1;

/// Hysteresis band of the stick/slip decision for nodes frozen by the cycling guard, relative
/// to the node's slip bound (evaluate_friction).
constexpr double cone_band = 1e-3;

} // namespace

std::vector<double> ContactConstraint::rigid_motion_weighted(const Side& s) const {
  const int dim = disc_.dim();
  const auto obstacle = s.itf.plane_displacement();
  std::vector<double> d(s.x.size()), w(s.x.size(), 0.0);
  for (std::size_t i = 0; i < d.size(); ++i)
    d[i] = s.x[i] - s.x_old[i] - (obstacle[i % dim] - s.plane_old[i % dim]);
  if (s.itf.standard()) {
    // This rank's coupling entries D_jk, k != j, summed on the owners of the nodes j (the
    // only values read: dissipation_increment).
    for (const auto& e : s.part.D_coupling)
      for (int c = 0; c < dim; ++c)
        w[static_cast<std::size_t>(e.row) * dim + c] +=
            e.value * d[static_cast<std::size_t>(e.col) * dim + c];
    parallel::sum_on_owners(disc_.comm().get(), s.node_keys, s.node_owners, w, dim);
  }
  for (std::size_t i = 0; i < d.size(); ++i) w[i] += s.D_diag[i / dim] * d[i];
  return w;
}

void ContactConstraint::init_friction(Side& s, const io::Interface& config, double c_n) {
  const int dim = disc_.dim();
  s.friction = true;
  s.law.model = config.friction.model;
  s.law.mu = config.friction.coefficient;
  s.law.bound = config.friction.bound;
  s.law.c_n = c_n;
  // c_t of the size of c_n keeps both parts of z = lambda_t + c_t s of one scale; converged
  // results do not depend on it.
  s.law.c_t = config.c_t ? *config.c_t : c_n;
  s.law.touching = 1e-9 * s.itf.slave_mesh_size();
  const auto n = static_cast<std::size_t>(s.itf.n_slave_nodes());
  s.lambda.assign(n * dim, 0.0);
  s.lambda_saved = s.lambda;
  s.status.assign(n, 0);
  s.status_previous = s.status;
  s.status_accepted = s.status;
  s.frozen_nodes = s.status;
  s.slip.assign(n * dim, 0.0);
  s.D_diag_old.assign(n, 0.0);
  const auto& nodes = s.itf.slave().mesh_nodes;
  s.x.resize(n * dim);
  for (std::size_t j = 0; j < n; ++j)
    for (int c = 0; c < dim; ++c) s.x[j * dim + c] = reference(nodes[j], c);
  s.x_old = s.x;
  contact::apply_inverse_transformation(s.T_inverse, dim, s.x, s.x_old);
  s.x = s.x_old;
}

contact::FrictionNode ContactConstraint::friction_node(const Side& s, std::size_t j) const {
  const int dim = disc_.dim();
  contact::FrictionNode node;
  node.dim = dim;
  for (int c = 0; c < dim; ++c) {
    node.lambda[c] = s.lambda[j * dim + c];
    node.normal[c] = s.itf.normals()[j * dim + c];
    node.slip[c] = s.slip[j * dim + c];
  }
  node.D = s.D[j];
  node.weighted_gap = s.gap[j];
  return node;
}

int ContactConstraint::evaluate_friction(Side& s, std::span<const double> u_mesh, bool first) {
  const int dim = disc_.dim();
  const auto& comm = disc_.comm();
  const auto& nodes = s.itf.slave().mesh_nodes;
  const auto n = nodes.size();
  std::vector<double> x(n * dim);
  for (std::size_t j = 0; j < n; ++j)
    for (int c = 0; c < dim; ++c)
      x[j * dim + c] =
          reference(nodes[j], c) + u_mesh[static_cast<std::size_t>(nodes[j]) * dim + c];
  // With a modified slave basis (tri6/quad8, d = T d~) D multiplies x~ = T^-1 x: the slip
  // increment below is objective only in these positions (sum_k D_jk x~_k = int Phi_j x dA).
  contact::apply_inverse_transformation(s.T_inverse, dim, x, s.x);
  // The weighted slip increment of the step (Gitterle et al. 2010, eq. 31, with the sign of
  // the slave's motion relative to the master):
  //   u~_j = sum_l (M_jl - M_jl^n) x_l - (D_jj - D_jj^n) x~_j;
  // against a translating rigid plane it reduces to D_jj P (x~_j - x~_j^n - (c - c^n)).
  // The increments are formed on the owners of the slave nodes, which hold the sums of D.
  const bool init = !s.has_old;
  std::fill(s.slip.begin(), s.slip.end(), 0.0);
  if (s.discrete_gradient) {
    // Energy-momentum contact: the frame-indifferent increment over the mean of the operators of
    // x_n and x_{n+1}, whose product with lambda_t is the work of the tangential force
    // (contact_energy_momentum_friction.cpp).
    energy_momentum_slip(s, u_mesh);
  } else if (s.itf.rigid()) {
    const auto plane = s.itf.plane_displacement();
    const double* normals = s.itf.normals().data();
    for (std::size_t j = 0; j < n; ++j) {
      if (s.node_owners[j] != comm.rank()) continue;
      double d[3] = {0, 0, 0}, dn = 0.0;
      for (int c = 0; c < dim; ++c) {
        d[c] = s.x[j * dim + c] - s.x_old[j * dim + c] - (plane[c] - s.plane_old[c]);
        dn += d[c] * normals[j * dim + c];
      }
      for (int c = 0; c < dim; ++c)
        s.slip[j * dim + c] = s.D[j] * (d[c] - dn * normals[j * dim + c]);
    }
  } else {
    // The operators "of the last converged step" before the first one has converged: those of
    // the start configuration (the first evaluation happens there). With D^n = M^n = 0 the
    // increment would be the gap vector, which has no tangential part.
    if (!s.has_old) {
      s.D_diag_old = s.D_diag;
      s.D_coupling_old = s.part.D_coupling;
      s.M_old = s.part.M;
      s.has_old = true;
    }
    // Current position of a master node (u_mesh holds the interface nodes).
    const auto x_of = [&](std::int32_t node, int c) {
      return reference(node, c) + u_mesh[static_cast<std::size_t>(node) * dim + c];
    };
    for (const auto& e : s.part.M)
      for (int c = 0; c < dim; ++c)
        s.slip[static_cast<std::size_t>(e.slave) * dim + c] += e.value * x_of(e.master_node, c);
    for (const auto& e : s.M_old)
      for (int c = 0; c < dim; ++c)
        s.slip[static_cast<std::size_t>(e.slave) * dim + c] -= e.value * x_of(e.master_node, c);
    // Standard multipliers: the off-diagonal part -sum_{k != j} (D_jk - D_jk^n) x~_k.
    for (const auto& e : s.part.D_coupling)
      for (int c = 0; c < dim; ++c)
        s.slip[static_cast<std::size_t>(e.row) * dim + c] -=
            e.value * s.x[static_cast<std::size_t>(e.col) * dim + c];
    for (const auto& e : s.D_coupling_old)
      for (int c = 0; c < dim; ++c)
        s.slip[static_cast<std::size_t>(e.row) * dim + c] +=
            e.value * s.x[static_cast<std::size_t>(e.col) * dim + c];
    parallel::sum_on_owners(comm.get(), s.node_keys, s.node_owners, s.slip, dim);
    for (std::size_t j = 0; j < n; ++j)
      if (s.node_owners[j] == comm.rank())
        for (int c = 0; c < dim; ++c)
          s.slip[j * dim + c] -= (s.D_diag[j] - s.D_diag_old[j]) * s.x[j * dim + c];
  }

  if (first) {
    s.frozen_nodes.assign(n, 0);
    s.cycles.start(s.status);
  }
  s.status_previous = s.status;
  const double d_max = max_weight(s);
  const double touching = 1e-9 * s.itf.slave_mesh_size();
  // Tolerance of the stick/slip conditions, in traction units.
  double scale = 0.0;
  for (const double l : s.lambda) scale = std::max(scale, std::abs(l));
  if (s.slave_in_part) scale = comm.max(scale); // every part the whole side's
  const double tolerance = 1e-8 * scale;
  std::vector<char> next(n, 0);
  // The status each owned node's condition asks for at this iterate, decided by its owner.
  for (std::size_t j = 0; j < n; ++j) {
    if (s.node_owners[j] != comm.rank()) continue;
    if (!paired(s, j, d_max)) continue;
    if (frame(s, j).wn < min_free_normal) continue;
    const auto node = friction_node(s, j);
    double lambda_n = 0.0;
    for (int c = 0; c < dim; ++c) lambda_n += node.lambda[c] * node.normal[c];
    if (lambda_n - s.c_n * (s.gap[j] / s.D[j] - touching) <= 0.0) continue;
    next[j] = static_cast<char>(contact::stick_or_slip(s.law, node));
    // A node on its cone satisfies both conditions: it keeps the status it has. A node that
    // slid in the last step starts the next one with a zero slip increment, |z| = |lambda_t| =
    // xi; deciding it by the strict test sent it to stick in the first iteration and back to
    // slip in the second, which the cycling guard took for a cycle and froze for the rest of the
    // step, so that a node whose slip then came to rest could no longer stick.
    if (next[j] != s.status[j] && s.status[j] != 0 &&
        contact::admissible(s.law, node, static_cast<contact::NodeStatus>(s.status[j]), tolerance))
      next[j] = s.status[j];
  }
  // Every rank gets the owners' sums, slip increments and decisions.
  publish_nodal_values(s, next);
  publish(s, s.slip, dim);
  // The checks below run on every rank over the contact zone (the cycling guard's consistency,
  // the complementarity residual, the friction rows): the owners' normals of the nodes with
  // nonzero sums, a rank computing those of the slave nodes it reads only.
  {
    std::vector<double> normals(n * dim, 0.0);
    const auto& mine = s.itf.normals();
    for (std::size_t j = 0; j < n; ++j)
      if (s.node_owners[j] == comm.rank() && s.D[j] != 0.0)
        for (int c = 0; c < dim; ++c) normals[j * dim + c] = mine[j * dim + c];
    publish(s, normals, dim);
    s.itf.set_normals_from_owners(normals);
  }
  if (init && s.has_old) s.D_diag_old = s.D_diag;
  // Cycling guard (contact/active_set_cycles.hpp): when the statuses return to those of k <= 12
  // iterations ago, the nodes that alternate keep the largest of their statuses in the cycle
  // (inactive < stick < slip) for the rest of the step; the others go on being decided. A frozen
  // node whose condition asks for another status counts as a change, so that an inconsistent state
  // (say, a stuck node whose traction has left the cone) is never accepted: the step is cut
  // instead.
  // A node without a pair at this iterate (paired()) is released from a frozen or held status
  // (no gap row: the saddle point would be singular; see evaluate()).
  const auto decided = [&](const std::vector<char>& wanted) {
    std::vector<char> out = wanted;
    for (std::size_t j = 0; j < n; ++j)
      if ((held_ || s.frozen_nodes[j]) && paired(s, j, d_max)) out[j] = s.status_previous[j];
    return out;
  };
  // The counts are the same on every rank: on a slave side held in part each rank counts the
  // nodes it owns and the counts are summed (every node is held by its owner).
  const auto counted = [&](std::size_t j) {
    return !s.slave_in_part || s.node_owners[j] == comm.rank();
  };
  const auto agreed = [&](int count) {
    return s.slave_in_part ? static_cast<int>(comm.sum(static_cast<double>(count))) : count;
  };
  std::vector<char> status = decided(next);
  int released = 0;
  for (std::size_t j = 0; j < n; ++j)
    released += counted(j) && (held_ || s.frozen_nodes[j]) && s.status_previous[j] != 0 &&
                !paired(s, j, d_max);
  if (!held_) {
    std::vector<char> alternating;
    // On a slave side held in part the sets are equal where they are equal on every rank.
    const auto all_ranks = [&](bool equal) { return comm.min(equal ? 1.0 : 0.0) > 0.0; };
    if (s.cycles.guard(status, alternating,
                       s.slave_in_part ? contact::ActiveSetCycles::Agree(all_ranks)
                                       : contact::ActiveSetCycles::Agree()) > 0)
      for (std::size_t j = 0; j < n; ++j) {
        if (alternating[j]) s.frozen_nodes[j] = 1;
        // The largest status of the cycle, unless the node has no pair at this iterate.
        if (status[j] != 0 && !paired(s, j, d_max)) {
          status[j] = 0;
          released += counted(j);
        }
      }
  }
  released_ += agreed(released);
  s.status = std::move(status);
  // A frozen node is consistent if its stick/slip condition holds up to a small tolerance (a
  // node on the cone may be either). Its normal status is kept as the frictionless guard keeps
  // it: a node that alternates between penetrating and pulling stays active, in slip (its
  // bound is zero then; in stick it could hold a traction outside the cone).
  //
  // A node frozen between stick and slip may find neither consistent: at a free edge of the
  // slave surface inside the contact zone (the lateral edges of the 3D ironing slab under a
  // wider die) the slip solution there can come out with a slip against its traction and the
  // stick solution with a traction just outside the cone, the nodal problem having no
  // solution for that set of its neighbours. Such a node lies on the cone to within a
  // hysteresis band (as FrontISTR's against stick/slip chattering): it is accepted when its
  // condition is violated by less than cone_band of its bound, |z| against xi, in traction
  // units (for slip, c_t times the slip against the traction), and counted so that the step
  // reports it.
  s.on_cone = 0;
  const auto consistent = [&](std::size_t j) {
    if (s.status[j] == next[j]) return true;
    const auto node = friction_node(s, j);
    const auto status = static_cast<contact::NodeStatus>(s.status[j]);
    if (contact::admissible(s.law, node, status, tolerance)) return true;
    if (s.status[j] == 0 || next[j] == 0) return false; // normal cycling: no band
    if (!contact::admissible(s.law, node, status, cone_band * contact::slip_bound(s.law, node)))
      return false;
    ++s.on_cone;
    return true;
  };
  int changes = 0;
  s.inconsistent = 0;
  for (std::size_t j = 0; j < n; ++j) {
    s.active[j] = s.status[j] != 0;
    if (!counted(j)) continue;
    changes += s.status[j] != s.status_previous[j];
    const bool inconsistent =
        s.frozen_nodes[j] && s.status[j] == s.status_previous[j] && !consistent(j);
    changes += inconsistent;
    s.inconsistent += inconsistent;
  }
  if (s.slave_in_part) {
    double counts[3] = {static_cast<double>(changes), static_cast<double>(s.inconsistent),
                        static_cast<double>(s.on_cone)};
    comm.sum_in_place(counts);
    changes = static_cast<int>(counts[0]);
    s.inconsistent = static_cast<int>(counts[1]);
    s.on_cone = static_cast<int>(counts[2]);
  }
  // Complementarity residual: c_n g~ and D_jj t_i . C_t on active nodes, D_jj |lambda_j| on the
  // others; summed over the owners of the nodes (each has the normals of its own nodes).
  s.ncp_norm2 = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    if (s.node_owners[j] != comm.rank()) continue;
    if (!s.active[j]) {
      for (int c = 0; c < dim; ++c) s.ncp_norm2 += std::pow(s.D[j] * s.lambda[j * dim + c], 2);
      continue;
    }
    s.ncp_norm2 += std::pow(s.c_n * s.gap[j], 2);
    const NodeFrame f = frame(s, j);
    const auto node = friction_node(s, j);
    const auto status = static_cast<contact::NodeStatus>(s.status[j]);
    for (int i = 0; i < f.n_tangents; ++i) {
      const std::array<double, 3> t{f.tangent[i][0], f.tangent[i][1], f.tangent[i][2]};
      s.ncp_norm2 += std::pow(s.D[j] * contact::friction_row(s.law, node, status, t).value, 2);
    }
  }
  s.ncp_norm2 = comm.sum(s.ncp_norm2);
  return changes;
}

ContactConstraint::FrictionRows ContactConstraint::friction_rows(const Side& s) const {
  // The rows of every active node (replicated data, so that each rank can weight its own
  // parts of the gradients).
  const auto n = s.itf.slave().mesh_nodes.size();
  FrictionRows out;
  out.frames.resize(n);
  out.rows.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    if (!s.active[j]) continue;
    out.frames[j] = frame(s, j);
    const auto node = friction_node(s, j);
    const auto status = static_cast<contact::NodeStatus>(s.status[j]);
    for (int i = 0; i < out.frames[j].n_tangents; ++i) {
      const auto& ti = out.frames[j].tangent[i];
      out.rows[j][static_cast<std::size_t>(i)] =
          contact::friction_row(s.law, node, status, {ti[0], ti[1], ti[2]});
    }
  }
  return out;
}

void ContactConstraint::friction_gradients(const Side& s, const FrictionRows& fr,
                                           const std::function<PetscInt(std::size_t, int)>& row_of,
                                           double sign, std::vector<PetscInt>& gi,
                                           std::vector<PetscInt>& gj,
                                           std::vector<double>& gv) const {
  const int dim = disc_.dim();
  const auto& nodes = s.itf.slave().mesh_nodes;
  const auto n = nodes.size();
  const auto& frames = fr.frames;
  const auto& rows = fr.rows;
  // += sign D_j coefficient * gradient, for each tangent row of node j (D_j = D_jj with dual
  // multipliers, the nodal weight with standard ones).
  const auto add_gradient = [&](std::size_t j, PetscInt column,
                                double (*coefficient)(const contact::FrictionRow&, int), int a,
                                double value) {
    for (int i = 0; i < frames[j].n_tangents; ++i) {
      const double v = sign * s.D[j] * coefficient(rows[j][static_cast<std::size_t>(i)], a) * value;
      if (v == 0.0) continue;
      gi.push_back(row_of(j, i));
      gj.push_back(column);
      gv.push_back(v);
    }
  };
  const auto coef_u = [](const contact::FrictionRow& r, int a) { return r.a_u[a]; };
  const auto coef_n = [](const contact::FrictionRow& r, int a) { return r.a_n[a]; };
  const auto coef_g = [](const contact::FrictionRow& r, int) { return r.a_g; };
  // Against a rigid plane u~ = D s with s = P (x~ - x~^n - (c - c^n)): dD enters through u~ too.
  // (Energy-momentum contact: u~ over the mean operators, as between two bodies.)
  const bool rigid = s.itf.rigid() && !s.discrete_gradient;
  std::vector<double> s_nodal(n * dim, 0.0);
  for (std::size_t j = 0; j < n; ++j)
    if (s.active[j] && rigid)
      for (int c = 0; c < dim; ++c) s_nodal[j * dim + c] = s.slip[j * dim + c] / s.D[j];
  const auto coef_D = [&](std::size_t j, int i) {
    const auto& r = rows[j][static_cast<std::size_t>(i)];
    double v = r.a_D;
    if (rigid)
      for (int c = 0; c < dim; ++c) v += r.a_u[c] * s_nodal[j * dim + c];
    return v;
  };
  // This rank's parts of the gradients of g~_j, D_j and of the operators in u~.
  for (const auto& e : s.lin.gap_gradient) {
    const auto j = static_cast<std::size_t>(e.row);
    if (s.active[j]) add_gradient(j, global_dof(e.col), coef_g, 0, e.value);
  }
  for (const auto& e : s.lin.D_gradient) {
    const auto j = static_cast<std::size_t>(e.row);
    if (!s.active[j]) continue;
    for (int i = 0; i < frames[j].n_tangents; ++i) {
      const double v = sign * s.D[j] * coef_D(j, i) * e.value;
      if (v == 0.0) continue;
      gi.push_back(row_of(j, i));
      gj.push_back(global_dof(e.col));
      gv.push_back(v);
    }
  }
  for (const auto& e : s.lin.operator_gradient) {
    const auto j = static_cast<std::size_t>(e.row / dim);
    if (s.active[j])
      add_gradient(j, global_dof(e.col), coef_u, static_cast<int>(e.row % dim), e.value);
  }
  // Row j of T^-1 (the unit row without a modified basis): dx~_j = sum_k T^-1_jk dx_k.
  std::vector<std::vector<std::pair<std::size_t, double>>> inverse_row(n);
  for (const auto& e : s.T_inverse)
    inverse_row[static_cast<std::size_t>(e.row)].emplace_back(static_cast<std::size_t>(e.col),
                                                              e.value);
  for (std::size_t j = 0; j < n; ++j)
    if (inverse_row[j].empty()) inverse_row[j].emplace_back(j, 1.0);
  if (s.discrete_gradient) {
    // Energy-momentum: u~_j = sum_k D_jk dx_k - sum_l M_jl dx_l at fixed (mean) operators (the
    // operators' derivatives and the rotation's correction are in s.lin.operator_gradient).
    for_each_mean_operator(s, [&](std::size_t j, std::int32_t node, double w) {
      if (s.active[j])
        for (int a = 0; a < dim; ++a) add_gradient(j, dof_of(node, a), coef_u, a, w);
    });
  } else if (!rigid) {
    // u~ at fixed operators: sum_l (M_jl - M_jl^n) dx_l (this rank's parts of M and M^n) and,
    // with standard multipliers, -sum_{k != j} (D_jk - D_jk^n) dx_k.
    for (const auto& e : s.part.M) {
      const auto j = static_cast<std::size_t>(e.slave);
      if (!s.active[j]) continue;
      for (int a = 0; a < dim; ++a) add_gradient(j, dof_of(e.master_node, a), coef_u, a, e.value);
    }
    for (const auto& e : s.M_old) {
      const auto j = static_cast<std::size_t>(e.slave);
      if (!s.active[j]) continue;
      for (int a = 0; a < dim; ++a) add_gradient(j, dof_of(e.master_node, a), coef_u, a, -e.value);
    }
    const auto coupling = [&](const std::vector<mortar::Triplet>& D, double scale) {
      for (const auto& e : D) {
        const auto j = static_cast<std::size_t>(e.row);
        if (!s.active[j]) continue;
        for (const auto& [k, tk] : inverse_row[static_cast<std::size_t>(e.col)])
          for (int a = 0; a < dim; ++a)
            add_gradient(j, dof_of(nodes[k], a), coef_u, a, scale * tk * e.value);
      }
    };
    coupling(s.part.D_coupling, -1.0);
    coupling(s.D_coupling_old, 1.0);
  }
  std::vector<contact::DofTriplet> dn;
  for (std::size_t j = 0; j < n; ++j) {
    if (!s.active[j] || !owns(nodes[j])) continue;
    // The normal's derivative; the slip increment at fixed operators on the slave node:
    // -(D_jj - D_jj^n) dx~_j (two bodies) or D_j P dx~_j (rigid plane), dx~ = T^-1 dx.
    dn.clear();
    s.itf.normal_jacobian(static_cast<local_index>(j), dn);
    for (const auto& e : dn)
      add_gradient(j, global_dof(e.col), coef_n, static_cast<int>(e.row), e.value);
    const double* normal = &s.itf.normals()[j * dim];
    if (rigid && !dn.empty()) {
      // A round obstacle's normal turns with the node, and so does P in u~ = D P d with
      // d = x~ - x~^n - (c - c^n): du~ = -D (n (d . dn) + (d . n) dn).
      const auto obstacle = s.itf.plane_displacement();
      double d[3] = {0, 0, 0}, dn_d = 0.0;
      for (int c = 0; c < dim; ++c) {
        d[c] = s.x[j * dim + c] - s.x_old[j * dim + c] - (obstacle[c] - s.plane_old[c]);
        dn_d += d[c] * normal[c];
      }
      for (const auto& e : dn)
        for (int c = 0; c < dim; ++c) {
          const double v = -s.D[j] * e.value *
                           (d[e.row] * normal[c] + (c == static_cast<int>(e.row) ? dn_d : 0.0));
          if (v != 0.0) add_gradient(j, global_dof(e.col), coef_u, c, v);
        }
    }
    for (const auto& [k, tk] : inverse_row[j])
      for (int a = 0; a < dim; ++a)
        for (int b = 0; b < dim; ++b) {
          double v = 0.0;
          if (rigid)
            v = s.D[j] * ((a == b ? 1.0 : 0.0) - normal[a] * normal[b]);
          else if (a == b)
            v = s.discrete_gradient ? 0.0 : -(s.D_diag[j] - s.D_diag_old[j]);
          if (v != 0.0) add_gradient(j, dof_of(nodes[k], b), coef_u, a, tk * v);
        }
  }
}

void ContactConstraint::condense_friction(
    Side& s, std::vector<char>& replaced, std::vector<PetscInt>& li, std::vector<PetscInt>& lj,
    std::vector<double>& lv, std::vector<PetscInt>& gi, std::vector<PetscInt>& gj,
    std::vector<double>& gv, std::vector<PetscInt>& set_rows, std::vector<double>& set_values,
    std::vector<PetscInt>& add_rows, std::vector<double>& add_values) const {
  const int dim = disc_.dim();
  const PetscInt first = disc_.first_owned_dof();
  const auto& nodes = s.itf.slave().mesh_nodes;
  const auto n = nodes.size();
  const FrictionRows fr = friction_rows(s);
  const auto& frames = fr.frames;
  const auto tangent_row = [&](std::size_t j, int i) {
    return dof_of(nodes[j], frames[j].tangent_component[i]);
  };
  // G += -D_jj beta: the tangent rows multiplied by -D_jj (contact_constraint.hpp).
  friction_gradients(s, fr, tangent_row, -1.0, gi, gj, gv);
  // Master rows: sum_j (M_jl / D_jj) P_V (K~_j dd + r_j).
  for (const auto& e : s.part.M) {
    const auto j = static_cast<std::size_t>(e.slave);
    if (!s.active[j]) continue;
    for (int a = 0; a < dim; ++a) {
      if (s.dirichlet[j * dim + a]) continue;
      li.push_back(dof_of(e.master_node, a));
      lj.push_back(dof_of(nodes[j], a));
      lv.push_back(e.value / s.D[j]);
    }
  }
  for (std::size_t j = 0; j < n; ++j) {
    if (!s.active[j] || !owns(nodes[j])) continue;
    const NodeFrame& f = frames[j];
    const PetscInt gap_row = dof_of(nodes[j], f.gap_component);
    replaced[static_cast<std::size_t>(gap_row - first)] = 1;
    set_rows.push_back(gap_row);
    set_values.push_back(s.c_n * s.gap[j]);
    for (int i = 0; i < f.n_tangents; ++i) {
      const auto& r = fr.rows[j][static_cast<std::size_t>(i)];
      const PetscInt row = tangent_row(j, i);
      replaced[static_cast<std::size_t>(row - first)] = 1;
      // -D_jj (alpha . lambda^{k+1}) = alpha . P_V (K~_j dd + r_j): through L.
      double alpha_lambda = 0.0;
      for (int b = 0; b < dim; ++b) {
        alpha_lambda += r.alpha[b] * s.lambda[j * dim + b];
        if (s.dirichlet[j * dim + b] || r.alpha[b] == 0.0) continue;
        li.push_back(row);
        lj.push_back(dof_of(nodes[j], b));
        lv.push_back(r.alpha[b]);
      }
      add_rows.push_back(row);
      add_values.push_back(-s.D[j] * (r.value - alpha_lambda));
    }
  }
}

int ContactConstraint::n_on_cone() const {
  int n = 0;
  for (const auto& s : sides_) n += s.friction ? s.on_cone : 0;
  return n;
}

int ContactConstraint::n_inconsistent() const {
  int n = 0;
  for (const auto& s : sides_) n += s.friction ? s.inconsistent : 0;
  return n;
}

void ContactConstraint::saddle_friction(Side& s, std::vector<PetscInt>& ci,
                                        std::vector<PetscInt>& cj, std::vector<double>& cv,
                                        std::vector<PetscInt>& ei, std::vector<PetscInt>& ej,
                                        std::vector<double>& ev,
                                        std::vector<double>& lm_rhs) const {
  // Rows of the multipliers lambda_j (dim per slave node, numbered from lm_index[j]), each
  // multiplied by the nodal weight D_j: inactive nodes and prescribed components lambda = 0;
  // active nodes the gap row c_n dg~_j dd = -c_n g~_j (component gap_component) and per
  // tangent t_i (component tangent_component[i]) the linearized frictional condition
  //   D_j alpha . lambda^{k+1} + D_j beta . dd = -D_j (C_i - alpha . lambda^k).
  const int dim = disc_.dim();
  const auto& nodes = s.itf.slave().mesh_nodes;
  const auto n = nodes.size();
  const FrictionRows fr = friction_rows(s);
  const auto& frames = fr.frames;
  const auto lm_row = [&](std::size_t j, int c) {
    return s.lm_index[j] + static_cast<PetscInt>(c);
  };
  friction_gradients(
      s, fr, [&](std::size_t j, int i) { return lm_row(j, frames[j].tangent_component[i]); }, 1.0,
      ci, cj, cv);
  for (const auto& e : s.lin.gap_gradient) {
    const auto j = static_cast<std::size_t>(e.row);
    if (!s.active[j]) continue;
    ci.push_back(lm_row(j, frames[j].gap_component));
    cj.push_back(global_dof(e.col));
    cv.push_back(s.c_n * e.value);
  }
  const double weight = mean_weight(s);
  for (std::size_t j = 0; j < n; ++j) {
    if (!owns(nodes[j])) continue;
    const double Dj = s.D[j] > 0.0 ? s.D[j] : weight;
    std::vector<double> rhs(static_cast<std::size_t>(dim), 0.0);
    std::vector<char> done(static_cast<std::size_t>(dim), 0);
    if (s.active[j]) {
      const NodeFrame& f = frames[j];
      rhs[static_cast<std::size_t>(f.gap_component)] = -s.c_n * s.gap[j];
      done[static_cast<std::size_t>(f.gap_component)] = 1;
      for (int i = 0; i < f.n_tangents; ++i) {
        const auto& r = fr.rows[j][static_cast<std::size_t>(i)];
        const int c = f.tangent_component[i];
        double alpha_lambda = 0.0;
        for (int b = 0; b < dim; ++b) {
          alpha_lambda += r.alpha[b] * s.lambda[j * dim + b];
          if (r.alpha[b] == 0.0) continue;
          ei.push_back(lm_row(j, c));
          ej.push_back(lm_row(j, b));
          ev.push_back(Dj * r.alpha[b]);
        }
        rhs[static_cast<std::size_t>(c)] = -Dj * (r.value - alpha_lambda);
        done[static_cast<std::size_t>(c)] = 1;
      }
    }
    for (int c = 0; c < dim; ++c) {
      if (!done[static_cast<std::size_t>(c)]) {
        ei.push_back(lm_row(j, c));
        ej.push_back(lm_row(j, c));
        ev.push_back(Dj);
      }
      lm_rhs.push_back(rhs[static_cast<std::size_t>(c)]);
    }
  }
}

double ContactConstraint::dissipation_increment(const Side& s) const {
  // Work of the frictional tractions on the step's relative motion: sum_j lambda_t,j . u~_j.
  // Against a rigid obstacle with standard multipliers u~_j here is sum_k D_jk d_k, not the
  // lumped D_j d_j of the stick/slip condition: the slave force of node k is
  // sum_j D_jk lambda_j, so this is exactly the work of the frictional forces, the term of
  // the energy balance (kinetic + strain + dissipated = external work). The lumped measure
  // misses sum_jk D_jk lambda_t,j . (d_k - d_j), a share of the neighbours' relative motion
  // that does not fall with the time step (5.4e-6 E0 at dt and 1.6e-5 at dt / 2 on the
  // thrown block of test_friction.py). Between two bodies the condition's slip already
  // carries the coupling (Gitterle et al. 2010, eq. 31), and so does the energy-momentum
  // increment over the mean operators (contact_energy_momentum_friction.cpp), also against an
  // obstacle.
  const int dim = disc_.dim();
  const bool coupled = s.itf.rigid() && s.itf.standard() && !s.discrete_gradient;
  const std::vector<double> w = coupled ? rigid_motion_weighted(s) : std::vector<double>{};
  const std::vector<double>& slip = coupled ? w : s.slip;
  // Summed over the owners of the nodes: a rank has the normals of the slave nodes it reads.
  const int rank = disc_.comm().rank();
  double work = 0.0;
  for (std::size_t j = 0; j < s.active.size(); ++j) {
    if (!s.active[j] || s.node_owners[j] != rank) continue;
    const double* n = &s.itf.normals()[j * dim];
    double ln = 0.0;
    for (int c = 0; c < dim; ++c) ln += s.lambda[j * dim + c] * n[c];
    for (int c = 0; c < dim; ++c) work += (s.lambda[j * dim + c] - ln * n[c]) * slip[j * dim + c];
  }
  return disc_.comm().sum(work);
}

void ContactConstraint::save_friction(Side& s) {
  s.dissipation += dissipation_increment(s);
  s.D_diag_old = s.D_diag;
  s.D_coupling_old = s.part.D_coupling;
  s.M_old = s.part.M;
  s.x_old = s.x;
  s.plane_old = s.itf.plane_displacement();
  s.has_old = true;
}

} // namespace seam::problem
