// Friction in energy-momentum contact (docs/contact_dynamics.md §5, "Friction"): two bodies,
// self contact and rigid obstacles with line2 or line3 (2D) or tri3, quad4, tri6, quad8 or
// quad9 (3D) faces.
//
// The Cartesian multiplier lambda_j of slave node j splits along the averaged normal n_j of
// x_{n+1} into lambda_n,j = n_j . lambda_j and lambda_t,j = P_j lambda_j (P_j = I - n_j n_j^T).
// The normal part takes the discrete-gradient force -lambda_n,j grad_d g~_j(x_n, x_{n+1}). With
// the mean mortar operators of the step, D = (D^n + D^{n+1}) / 2, M = (M^n + M^{n+1}) / 2 (those
// of the last converged step fixed in the step), and G_j(y) = sum_k D_jk y_k - sum_l M_jl y_l,
// the frictional condition (contact/friction.hpp) uses the slip increment
//   u~_j = G_j(dx) - theta_j x G_j(x_mid),   dx = x_{n+1} - x_n,
// theta_j the least-squares rotation of the slave nodes around j (its normal ring) in the step,
// so that no rigid motion slips. The tangential force is its work conjugate: the mortar force of
// lambda_t,j (slave k: D_jk lambda_t,j, master l: -M_jl lambda_t,j), whose moment about the
// midpoint is G_j(x_mid) x lambda_t,j, and the couple -Omega_j x y_b on the ring (y_b about its
// centroid), Omega_j = J_j^-1 (G_j(x_mid) x lambda_t,j), whose moment is the opposite. Then
//   f_c . dx = -sum_j lambda_n,j (g~_j(x_{n+1}) - g~_j(x_n)) + sum_j lambda_t,j . u~_j:
// in persistent contact the step's energy changes by exactly minus the frictional work (the
// dissipation of interfaces.csv, >= 0 by the condition: lambda_t,j is parallel to P_j u~_j in
// slip, P_j u~_j = 0 in stick), and the force has neither resultant (equal row sums of D and M;
// the couple) nor moment: linear and angular momentum are exact.
// Against a rigid obstacle (M = 0) the obstacle is the frame: u~_j = G_j(dx) - (sum_k D_jk) dc
// with dc the obstacle's displacement in the step, no rotation taken out and no couple; the
// energy statement is the same, and the frictional force changes the momenta as it should.
// With the modified dual basis of tri6/quad8 faces D_jj weighs the positions of that basis,
// x~ = T^-1 x (the basis the weighted gaps are taken in): the slave part of G_j is
// D_jj (T^-1 y)_j and the force D_jj lambda_t,j acts on node m by (T^-1)_jm. T is constant and
// the rows of T^-1 sum to one, so all of the above holds unchanged.
#include "seam/problem/contact_constraint.hpp"

#include "seam/parallel/exchange.hpp"

#include <Eigen/Dense>

#include <map>

namespace seam::problem {

namespace {

/// The step's rigid rotation of the slave nodes around node j (its normal ring): y_b the
/// midpoint positions about their centroid, dx_b the increments, J = sum_b (|y_b|^2 I -
/// y_b y_b^T) and theta = J^-1 sum_b y_b x dx_b, the least-squares rotation (about z only in 2D).
struct Ring {
  std::vector<std::int32_t> nodes;
  std::vector<Eigen::Vector3d> y, dx;
  Eigen::Matrix3d J_inv = Eigen::Matrix3d::Zero();
  Eigen::Vector3d theta = Eigen::Vector3d::Zero();
};

Eigen::Vector3d vector3(const double* v, int dim) {
  Eigen::Vector3d out = Eigen::Vector3d::Zero();
  for (int c = 0; c < dim; ++c) out(c) = v[c];
  return out;
}

Ring ring_of(const contact::ContactInterface& itf, std::size_t j, int dim,
             std::span<const double> X, std::span<const double> u, std::span<const double> u0) {
  Ring r;
  const auto j_local = static_cast<local_index>(j);
  for (const auto k : itf.normal_ring(std::span<const local_index>(&j_local, 1)))
    r.nodes.push_back(itf.slave().mesh_nodes[static_cast<std::size_t>(k)]);
  auto& dx = r.dx;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto node : r.nodes) {
    Eigen::Vector3d x = Eigen::Vector3d::Zero(), d = Eigen::Vector3d::Zero();
    for (int c = 0; c < dim; ++c) {
      const auto i = static_cast<std::size_t>(node) * dim + c;
      x(c) = X[i] + 0.5 * (u[i] + u0[i]);
      d(c) = u[i] - u0[i];
    }
    r.y.push_back(x);
    dx.push_back(d);
    centre += x / static_cast<double>(r.nodes.size());
  }
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  Eigen::Vector3d h = Eigen::Vector3d::Zero();
  for (std::size_t b = 0; b < r.y.size(); ++b) {
    r.y[b] -= centre;
    J += r.y[b].squaredNorm() * Eigen::Matrix3d::Identity() - r.y[b] * r.y[b].transpose();
    h += r.y[b].cross(dx[b]);
  }
  if (dim == 2)
    r.J_inv(2, 2) = 1.0 / J(2, 2);
  else
    r.J_inv = J.inverse();
  r.theta = r.J_inv * h;
  return r;
}

} // namespace

