// Energy-momentum contact (docs/contact_dynamics.md §4; Hesch & Betsch 2009, Gonzalez 1996):
// the contact force of the energy-momentum step (in the residual f_int - f_ext + f_c) is
// f_c = -sum_j lambda_j grad_d g~_j (lambda_j >= 0 pushes the bodies apart: the gradient of
// g~_j points from the slave towards the master side) with the discrete gradient
//   grad_d g~_j = G + (g~_j(x_{n+1}) - g~_j(x_n) - G . dx) w / (w . dx),   G = grad g~_j(x_mid),
// dx = x_{n+1} - x_n on the nodes of g~_j, x_mid = (x_n + x_{n+1}) / 2 and w = dx without its
// rigid part (translations and the infinitesimal rotation about x_mid, Euclidean projection):
// grad_d g~_j . dx = g~_j(x_{n+1}) - g~_j(x_n) (exactly unless dx is rigid to 1e-3, see
// discrete_gradient), and the force and its moment about the midpoint vanish as for G. The Newton
// matrix takes its exact derivative with respect to x_{n+1}: lambda_j H/2 (H the Hessian of g~_j at
// x_mid) plus the derivative of the correction.
#include "seam/problem/contact_constraint.hpp"
#include "seam/problem/diagnostics.hpp"

#include "seam/common/error.hpp"
#include "seam/parallel/exchange.hpp"

#include <Eigen/Dense>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string_view>

