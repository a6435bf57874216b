// Friction in energy-momentum contact (docs/contact_dynamics.md §5, "Friction"): two bodies
// and self contact with line2 (2D) or tri3/quad4 (3D) faces.
//
// The Cartesian multiplier lambda_j of slave node j splits along the averaged normal n_j of
// x_{n+1} into lambda_n,j = n_j . lambda_j and lambda_t,j = P_j lambda_j (P_j = I - n_j n_j^T).
// The contact force in the residual is
//   f_c = -sum_j lambda_n,j grad_d g~_j(x_n, x_{n+1})                 (the discrete gradient)
//         + sum_j (slave k: D_jk lambda_t,j,  master l: -M_jl lambda_t,j)   (D, M of x_{n+1}),
// and the frictional condition (contact/friction.hpp) uses the slip increment
//   u~_j = sum_k D_jk dx_k - sum_l M_jl dx_l,   dx = x_{n+1} - x_n,
// the step's relative motion weighted by the same operators. Then f_c . dx =
// -sum_j lambda_n,j (g~_j(x_{n+1}) - g~_j(x_n)) + sum_j lambda_t,j . u~_j: in persistent
// contact the step's energy changes by exactly minus the frictional work sum_j lambda_t,j . u~_j
// (interfaces.csv's dissipation), which the condition makes >= 0 (lambda_t,j is parallel to
// P_j u~_j in slip, P_j u~_j = 0 in stick). The rows of D and M sum alike, so both parts are
// free of force: the linear momentum is exact. The tangential part's moment about any point
// is -sum_j G_j(x_mid) x lambda_t,j with G_j(y) = sum_k D_jk y_k - sum_l M_jl y_l; its
// tangential component is parallel to lambda_t,j up to the gap, so what remains is of the size
// of the weighted gap vector at the midpoint (zero for g~_j(x_mid) = 0 on flat faces).
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

void ContactConstraint::energy_momentum_slip(Side& s, std::span<const double> u_mesh) const {
  const int dim = disc_.dim();
  const auto& nodes = s.itf.slave().mesh_nodes;
  const auto dx = [&](std::int32_t node, int c) {
    const auto i = static_cast<std::size_t>(node) * dim + c;
    return u_mesh[i] - u_mesh_start_[i];
  };
  std::fill(s.slip.begin(), s.slip.end(), 0.0);
  // This rank's parts of D and M.
  for (std::size_t j = 0; j < nodes.size(); ++j)
    if (s.part.D[j] != 0.0)
      for (int c = 0; c < dim; ++c) s.slip[j * dim + c] += s.part.D[j] * dx(nodes[j], c);
  for (const auto& e : s.part.D_coupling)
    for (int c = 0; c < dim; ++c)
      s.slip[static_cast<std::size_t>(e.row) * dim + c] +=
          e.value * dx(nodes[static_cast<std::size_t>(e.col)], c);
  for (const auto& e : s.part.M)
    for (int c = 0; c < dim; ++c)
      s.slip[static_cast<std::size_t>(e.slave) * dim + c] -= e.value * dx(e.master_node, c);
  parallel::sum_on_owners(disc_.comm().get(), s.node_keys, s.node_owners, s.slip, dim);
}

void ContactConstraint::energy_momentum_friction_tangent(Side& s) {
  const int dim = disc_.dim();
  const auto& nodes = s.itf.slave().mesh_nodes;
  const auto& normals = s.itf.normals();
  const auto lambda_n = normal_multipliers(s);
  const auto lambda_t = tangential_multipliers(s);
  // The operators' part: d(D) lambda_t and -d(M) lambda_t at fixed lambda_t, with D_j and the
  // operators' derivative in u~ (contracted with dx) for the friction rows of active nodes.
  contact::Linearization lin;
  s.itf.linearize(lambda_t, s.active, lin, u_mesh_start_);
  s.em_tangent.insert(s.em_tangent.end(), lin.force_tangent.begin(), lin.force_tangent.end());
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
  for (std::size_t j = 0; j < nodes.size(); ++j) add_turning(j, nodes[j], s.part.D[j]);
  for (const auto& e : s.part.D_coupling)
    add_turning(static_cast<std::size_t>(e.row), nodes[static_cast<std::size_t>(e.col)], e.value);
  for (const auto& e : s.part.M)
    add_turning(static_cast<std::size_t>(e.slave), e.master_node, -e.value);
}

void ContactConstraint::energy_momentum_friction_columns(const Side& s, std::vector<PetscInt>& bi,
                                                         std::vector<PetscInt>& bj,
                                                         std::vector<double>& bv) const {
  const int dim = disc_.dim();
  const auto& nodes = s.itf.slave().mesh_nodes;
  const auto& normals = s.itf.normals();
  // Column (j, c): -n_j,c grad_d g~_j + the mortar force of P_j e_c.
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
  for (std::size_t j = 0; j < nodes.size(); ++j) add(j, nodes[j], s.part.D[j]);
  for (const auto& e : s.part.D_coupling)
    add(static_cast<std::size_t>(e.row), nodes[static_cast<std::size_t>(e.col)], e.value);
  for (const auto& e : s.part.M) add(static_cast<std::size_t>(e.slave), e.master_node, -e.value);
}

} // namespace seam::problem