std::vector<double> ContactConstraint::normal_multipliers(const Side& s) const {
  if (!s.friction) return s.lambda;
  const int dim = disc_.dim();
  const auto n = s.lambda.size() / static_cast<std::size_t>(dim);
  const auto& normals = s.itf.normals();
  std::vector<double> out(n, 0.0);
  for (std::size_t j = 0; j < n; ++j)
    for (int c = 0; c < dim; ++c) out[j] += s.lambda[j * dim + c] * normals[j * dim + c];
  return out;
}

std::vector<double> ContactConstraint::tangential_multipliers(const Side& s) const {
  const int dim = disc_.dim();
  const auto lambda_n = normal_multipliers(s);
  const auto& normals = s.itf.normals();
  std::vector<double> out(s.lambda.size());
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = s.lambda[i] - lambda_n[i / dim] * normals[i];
  return out;
}

void ContactConstraint::for_each_mean_operator(
    const Side& s, const std::function<void(std::size_t, std::int32_t, double)>& visit) const {
  const auto& nodes = s.itf.slave().mesh_nodes;
  // With the modified basis of tri6/quad8 faces D_jj weighs x~_j = sum_m (T^-1)_jm x_m.
  const contact::InverseTransformationRows rows(s.itf.transformation_inverse(), nodes.size());
  const auto diagonal = [&](std::size_t j, double d) {
    if (d != 0.0) rows.visit(j, [&](std::size_t m, double t) { visit(j, nodes[m], 0.5 * d * t); });
  };
  for (std::size_t j = 0; j < nodes.size(); ++j) {
    diagonal(j, s.part.D[j]);
    if (s.node_owners[j] == disc_.comm().rank()) diagonal(j, s.D_diag_old[j]);
  }
  for (const auto* coupling : {&s.part.D_coupling, &s.D_coupling_old})
    for (const auto& e : *coupling)
      visit(static_cast<std::size_t>(e.row), nodes[static_cast<std::size_t>(e.col)], 0.5 * e.value);
  for (const auto* M : {&s.part.M, &s.M_old})
    for (const auto& e : *M)
      visit(static_cast<std::size_t>(e.slave), e.master_node, -0.5 * e.value);
}