namespace seam::problem {

namespace {

/// One contribution to the per-node data of the discrete gradient: node j, what (the gap at
/// the start g0 or end g1 of the step, the gradient at the midpoint G or at the end G1, H dx
/// at the midpoint), the dof (id of the node in the mesh as read * dim + component, the same on
/// every rank) and the value; with a dof, the step's increment and the
/// midpoint position there, so that the node's owner reads no displacement of its own (the
/// sender read them with its blocks).
struct Entry {
  std::int64_t dof = 0;
  std::int64_t node = 0; ///< the slave node's id in the mesh as read (not its index in the side)
  std::int32_t kind = 0;
  std::int32_t pad = 0;
  double value = 0.0;
  double dx = 0.0;
  double x_mid = 0.0;
};
enum Kind : std::int32_t { g0 = 0, g1 = 1, mid_gradient = 2, end_gradient = 3, hessian_dx = 4 };

/// The discrete gradient of one weighted gap over its n = dim * nodes dofs and the derivative
/// of its correction term with respect to x_{n+1} (column-major n x n; zero if uncorrected).
struct DiscreteGradient {
  Eigen::VectorXd value;
  Eigen::MatrixXd correction_jacobian;
  double w_norm = 0.0, dx_norm = 0.0, N = 0.0, ratio = 0.0; ///< diagnostics
};

/// The motions that change no weighted gap of a side, removed from the increment to make the
/// correction's direction w: translations along `translations` and rotations about `axes`
/// through `centre` (through the centroid of the nodes if `about_centroid`). Two bodies: all
/// rigid motions; a rigid plane: the translations along it and (3D) the rotation about its
/// normal; a rigid sphere: the rotations about its centre; a rigid cylinder: the translations
/// along its axis and the rotations about it. The discrete gradient is then free
/// of force along those translations and of moment about those axes, as the gradient of a
/// function invariant under them is.
struct Invariance {
  std::vector<Eigen::Vector3d> translations, axes;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  bool about_centroid = true;
};

Invariance invariance_of(const contact::ContactInterface& itf, int dim) {
  Invariance inv;
  const auto unit = [](int k) {
    Eigen::Vector3d e = Eigen::Vector3d::Zero();
    e(k) = 1.0;
    return e;
  };
  if (!itf.rigid()) {
    for (int k = 0; k < dim; ++k) inv.translations.push_back(unit(k));
    if (dim == 2)
      inv.axes.push_back(unit(2));
    else
      for (int k = 0; k < 3; ++k) inv.axes.push_back(unit(k));
    return inv;
  }
  const contact::Obstacle& o = itf.obstacle();
  if (o.shape == contact::Obstacle::Shape::plane) {
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (int k = 0; k < dim; ++k) n(k) = o.direction[static_cast<std::size_t>(k)];
    if (dim == 2) {
      inv.translations.push_back(Eigen::Vector3d(-n(1), n(0), 0.0));
    } else {
      int axis = 0;
      n.cwiseAbs().minCoeff(&axis);
      const Eigen::Vector3d t1 = n.cross(unit(axis)).normalized();
      inv.translations = {t1, n.cross(t1)};
      inv.axes.push_back(n);
    }
    return inv;
  }
  inv.about_centroid = false;
  for (int k = 0; k < dim; ++k) inv.centre(k) = o.point[static_cast<std::size_t>(k)];
  if (o.shape == contact::Obstacle::Shape::cylinder) {
    // A cylinder (3D only): the translations along its axis and the rotations about it.
    const Eigen::Vector3d a(o.direction[0], o.direction[1], o.direction[2]);
    inv.translations.push_back(a);
    inv.axes.push_back(a);
    return inv;
  }
  // A sphere (a circle in 2D): the rotations about its centre.
  if (dim == 2)
    inv.axes.push_back(unit(2));
  else
    for (int k = 0; k < 3; ++k) inv.axes.push_back(unit(k));
  return inv;
}

/// dx, x_mid: the step's increment and midpoint positions on the dofs (node-major, dim per
/// node); G, G1: the gradients at the midpoint and the end; Hdx: the Hessian at the midpoint
/// times dx.
DiscreteGradient discrete_gradient(int dim, const Invariance& inv, const Eigen::VectorXd& dx,
                                   const Eigen::VectorXd& x_mid, double gap_start, double gap_end,
                                   const Eigen::VectorXd& G, const Eigen::VectorXd& G1,
                                   const Eigen::VectorXd& Hdx, bool jacobian) {
  const auto n = dx.size();
  const int n_nodes = static_cast<int>(n / dim);
  const int n_translations = static_cast<int>(inv.translations.size());
  const int n_rotations = static_cast<int>(inv.axes.size());
  const int r = n_translations + n_rotations;
  DiscreteGradient out;
  out.value = G;
  out.correction_jacobian = Eigen::MatrixXd::Zero(n, n);
  // The invariant motions: translations t, rotations a_k x (x_a - c) about the centre c (the
  // centroid of x_mid where the translations make the choice free).
  Eigen::Vector3d c = inv.centre;
  if (inv.about_centroid) {
    c.setZero();
    for (int a = 0; a < n_nodes; ++a)
      for (int b = 0; b < dim; ++b) c(b) += x_mid(a * dim + b) / n_nodes;
  }
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(n, r);
  // a_k x e_b, the derivative of rotation mode k at a node along coordinate b.
  const auto spin = [&inv](int k, int b) {
    Eigen::Vector3d e = Eigen::Vector3d::Zero();
    e(b) = 1.0;
    return Eigen::Vector3d(inv.axes[static_cast<std::size_t>(k)].cross(e));
  };
  for (int a = 0; a < n_nodes; ++a) {
    Eigen::Vector3d y = Eigen::Vector3d::Zero();
    for (int b = 0; b < dim; ++b) y(b) = x_mid(a * dim + b) - c(b);
    for (int k = 0; k < n_translations; ++k)
      for (int b = 0; b < dim; ++b)
        R(a * dim + b, k) = inv.translations[static_cast<std::size_t>(k)](b);
    for (int k = 0; k < n_rotations; ++k) {
      const Eigen::Vector3d v = inv.axes[static_cast<std::size_t>(k)].cross(y);
      for (int b = 0; b < dim; ++b) R(a * dim + b, n_translations + k) = v(b);
    }
  }
  // At most 6 x 6 (3 translations, 3 rotations). A fixed-capacity type: inverting a MatrixXd
  // would instantiate PartialPivLU<MatrixXd> in seam, and the dynamic linker then binds Gmsh's
  // own calls of that template to seam's copy, whose allocation differs when the two were
  // built with other alignment settings (AddressSanitizer: bad-free inside libgmsh).
  using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
  const Small A_inv = Small(R.transpose() * R).inverse();
  const Eigen::VectorXd coefficients = A_inv * (R.transpose() * dx);
  const Eigen::VectorXd w = dx - R * coefficients;
  // The correction N w / |w|^2 is 0 / 0 for a rigid increment (which changes no gap) and, as
  // |w| -> 0, round-off in N over |w|: the denominator is |w|^2 + (c |dx|)^2. For
  // |w| >> c |dx| the discrete gradient is exact; below, grad_d . dx misses N c^2 |dx|^2 /
  // (|w|^2 + c^2 |dx|^2) <= |N|, and N = O(|w| |dx|^2) there (the midpoint rule's error for a
  // nearly rigid motion): a relative energy error of about c |dx|^2 / L^2 of the step's
  // contact work. c = 1e-3 keeps the round-off eps |G| |dx| / (c |dx|) at 1e-13 of |G|.
  constexpr double c2 = 1e-6;
  const double Q = w.squaredNorm();
  const double den = Q + c2 * dx.squaredNorm();
  if (!(den > 0.0)) return out;
  const double N = gap_end - gap_start - G.dot(dx);
  const double ratio = N / den;
  out.w_norm = std::sqrt(Q);
  out.dx_norm = dx.norm();
  out.N = N;
  out.ratio = ratio;
  out.value += ratio * w;
  if (!jacobian) return out;
  // dw/dx_{n+1} = P (I - dR a) - R A^-1 dR^T w with dR = d R / d x_{n+1} (x_mid moves by half).
  Eigen::MatrixXd dw(n, n);
  for (int a = 0; a < n_nodes; ++a)
    for (int b = 0; b < dim; ++b) {
      const int v = a * dim + b;
      Eigen::VectorXd y = Eigen::VectorXd::Zero(n);
      y(v) = 1.0;
      Eigen::VectorXd rotation_rows = Eigen::VectorXd::Zero(r);
      Eigen::Vector3d wa = Eigen::Vector3d::Zero();
      for (int e = 0; e < dim; ++e) wa(e) = w(a * dim + e);
      for (int k = 0; k < n_rotations; ++k) {
        const Eigen::Vector3d s = spin(k, b);
        for (int e = 0; e < dim; ++e)
          y(a * dim + e) -= 0.5 * coefficients(n_translations + k) * s(e);
        rotation_rows(n_translations + k) = 0.5 * s.dot(wa);
      }
      dw.col(v) = y - R * (A_inv * (R.transpose() * y)) - R * (A_inv * rotation_rows);
    }
  const Eigen::VectorXd dN = G1 - G - 0.5 * Hdx;
  const Eigen::VectorXd dden = 2.0 * dw.transpose() * w + 2.0 * c2 * dx;
  out.correction_jacobian = w * (dN / den - N / (den * den) * dden).transpose() + ratio * dw;
  return out;
}

} // namespace

void ContactConstraint::start_step(const la::Vector& u_n) {
  if (!energy_momentum_ || sides_.empty()) return;
  // Kept whole as the distributed vector; each rank reads the nodes it reads of u by the same
  // scatter (refresh_displacement), not every interface node.
  if (!has_start_) u_start_ = u_n.duplicate();
  u_start_.copy_from(u_n);
  has_start_ = true;
  start_read_ = false;
}

int ContactConstraint::n_discrete_gradient() const {
  return static_cast<int>(std::count_if(sides_.begin(), sides_.end(),
                                        [](const Side& s) { return s.discrete_gradient; }));
}

int ContactConstraint::n_end_of_step() const {
  return static_cast<int>(sides_.size()) - n_discrete_gradient();
}

void ContactConstraint::evaluate_discrete_gradient(Side& s, std::span<const double> u,
                                                   bool tangent) {
  const int dim = disc_.dim();
  const auto& X = reference_x_; // mesh and outside nodes
  s.em_gradient.clear();
  s.em_tangent.clear();
  // Before the first step: the start is u. Nodes found outside this part since the start was
  // read (map_nodes below numbers the dofs of the discrete gradients) are not read by it.
  if (u_mesh_start_.empty()) u_mesh_start_.assign(u.begin(), u.end());
  if (u_mesh_start_.size() < u.size()) u_mesh_start_.resize(u.size(), 0.0);
  const std::vector<double>& u0 = u_mesh_start_;
  std::vector<double> mid(u.size());
  for (std::size_t i = 0; i < u.size(); ++i) mid[i] = 0.5 * (u[i] + u0[i]);
  std::vector<contact::GapBlock> start, end, middle;
  s.itf.gap_blocks(u0, contact::GapOrder::value, start);
  const long r0 = contact::detail::gap_rejections[0], r1 = contact::detail::gap_rejections[1],
             r2 = contact::detail::gap_rejections[2];
  std::vector<contact::GapPairRecord> pair_log;
  if (contact_trace_level() == 3) contact::detail::gap_pair_log = &pair_log;
  s.itf.gap_blocks(u, contact::GapOrder::gradient, end);
  contact::detail::gap_pair_log = nullptr;
  if (contact_trace_level() == 3) trace_gap_pairs(s.itf.name(), pair_log);
  s.em_rejections[0] = contact::detail::gap_rejections[0] - r0;
  s.em_rejections[1] = contact::detail::gap_rejections[1] - r1;
  s.em_rejections[2] = contact::detail::gap_rejections[2] - r2;
  // The Hessians at the midpoint (the bulk of the cost) only when the Newton matrix is built,
  // and only of the blocks with a slave node that carries a multiplier: the Hessian enters
  // the matrix times lambda_j (H / 2 and, through H dx, the correction's derivative).
  // With friction the normal part n_j . lambda_j of the Cartesian multiplier.
  const std::vector<double> lambda = normal_multipliers(s);
  std::vector<char> carries(lambda.size(), 0);
  for (std::size_t j = 0; j < carries.size(); ++j) carries[j] = lambda[j] != 0.0;
  s.itf.gap_blocks(mid, tangent ? contact::GapOrder::hessian : contact::GapOrder::gradient, middle,
                   carries);
  const auto dof_of = [](const contact::GapBlock& b, int v) { return b.dof(v); };
  // An entry at mesh dof d: sent with its node id, the increment and the midpoint there.
  const auto key = [&](local_index j) { return s.slave_ids.nodes[static_cast<std::size_t>(j)]; };
  const auto at = [&](std::int64_t d, local_index j, Kind kind, double value) {
    const auto i = static_cast<std::size_t>(d);
    const std::int64_t id = node_id(static_cast<std::int32_t>(d / dim)) * dim + d % dim;
    return Entry{id, key(j), kind, 0, value, u[i] - u0[i], X[i] + mid[i]};
  };
  s.em_blocks = end.size();
  s.em_blocks_hash = 1469598103934665603ull;
  for (const auto& b : end) {
    const auto mix = [&s](std::int64_t v) {
      s.em_blocks_hash = (s.em_blocks_hash ^ static_cast<std::uint64_t>(v)) * 1099511628211ull;
    };
    for (const auto j : b.slave) mix(j);
    for (const auto d : b.dofs) mix(d);
  }
  // The gap rows of the Newton step: this rank's part of d g~_j / dx at x_{n+1}, of the same
  // function whose discrete gradient is the force (so that g~_j(x_{n+1}) = 0 holds for it).
  s.lin.gap_gradient.clear();
  for (const auto& b : end) {
    const int nv = b.n_variables();
    for (std::size_t r = 0; r < b.slave.size(); ++r)
      for (int v = 0; v < nv; ++v)
        if (const auto dof = dof_of(b, v);
            dof >= 0 &&
            b.gradient[r * static_cast<std::size_t>(nv) + static_cast<std::size_t>(v)] != 0.0)
          s.lin.gap_gradient.push_back(
              {b.slave[r], dof,
               b.gradient[r * static_cast<std::size_t>(nv) + static_cast<std::size_t>(v)]});
  }
  // This rank's entries and, for each, the rank it goes to: the owner of its slave node,
  // which alone assembles the node's discrete gradient.
  std::vector<Entry> local;
  std::vector<int> to;
  const auto add = [&](local_index j, const Entry& e) {
    local.push_back(e);
    to.push_back(s.node_owners[static_cast<std::size_t>(j)]);
  };
  for (const auto& b : start)
    for (std::size_t r = 0; r < b.slave.size(); ++r)
      add(b.slave[r], {0, key(b.slave[r]), g0, 0, b.gap[r]});
  for (const auto& b : end) {
    const auto nv = static_cast<std::size_t>(b.n_variables());
    for (std::size_t r = 0; r < b.slave.size(); ++r) {
      add(b.slave[r], {0, key(b.slave[r]), g1, 0, b.gap[r]});
      for (std::size_t v = 0; v < nv; ++v)
        if (const auto dof = dof_of(b, static_cast<int>(v)); dof >= 0)
          add(b.slave[r], at(dof, b.slave[r], end_gradient, b.gradient[r * nv + v]));
    }
  }
  for (const auto& b : middle) {
    const auto nv = static_cast<std::size_t>(b.n_variables());
    for (std::size_t r = 0; r < b.slave.size(); ++r) {
      const auto j = static_cast<std::size_t>(b.slave[r]);
      for (std::size_t v = 0; v < nv; ++v) {
        const auto dof = dof_of(b, static_cast<int>(v));
        if (dof < 0) continue;
        add(b.slave[r], at(dof, b.slave[r], mid_gradient, b.gradient[r * nv + v]));
        if (!tangent || b.hessian.empty()) continue;
        double hdx = 0.0;
        for (std::size_t k = 0; k < nv; ++k)
          if (const auto col = dof_of(b, static_cast<int>(k)); col >= 0) {
            const double h = b.hessian[(r * nv + v) * nv + k];
            hdx += h * (u[static_cast<std::size_t>(col)] - u0[static_cast<std::size_t>(col)]);
            // This rank's part of -lambda_j d(grad g~_j(x_mid))/dx_{n+1} = -lambda_j H / 2.
            if (lambda[j] != 0.0 && h != 0.0)
              s.em_tangent.push_back({dof, col, -0.5 * lambda[j] * h});
          }
        add(b.slave[r], at(dof, b.slave[r], hessian_dx, hdx));
      }
    }
  }
  // Each entry to the owner of its slave node only (one Alltoallv), in this rank's order:
  // the owner receives them by source rank, so that every sum below runs in the same order at
  // every np (by node id, then source rank, then the sender's order).
  const int size = disc_.comm().size();
  std::vector<std::int64_t> send_offsets(static_cast<std::size_t>(size) + 1, 0);
  for (const int r : to) ++send_offsets[static_cast<std::size_t>(r) + 1];
  for (int r = 0; r < size; ++r) send_offsets[r + 1] += send_offsets[r];
  std::vector<Entry> send(local.size());
  {
    std::vector<std::int64_t> next(send_offsets.begin(), send_offsets.end() - 1);
    for (std::size_t e = 0; e < local.size(); ++e)
      send[static_cast<std::size_t>(next[static_cast<std::size_t>(to[e])]++)] = local[e];
  }
  std::vector<std::int64_t> recv_offsets;
  std::vector<Entry> all = parallel::alltoallv<Entry>(
      disc_.comm().get(), std::span<const Entry>(send), send_offsets, recv_offsets);
  s.em_entries_sent += static_cast<std::int64_t>(send.size());
  s.em_entries_received += static_cast<std::int64_t>(all.size());
  const auto& nodes = s.itf.slave().mesh_nodes;
  const Invariance invariance = invariance_of(s.itf, dim);
  // The side-local index of a slave node id (every node an entry reaches is held by its
  // owner, the receiver).
  const auto held = [&](std::int64_t id) -> std::int64_t {
    const auto& ids = s.slave_ids.nodes;
    const auto it = std::lower_bound(ids.begin(), ids.end(), id);
    return it != ids.end() && *it == id ? it - ids.begin() : -1;
  };
  // The weighted gaps at x_{n+1} that the active set and the gap rows use, and which slave
  // nodes have a gap row at all: the segmentation's D_jj can be positive where these blocks
  // integrate nothing (their own pre-checks), and such a node must stay inactive. Summed by
  // the owners and published to the nodes' holders (the cycling guard reads the gap rows of
  // every held node).
  const auto n_side = s.gap.size();
  std::vector<double> sums(n_side * 2, 0.0);
  for (const auto& e : all) {
    const auto jj = held(e.node);
    SEAM_ASSERT(jj >= 0 && owns(nodes[static_cast<std::size_t>(jj)]));
    const auto j = static_cast<std::size_t>(jj);
    if (e.kind == g1) sums[j * 2] += e.value;
    if (e.kind == end_gradient && e.value != 0.0) sums[j * 2 + 1] = 1.0;
  }
  publish(s, sums, 2);
  s.em_row.assign(n_side, 0);
  for (std::size_t j = 0; j < n_side; ++j) {
    s.gap[j] = sums[j * 2];
    s.em_row[j] = sums[j * 2 + 1] != 0.0;
  }
  std::stable_sort(all.begin(), all.end(),
                   [](const Entry& a, const Entry& b) { return a.node < b.node; });
  // The nodes of the dofs of the slave nodes this rank owns: mesh nodes, or on sides held in
  // part nodes outside its part (map_nodes, collective: the same decision on every rank).
  std::vector<std::int64_t> dof_ids;
  for (const auto& e : all)
    if (e.kind >= mid_gradient) dof_ids.push_back(e.dof / dim);
  std::sort(dof_ids.begin(), dof_ids.end());
  dof_ids.erase(std::unique(dof_ids.begin(), dof_ids.end()), dof_ids.end());
  std::vector<std::int32_t> dof_nodes;
  if (s.slave_in_part || s.master_in_part) {
    map_nodes(dof_ids, dof_nodes);
  } else {
    dof_nodes.resize(dof_ids.size());
    for (std::size_t i = 0; i < dof_ids.size(); ++i) dof_nodes[i] = node_of_gid(dof_ids[i]);
  }
  // SEAM_CONTACT_TRACE=2 (docs/contact_dynamics.md, "Diagnosing a stalled Newton step"): the
  // slave nodes with the largest correction force lambda_j |N| / sqrt(den) at each Newton
  // matrix, with |w|, |dx|, N and the gaps at both ends of the step.
  const bool trace = contact_trace_level() == 2;
  struct Traced {
    double force;
    std::int64_t node;
    double lambda, w, dx, N, g0, g1;
    int nodes;
    std::string list;
  };
  std::vector<Traced> traced;
  for (std::size_t begin = 0; begin < all.size();) {
    std::size_t stop = begin;
    while (stop < all.size() && all[stop].node == all[begin].node) ++stop;
    const auto j = static_cast<std::size_t>(held(all[begin].node));
    // The node's dofs (by node id, so in the same order at every np), node-major with all dim
    // components.
    std::map<std::int64_t, int> index;
    for (std::size_t e = begin; e < stop; ++e)
      if (all[e].kind >= mid_gradient) index.emplace(all[e].dof / dim * dim, 0);
    std::vector<std::int64_t> dofs;
    for (auto& [node_dof, i] : index) {
      i = static_cast<int>(dofs.size());
      for (int c = 0; c < dim; ++c) dofs.push_back(node_dof + c);
    }
    const auto n = static_cast<Eigen::Index>(dofs.size());
    Eigen::VectorXd G = Eigen::VectorXd::Zero(n), G1 = G, Hdx = G, dx = G, x_mid = G;
    double gap_start = 0.0, gap_end = 0.0;
    for (std::size_t e = begin; e < stop; ++e) {
      const Entry& en = all[e];
      if (en.kind == g0) gap_start += en.value;
      if (en.kind == g1) gap_end += en.value;
      if (en.kind < mid_gradient) continue;
      const auto i = index[en.dof / dim * dim] + static_cast<int>(en.dof % dim);
      (en.kind == mid_gradient ? G : en.kind == end_gradient ? G1 : Hdx)(i) += en.value;
      dx(i) = en.dx;
      x_mid(i) = en.x_mid;
    }
    // Their mesh dofs (the gradient and the tangent are kept in mesh dofs).
    for (auto& d : dofs) {
      const auto at_id = std::lower_bound(dof_ids.begin(), dof_ids.end(), d / dim);
      SEAM_ASSERT(at_id != dof_ids.end() && *at_id == d / dim);
      const auto node = dof_nodes[static_cast<std::size_t>(at_id - dof_ids.begin())];
      SEAM_ASSERT(node >= 0);
      d = static_cast<std::int64_t>(node) * dim + d % dim;
    }
    const DiscreteGradient dg =
        discrete_gradient(dim, invariance, dx, x_mid, gap_start, gap_end, G, G1, Hdx, tangent);
    if (trace && tangent && lambda[j] != 0.0)
      traced.push_back(
          {std::abs(lambda[j] * dg.ratio) *
               std::sqrt(dg.w_norm * dg.w_norm + 1e-6 * dg.dx_norm * dg.dx_norm),
           node_id(nodes[j]), lambda[j], dg.w_norm, dg.dx_norm, dg.N, gap_start, gap_end,
           static_cast<int>(n / dim), [&] {
             // The nodes of g~_j with |G| and |H dx| per node.
             std::string list;
             for (Eigen::Index a = 0; a < n / dim; ++a) {
               char item[120];
               std::snprintf(item, sizeof item, " %lld (|G| %.2e, |Hdx| %.2e)",
                             static_cast<long long>(dofs[static_cast<std::size_t>(a * dim)] / dim),
                             G.segment(a * dim, dim).norm(), Hdx.segment(a * dim, dim).norm());
               list += item;
             }
             return list;
           }()});
    for (Eigen::Index i = 0; i < n; ++i)
      if (dg.value(i) != 0.0)
        s.em_gradient.push_back({j, dofs[static_cast<std::size_t>(i)], -dg.value(i)});
    if (tangent && lambda[j] != 0.0)
      for (Eigen::Index k = 0; k < n; ++k)
        for (Eigen::Index i = 0; i < n; ++i)
          if (const double v = dg.correction_jacobian(i, k); v != 0.0)
            s.em_tangent.push_back({dofs[static_cast<std::size_t>(i)],
                                    dofs[static_cast<std::size_t>(k)], -lambda[j] * v});
    begin = stop;
  }
  if (trace && tangent) {
    const std::size_t n = std::min<std::size_t>(6, traced.size());
    std::partial_sort(traced.begin(), traced.begin() + static_cast<std::ptrdiff_t>(n), traced.end(),
                      [](auto& a, auto& b) { return a.force > b.force; });
    for (std::size_t k = 0; k < n; ++k) {
      const auto& e = traced[k];
      std::printf("  %s: correction of node %lld: lambda |N| / sqrt(den) %.3e, lambda %.4e, "
                  "|w| %.3e, |dx| %.3e, N %.3e, g~(x_n) %.3e, g~(x_n+1) %.3e, %d nodes:%s\n",
                  s.itf.name().c_str(), static_cast<long long>(e.node), e.force, e.lambda, e.w,
                  e.dx, e.N, e.g0, e.g1, e.nodes, e.list.c_str());
    }
  }
}

} // namespace seam::problem
