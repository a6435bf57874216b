// Friction in energy-momentum contact (docs/contact_dynamics.md §5, "Friction"): two bodies
// and self contact with line2 (2D) or tri3/quad4 (3D) faces.
//
// The Cartesian multiplier lambda_j of slave node j splits along the averaged normal n_j of
// x_{n+1} into lambda_n,j = n_j . lambda_j and lambda_t,j = P_j lambda_j (P_j = I - n_j n_j^T).
// With the mean mortar operators of the step, D = (D^n + D^{n+1}) / 2 and M = (M^n + M^{n+1}) / 2
// (D^n, M^n those of the last converged step, fixed in the step), the contact force in the
// residual is
//   f_c = -sum_j lambda_n,j grad_d g~_j(x_n, x_{n+1})                 (the discrete gradient)
//         + sum_j (slave k: D_jk lambda_t,j,  master l: -M_jl lambda_t,j),
// and the frictional condition (contact/friction.hpp) uses the slip increment
//   u~_j = sum_k D_jk dx_k - sum_l M_jl dx_l,   dx = x_{n+1} - x_n.
// Then f_c . dx = -sum_j lambda_n,j (g~_j(x_{n+1}) - g~_j(x_n)) + sum_j lambda_t,j . u~_j: in
// persistent contact the step's energy changes by exactly minus the frictional work
// sum_j lambda_t,j . u~_j (interfaces.csv's dissipation), which the condition makes >= 0
// (lambda_t,j is parallel to P_j u~_j in slip, P_j u~_j = 0 in stick). The rows of D and M
// sum alike, so the force has no resultant: the linear momentum is exact. Its moment about the
// midpoint is G_j(x_mid) x lambda_t,j with G_j(y) = sum_k D_jk y_k - sum_l M_jl y_l, and
//   G_j(x_mid) = (G^n_j(x_n) + G^{n+1}_j(x_{n+1})) / 2 + (G^n_j - G^{n+1}_j)(dx) / 4:
// the weighted gap vectors of the two ends (zero normal part in persistent contact) and the
// change of the operators times the increment (second order in the step). With the operators of
// x_{n+1} alone the moment held -G^{n+1}_j(dx) / 2 x lambda_t,j instead, half the weighted slip
// against the traction: first order, and large where n_j is tilted against the motion (the
// averaged normals at the rims of extruded rings: 1.5e-3 of the angular momentum).
#include "seam/problem/contact_constraint.hpp"

#include "seam/parallel/exchange.hpp"

#include <map>

namespace seam::problem {

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
  for (std::size_t j = 0; j < nodes.size(); ++j) {
    if (s.part.D[j] != 0.0) visit(j, nodes[j], 0.5 * s.part.D[j]);
    if (s.D_diag_old[j] != 0.0 && s.node_owners[j] == disc_.comm().rank())
      visit(j, nodes[j], 0.5 * s.D_diag_old[j]);
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
}

void ContactConstraint::add_energy_momentum_friction_force(const Side& s,
                                                           std::span<double> f) const {
  const int dim = disc_.dim();
  const auto lambda_t = tangential_multipliers(s);
  for_each_mean_operator(s, [&](std::size_t j, std::int32_t node, double w) {
    for (int c = 0; c < dim; ++c)
      f[static_cast<std::size_t>(node) * dim + c] += w * lambda_t[j * dim + c];
  });
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
        bi.push_back(disc_.global_dof(node, a));
        bj.push_back(s.lm_index[j] + c);
        bv.push_back(v);
      }
  };
  for_each_mean_operator(s, add);
}

} // namespace seam::problem