void ContactConstraint::energy_momentum_slip(Side& s, std::span<const double> u_mesh) const {
  const int dim = disc_.dim();
  // The operators "of the last converged step" before the first one has converged: those of
  // the first evaluation.
  if (!s.has_old) {
    s.D_diag_old = s.D_diag;
    s.D_coupling_old = s.part.D_coupling;
    s.M_old = s.part.M;
    s.has_old = true;
  }
  std::fill(s.slip.begin(), s.slip.end(), 0.0);
  for_each_mean_operator(s, [&](std::size_t j, std::int32_t node, double w) {
    for (int c = 0; c < dim; ++c) {
      const auto i = static_cast<std::size_t>(node) * dim + c;
      s.slip[j * dim + c] += w * (u_mesh[i] - u_mesh_start_[i]);
    }
  });
  parallel::sum_on_owners(disc_.comm().get(), s.node_keys, s.node_owners, s.slip, dim);
  if (s.itf.rigid()) {
    // Against a rigid obstacle the obstacle is the frame: u~_j = sum_k D_jk (dx_k - dc) with
    // dc the obstacle's displacement in the step, and no rotation is taken out (a body turning
    // on the obstacle slips on it). No couple: G_j(x_mid) is set to zero.
    const auto obstacle = s.itf.plane_displacement();
    std::vector<double> weight(s.node_owners.size(), 0.0);
    for_each_mean_operator(s, [&](std::size_t j, std::int32_t, double w) { weight[j] += w; });
    parallel::sum_on_owners(disc_.comm().get(), s.node_keys, s.node_owners, weight, 1);
    for (std::size_t j = 0; j < s.node_owners.size(); ++j)
      if (s.node_owners[j] == disc_.comm().rank())
        for (int c = 0; c < dim; ++c)
          s.slip[j * dim + c] -= weight[j] * (obstacle[static_cast<std::size_t>(c)] -
                                              s.plane_old[static_cast<std::size_t>(c)]);
    s.em_gap_mid.assign(s.slip.size(), 0.0);
    return;
  }
  // Frame indifference: u~_j - theta_j x G_j(x_mid), theta_j the step's rotation of the nodes
  // around j. A rigid rotation then slips nowhere, and the work conjugate force (the mortar
  // force of lambda_t and the couple -Omega x y_b, add_energy_momentum_friction_force) has no
  // moment about the midpoint.
  const auto& X = reference_x_; // mesh and outside nodes
  std::vector<double> g(s.slip.size(), 0.0);
  for_each_mean_operator(s, [&](std::size_t j, std::int32_t node, double w) {
    for (int c = 0; c < dim; ++c) {
      const auto i = static_cast<std::size_t>(node) * dim + c;
      g[j * dim + c] += w * (X[i] + 0.5 * (u_mesh[i] + u_mesh_start_[i]));
    }
  });
  parallel::sum_on_owners(disc_.comm().get(), s.node_keys, s.node_owners, g, dim);
  for (std::size_t j = 0; j < s.node_owners.size(); ++j) {
    if (s.node_owners[j] != disc_.comm().rank()) continue;
    const Eigen::Vector3d G = vector3(&g[j * dim], dim);
    if (G.isZero(0.0)) continue;
    const Eigen::Vector3d correction =
        ring_of(s.itf, j, dim, X, u_mesh, u_mesh_start_).theta.cross(G);
    for (int c = 0; c < dim; ++c) s.slip[j * dim + c] -= correction(c);
  }
  publish(s, g, dim);
  s.em_gap_mid = std::move(g);
}

void ContactConstraint::add_energy_momentum_friction_force(const Side& s,
                                                           std::span<double> f) const {
  const int dim = disc_.dim();
  const auto lambda_t = tangential_multipliers(s);
  for_each_mean_operator(s, [&](std::size_t j, std::int32_t node, double w) {
    for (int c = 0; c < dim; ++c)
      f[static_cast<std::size_t>(node) * dim + c] += w * lambda_t[j * dim + c];
  });
  // The couple on the ring of j: -Omega_j x y_b with Omega_j = J^-1 (G_j(x_mid) x lambda_t,j).
  for (std::size_t j = 0; j < s.node_owners.size(); ++j) {
    if (s.node_owners[j] != disc_.comm().rank()) continue;
    const Eigen::Vector3d G = vector3(&s.em_gap_mid[j * dim], dim);
    const Eigen::Vector3d lt = vector3(&lambda_t[j * dim], dim);
    if (G.isZero(0.0) || lt.isZero(0.0)) continue;
    const Ring r = ring_of(s.itf, j, dim, reference_x_, s.em_displacement, u_mesh_start_);
    const Eigen::Vector3d omega = r.J_inv * G.cross(lt);
    for (std::size_t b = 0; b < r.nodes.size(); ++b) {
      const Eigen::Vector3d fb = -omega.cross(r.y[b]);
      for (int c = 0; c < dim; ++c) f[static_cast<std::size_t>(r.nodes[b]) * dim + c] += fb(c);
    }
  }
}

void ContactConstraint::energy_momentum_friction_tangent(Side& s) {
  const int dim = disc_.dim();
  const auto& normals = s.itf.normals();
  const auto lambda_n = normal_multipliers(s);
  const auto lambda_t = tangential_multipliers(s);
  // The operators' part (D^{n+1} and M^{n+1} enter the mean by half): d(D) lambda_t and
  // -d(M) lambda_t at fixed lambda_t, and for the friction rows of the active nodes the
  // derivative of D_j and of the operators in u~ (contracted with dx).
  contact::Linearization lin;
  s.itf.linearize(lambda_t, s.active, lin, u_mesh_start_);
  for (auto& e : lin.force_tangent) s.em_tangent.push_back({e.row, e.col, 0.5 * e.value});
  for (auto& e : lin.operator_gradient) e.value *= 0.5;
  s.lin.D_gradient = std::move(lin.D_gradient);
  s.lin.operator_gradient = std::move(lin.operator_gradient);
  // The turning normal: d lambda_n,j = q_j . dx with q_j = lambda_j^T dn_j/dx, and
  // d lambda_t,j = -n_j (q_j . dx) - lambda_n,j dn_j/dx dx. Per node j with a multiplier, its
  // q_j and dn_j (column mesh dof -> dim values).
  struct Turning {
    std::map<std::int64_t, double> q;
    std::map<std::int64_t, std::array<double, 3>> dn;
  };
  std::map<std::size_t, Turning> turning;
  std::vector<contact::DofTriplet> entries;
  const auto of = [&](std::size_t j) -> const Turning& {
    auto it = turning.find(j);
    if (it != turning.end()) return it->second;
    Turning t;
    entries.clear();
    s.itf.normal_jacobian(static_cast<local_index>(j), entries);
    for (const auto& e : entries) {
      t.q[e.col] += s.lambda[j * dim + static_cast<std::size_t>(e.row)] * e.value;
      auto& d = t.dn.try_emplace(e.col, std::array<double, 3>{0, 0, 0}).first->second;
      d[static_cast<std::size_t>(e.row)] += e.value;
    }
    return turning.emplace(j, std::move(t)).first->second;
  };
  const auto carries = [&](std::size_t j) {
    for (int c = 0; c < dim; ++c)
      if (s.lambda[j * dim + c] != 0.0) return true;
    return false;
  };
  // -grad_d g~_j (this rank's owned nodes) times d lambda_n,j.
  for (const auto& e : s.em_gradient) {
    if (!carries(e.j)) continue;
    for (const auto& [col, q] : of(e.j).q)
      if (q != 0.0) s.em_tangent.push_back({e.dof, col, e.value * q});
  }
  // weight * d lambda_t,j on the rows of mesh node `node`.
  const auto add_turning = [&](std::size_t j, std::int32_t node, double weight) {
    if (weight == 0.0 || !carries(j)) return;
    const Turning& t = of(j);
    const double* n = &normals[j * dim];
    for (const auto& [col, dn] : t.dn) {
      const double q = t.q.at(col);
      for (int c = 0; c < dim; ++c) {
        const double v = weight * (-n[c] * q - lambda_n[j] * dn[static_cast<std::size_t>(c)]);
        if (v != 0.0) s.em_tangent.push_back({static_cast<std::int64_t>(node) * dim + c, col, v});
      }
    }
  };
  for_each_mean_operator(s, add_turning);
  // Against a rigid obstacle there is no frame-indifference correction (energy_momentum_slip).
  if (s.itf.rigid()) return;

  // The frame-indifference correction (energy_momentum_slip): u~_j -= theta_j x G_j and the
  // couple -Omega_j x y_b on the ring of j, Omega_j = J^-1 (G_j x lambda_t,j).
  const auto& X = reference_x_; // mesh and outside nodes
  const std::span<const double> u = s.em_displacement;
  std::map<std::size_t, Ring> rings;
  const auto ring = [&](std::size_t j) -> const Ring& {
    auto it = rings.find(j);
    if (it == rings.end()) it = rings.emplace(j, ring_of(s.itf, j, dim, X, u, u_mesh_start_)).first;
    return it->second;
  };
  const auto push = [&](std::vector<contact::DofTriplet>& to, std::int64_t row0,
                        const Eigen::Vector3d& v, std::int64_t col) {
    for (int c = 0; c < dim; ++c)
      if (v(c) != 0.0) to.push_back({row0 + c, col, v(c)});
  };
  const auto gap_mid = [&](std::size_t j) { return vector3(&s.em_gap_mid[j * dim], dim); };
  std::vector<char> wanted(s.active.size(), 0);
  for (std::size_t j = 0; j < wanted.size(); ++j) wanted[j] = s.active[j] || carries(j);
  // dG_j / dx_{n+1}: the mean operators at fixed positions times half the midpoint's motion,
  // and the derivative of the operators of x_{n+1} (half) contracted with x_mid.
  std::vector<double> to_mid(u.size());
  for (std::size_t i = 0; i < u.size(); ++i) to_mid[i] = 0.5 * (u[i] - u_mesh_start_[i]) - X[i];
  contact::Linearization at_mid;
  s.itf.linearize(lambda_t, wanted, at_mid, to_mid);
  std::vector<contact::DofTriplet> dG;
  for (const auto& e : at_mid.operator_gradient) dG.push_back({e.row, e.col, 0.5 * e.value});
  for_each_mean_operator(s, [&](std::size_t j, std::int32_t node, double w) {
    if (!wanted[j]) return;
    for (int a = 0; a < dim; ++a)
      dG.push_back({static_cast<std::int64_t>(j) * dim + a,
                    static_cast<std::int64_t>(node) * dim + a, 0.5 * w});
  });
  for (const auto& e : dG) {
    const auto j = static_cast<std::size_t>(e.row / dim);
    if (gap_mid(j).isZero(0.0)) continue;
    Eigen::Vector3d dg = Eigen::Vector3d::Zero();
    dg(static_cast<int>(e.row % dim)) = e.value;
    const Ring& r = ring(j);
    if (s.active[j])
      push(s.lin.operator_gradient, static_cast<std::int64_t>(j) * dim, -r.theta.cross(dg), e.col);
    if (!carries(j)) continue;
    const Eigen::Vector3d omega = r.J_inv * dg.cross(vector3(&lambda_t[j * dim], dim));
    for (std::size_t b = 0; b < r.nodes.size(); ++b)
      push(s.em_tangent, static_cast<std::int64_t>(r.nodes[b]) * dim, -omega.cross(r.y[b]), e.col);
  }
  // Through the ring's positions (theta, J, y_b) and the turning normal in lambda_t, on the
  // owner of j.
  for (std::size_t j = 0; j < wanted.size(); ++j) {
    if (!wanted[j] || s.node_owners[j] != disc_.comm().rank()) continue;
    const Eigen::Vector3d G = gap_mid(j);
    if (G.isZero(0.0)) continue;
    const Ring& r = ring(j);
    const Eigen::Vector3d lt = vector3(&lambda_t[j * dim], dim);
    const Eigen::Vector3d omega = r.J_inv * G.cross(lt);
    const auto n_ring = r.nodes.size();
    // dJ v for the motion dy_b of the midpoint positions.
    const auto dJ = [&](const std::vector<Eigen::Vector3d>& dy, const Eigen::Vector3d& v) {
      Eigen::Vector3d out = Eigen::Vector3d::Zero();
      for (std::size_t b = 0; b < n_ring; ++b)
        out += 2.0 * r.y[b].dot(dy[b]) * v - dy[b] * r.y[b].dot(v) - r.y[b] * dy[b].dot(v);
      return out;
    };
    std::vector<Eigen::Vector3d> dy(n_ring);
    for (std::size_t e = 0; e < n_ring; ++e)
      for (int q = 0; q < dim; ++q) {
        const auto col = static_cast<std::int64_t>(r.nodes[e]) * dim + q;
        // x_{n+1} of ring node e along q: dy_b = (delta_be - 1/N) e_q / 2, d dx_b = delta_be e_q.
        Eigen::Vector3d dh = Eigen::Vector3d::Zero(), eq = Eigen::Vector3d::Zero();
        eq(q) = 1.0;
        for (std::size_t b = 0; b < n_ring; ++b) {
          dy[b] = 0.5 * ((b == e ? 1.0 : 0.0) - 1.0 / static_cast<double>(n_ring)) * eq;
          dh += dy[b].cross(r.dx[b]);
        }
        dh += r.y[e].cross(eq);
        if (s.active[j]) {
          const Eigen::Vector3d dtheta = r.J_inv * (dh - dJ(dy, r.theta));
          push(s.lin.operator_gradient, static_cast<std::int64_t>(j) * dim, -dtheta.cross(G), col);
        }
        if (lt.isZero(0.0)) continue;
        const Eigen::Vector3d domega = -(r.J_inv * dJ(dy, omega));
        for (std::size_t b = 0; b < n_ring; ++b)
          push(s.em_tangent, static_cast<std::int64_t>(r.nodes[b]) * dim,
               -(domega.cross(r.y[b]) + omega.cross(dy[b])), col);
      }
    if (!carries(j)) continue;
    const Turning& t = of(j);
    const Eigen::Vector3d n = vector3(&normals[j * dim], dim);
    for (const auto& [col, dn] : t.dn) {
      const Eigen::Vector3d dlt = -n * t.q.at(col) - lambda_n[j] * vector3(dn.data(), dim);
      const Eigen::Vector3d domega = r.J_inv * G.cross(dlt);
      for (std::size_t b = 0; b < n_ring; ++b)
        push(s.em_tangent, static_cast<std::int64_t>(r.nodes[b]) * dim, -domega.cross(r.y[b]), col);
    }
  }
}

void ContactConstraint::energy_momentum_friction_columns(const Side& s, std::vector<PetscInt>& bi,
                                                         std::vector<PetscInt>& bj,
                                                         std::vector<double>& bv) const {
  const int dim = disc_.dim();
  const auto& normals = s.itf.normals();
  // Column (j, c): -n_j,c grad_d g~_j + the mean operators' force of P_j e_c.
  for (const auto& e : s.em_gradient)
    for (int c = 0; c < dim; ++c) {
      const double v = e.value * normals[e.j * dim + static_cast<std::size_t>(c)];
      if (v == 0.0) continue;
      bi.push_back(global_dof(e.dof));
      bj.push_back(s.lm_index[e.j] + c);
      bv.push_back(v);
    }
  const auto add = [&](std::size_t j, std::int32_t node, double weight) {
    if (weight == 0.0) return;
    const double* n = &normals[j * dim];
    for (int c = 0; c < dim; ++c)
      for (int a = 0; a < dim; ++a) {
        const double v = weight * ((a == c ? 1.0 : 0.0) - n[a] * n[c]);
        if (v == 0.0) continue;
        bi.push_back(dof_of(node, a));
        bj.push_back(s.lm_index[j] + c);
        bv.push_back(v);
      }
  };
  for_each_mean_operator(s, add);
  // The couple's column: Omega_j = J^-1 (G_j x P_j e_c).
  for (std::size_t j = 0; j < s.node_owners.size(); ++j) {
    if (s.node_owners[j] != disc_.comm().rank()) continue;
    const Eigen::Vector3d G = vector3(&s.em_gap_mid[j * dim], dim);
    if (G.isZero(0.0)) continue;
    const Ring r = ring_of(s.itf, j, dim, reference_x_, s.em_displacement, u_mesh_start_);
    const Eigen::Vector3d n = vector3(&normals[j * dim], dim);
    for (int c = 0; c < dim; ++c) {
      Eigen::Vector3d p = -n(c) * n;
      p(c) += 1.0;
      const Eigen::Vector3d omega = r.J_inv * G.cross(p);
      for (std::size_t b = 0; b < r.nodes.size(); ++b) {
        const Eigen::Vector3d fb = -omega.cross(r.y[b]);
        for (int a = 0; a < dim; ++a)
          if (fb(a) != 0.0) {
            bi.push_back(dof_of(r.nodes[b], a));
            bj.push_back(s.lm_index[j] + c);
            bv.push_back(fb(a));
          }
      }
    }
  }
}

} // namespace seam::problem
