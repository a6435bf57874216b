#include "seam/fluid/navier_stokes.hpp"

#include "seam/common/error.hpp"

#include <array>
#include <cmath>

namespace seam::fluid {

namespace {

constexpr int max_nodes = fem::max_cell_nodes;
constexpr int max_dofs = max_nodes * 3 + 8;

// The quantities of one quadrature point: shape functions, their physical gradients, the
// weight times det J, the physical point.
struct Point {
  std::array<double, max_nodes> N;
  std::array<double, max_nodes * 3> G; // dN_a/dx_i at [a * dim + i]
  std::array<double, 8> M;             // pressure shape functions
  std::array<double, 3> x;
  double weight;
};

// Geometry at reference point xi; false if det J <= 0.
bool evaluate(const FluidElementInput& in, const double* xi, double w, Point& q) {
  const int dim = in.dim;
  const int n = fem::n_nodes(in.cell);
  std::array<double, max_nodes * 3> dN;
  fem::shape_values(in.cell, xi, q.N.data());
  fem::shape_gradients(in.cell, xi, dN.data());
  fem::shape_values(pressure_cell(in.cell), xi, q.M.data());
  std::array<double, 9> J{}, Jinv{};
  q.x = {0.0, 0.0, 0.0};
  for (int a = 0; a < n; ++a)
    for (int i = 0; i < dim; ++i) {
      q.x[i] += q.N[a] * in.x[a * dim + i];
      for (int b = 0; b < dim; ++b) J[i * dim + b] += in.x[a * dim + i] * dN[a * dim + b];
    }
  double det;
  if (dim == 2) {
    det = J[0] * J[3] - J[1] * J[2];
    Jinv = {J[3] / det, -J[1] / det, -J[2] / det, J[0] / det};
  } else {
    const auto c = [&](int r, int s) { return J[r * 3 + s]; };
    det = c(0, 0) * (c(1, 1) * c(2, 2) - c(1, 2) * c(2, 1)) -
          c(0, 1) * (c(1, 0) * c(2, 2) - c(1, 2) * c(2, 0)) +
          c(0, 2) * (c(1, 0) * c(2, 1) - c(1, 1) * c(2, 0));
    for (int r = 0; r < 3; ++r)
      for (int s = 0; s < 3; ++s) {
        // inverse = adjugate / det: cofactor of (s, r)
        const int r1 = (s + 1) % 3, r2 = (s + 2) % 3, s1 = (r + 1) % 3, s2 = (r + 2) % 3;
        Jinv[r * 3 + s] = (c(r1, s1) * c(r2, s2) - c(r1, s2) * c(r2, s1)) / det;
      }
  }
  if (!(det > 0.0)) return false;
  // dN_a/dx_i = dN_a/dxi_b dxi_b/dx_i
  for (int a = 0; a < n; ++a)
    for (int i = 0; i < dim; ++i) {
      double g = 0.0;
      for (int b = 0; b < dim; ++b) g += dN[a * dim + b] * Jinv[b * dim + i];
      q.G[a * dim + i] = g;
    }
  q.weight = w * det;
  return true;
}

// Velocity, its gradient grad_u[i * dim + j] = du_i/dx_j and the pressure at a point.
void interpolate(const FluidElementInput& in, const Point& q, double* u, double* grad_u,
                 double& p) {
  const int dim = in.dim;
  const int n = fem::n_nodes(in.cell);
  for (int i = 0; i < dim; ++i) {
    u[i] = 0.0;
    for (int j = 0; j < dim; ++j) grad_u[i * dim + j] = 0.0;
  }
  for (int a = 0; a < n; ++a)
    for (int i = 0; i < dim; ++i) {
      const double ua = in.u[a * dim + i];
      u[i] += q.N[a] * ua;
      for (int j = 0; j < dim; ++j) grad_u[i * dim + j] += ua * q.G[a * dim + j];
    }
  p = 0.0;
  for (int k = 0; k < fem::n_vertices(in.cell); ++k) p += q.M[k] * in.p[k];
}

// Residual-based stabilization of equal-order linear cells (PSPG, SUPG, LSIC; Tezduyar 1991,
// Whiting & Jansen 2001), added at one quadrature point. The strong momentum residual
// R = rho Du/Dt + grad p - f (the viscous term vanishes on linear cells up to their
// bilinear part, neglected as usual) tests against tau_M (rho u . grad N_a) and -tau_M grad
// M_k, div u against tau_C div N_a, with
//   tau_M = ((2 rho / dt)^2 + (2 rho |u| / h)^2 + (12 mu / h^2)^2)^(-1/2),  tau_C = h^2 / (8 tau_M)
// (dt = 0 for steady flow); the derivatives of tau by u are in K, so Newton stays exact.
struct Stabilization {
  double h = 0.0;  // cell size: diameter of the circle (sphere) of the cell's area (volume)
  double dt = 0.0; // 0: steady
};

// `u` is the convective velocity c = u - w (ALE): the SUPG direction and tau's |c|.
void add_stabilization(const FluidElementInput& in, const Stabilization& st, const Point& q,
                       const double* u, const double* grad_u, const double* material,
                       const double* f, std::span<double> r, std::span<double> K) {
  const int dim = in.dim;
  const int n = fem::n_nodes(in.cell);
  const int nu = n * dim;
  const int nd = nu + n;
  const double rho = in.fluid.density, mu = in.fluid.viscosity, w = q.weight;
  const double cw = in.state_weight;
  std::array<double, 3> R{};
  double uu = 0.0, div = 0.0;
  for (int i = 0; i < dim; ++i) {
    double grad_p = 0.0;
    for (int k = 0; k < n; ++k) grad_p += in.p[k] * q.G[k * dim + i];
    R[i] = rho * material[i] + grad_p - f[i];
    uu += u[i] * u[i];
    div += grad_u[i * dim + i];
  }
  const double A = st.dt > 0.0 ? std::pow(2.0 * rho / st.dt, 2) : 0.0;
  const double B = std::pow(2.0 * rho / st.h, 2);
  const double C = std::pow(12.0 * mu / (st.h * st.h), 2);
  const double tau = 1.0 / std::sqrt(A + B * uu + C);
  const double tau_c = st.h * st.h / (8.0 * tau);
  std::array<double, max_nodes> uG{};
  for (int a = 0; a < n; ++a)
    for (int j = 0; j < dim; ++j) uG[a] += u[j] * q.G[a * dim + j];
  for (int a = 0; a < n; ++a)
    for (int i = 0; i < dim; ++i)
      r[a * dim + i] += w * (tau * rho * uG[a] * R[i] + tau_c * q.G[a * dim + i] * div);
  for (int k = 0; k < n; ++k) {
    double GR = 0.0;
    for (int i = 0; i < dim; ++i) GR += q.G[k * dim + i] * R[i];
    r[nu + k] -= w * tau * GR;
  }
  if (K.empty()) return;
  // Derivatives by the unknown velocity u_{b j} and pressure p_l.
  for (int b = 0; b < n; ++b) {
    const double Nb = q.N[b];
    const double* Gb = &q.G[b * dim];
    for (int j = 0; j < dim; ++j) {
      const double dtau = -cw * tau * tau * tau * B * u[j] * Nb;
      const double dtau_c = -tau_c / tau * dtau;
      // dR_i / du_{b j}
      std::array<double, 3> dR{};
      for (int i = 0; i < dim; ++i)
        dR[i] = cw * rho * Nb * grad_u[i * dim + j] + (i == j ? cw * rho * uG[b] : 0.0) +
                (i == j ? in.mass_weight * rho * Nb : 0.0);
      const int col = b * dim + j;
      for (int a = 0; a < n; ++a) {
        const double* Ga = &q.G[a * dim];
        const double duG = cw * Nb * Ga[j];
        for (int i = 0; i < dim; ++i)
          K[(a * dim + i) * nd + col] +=
              w * (rho * (dtau * uG[a] * R[i] + tau * duG * R[i] + tau * uG[a] * dR[i]) +
                   dtau_c * Ga[i] * div + tau_c * Ga[i] * cw * Gb[j]);
      }
      for (int k = 0; k < n; ++k) {
        double GR = 0.0, GdR = 0.0;
        for (int i = 0; i < dim; ++i) {
          GR += q.G[k * dim + i] * R[i];
          GdR += q.G[k * dim + i] * dR[i];
        }
        K[(nu + k) * nd + col] -= w * (dtau * GR + tau * GdR);
      }
    }
  }
  for (int l = 0; l < n; ++l) {
    const double* Gl = &q.G[l * dim];
    for (int a = 0; a < n; ++a)
      for (int i = 0; i < dim; ++i)
        K[(a * dim + i) * nd + nu + l] += w * tau * rho * uG[a] * cw * Gl[i];
    for (int k = 0; k < n; ++k) {
      double GG = 0.0;
      for (int i = 0; i < dim; ++i) GG += q.G[k * dim + i] * Gl[i];
      K[(nu + k) * nd + nu + l] -= w * tau * cw * GG;
    }
  }
}

} // namespace

bool is_taylor_hood(fem::CellType cell) {
  using fem::CellType;
  return cell == CellType::tri6 || cell == CellType::quad9 || cell == CellType::tet10 ||
         cell == CellType::hex27;
}

bool is_stabilized(fem::CellType cell) {
  using fem::CellType;
  return cell == CellType::tri3 || cell == CellType::quad4 || cell == CellType::tet4 ||
         cell == CellType::hex8;
}

fem::CellType pressure_cell(fem::CellType velocity_cell) {
  using fem::CellType;
  switch (velocity_cell) {
  case CellType::tri6:
    return CellType::tri3;
  case CellType::quad9:
    return CellType::quad4;
  case CellType::tet10:
    return CellType::tet4;
  case CellType::hex27:
    return CellType::hex8;
  case CellType::tri3:
  case CellType::quad4:
  case CellType::tet4:
  case CellType::hex8:
    return velocity_cell; // equal order
  default:
    SEAM_THROW(InputError, "cell type ", fem::name(velocity_cell),
               " is not a fluid cell of seam (tri3, quad4, tet4, hex8 stabilized; tri6, quad9, "
               "tet10, hex27 Taylor-Hood)");
  }
}

int n_element_dofs(fem::CellType cell) {
  return fem::n_nodes(cell) * fem::dimension(cell) + fem::n_vertices(cell);
}

bool navier_stokes(const FluidElementInput& in, std::span<double> r, std::span<double> K) {
  const int dim = in.dim;
  const int n = fem::n_nodes(in.cell);
  const int nv = fem::n_vertices(in.cell);
  const int nu = n * dim;
  const int nd = nu + nv;
  SEAM_ASSERT(static_cast<int>(r.size()) == nd &&
              (K.empty() || static_cast<int>(K.size()) == nd * nd));
  SEAM_ASSERT(nd <= max_dofs);
  std::fill(r.begin(), r.end(), 0.0);
  std::fill(K.begin(), K.end(), 0.0);
  const double rho = in.fluid.density, mu = in.fluid.viscosity;
  // N_a u grad u is of degree 3 order (per direction on tensor cells, total on simplices).
  const auto rule = fem::quadrature(in.cell, 3 * fem::order(in.cell));
  Point q;
  const bool stabilized = is_stabilized(in.cell);
  Stabilization st;
  if (stabilized) {
    double volume = 0.0;
    for (int iq = 0; iq < rule.n_points; ++iq) {
      if (!evaluate(in, &rule.points[iq * dim], rule.weights[iq], q)) return false;
      volume += q.weight;
    }
    st.h = dim == 2 ? 2.0 * std::sqrt(volume / M_PI) : std::cbrt(6.0 * volume / M_PI);
    st.dt = in.time_step;
  }
  std::array<double, 3> u{}, c{}, f{}, material{};
  std::array<double, 9> grad_u{};
  std::array<double, max_nodes> c_G{};
  double p = 0.0;
  for (int iq = 0; iq < rule.n_points; ++iq) {
    if (!evaluate(in, &rule.points[iq * dim], rule.weights[iq], q)) return false;
    interpolate(in, q, u.data(), grad_u.data(), p);
    // The convective velocity c = u - w (ALE; w = 0 on a fixed mesh).
    c = u;
    if (!in.mesh_velocity.empty())
      for (int a = 0; a < n; ++a)
        for (int i = 0; i < dim; ++i) c[i] -= q.N[a] * in.mesh_velocity[a * dim + i];
    f = {0.0, 0.0, 0.0};
    if (in.body_force) (*in.body_force)(q.x.data(), f.data());
    double div = 0.0;
    for (int i = 0; i < dim; ++i) {
      div += grad_u[i * dim + i];
      material[i] = 0.0;
      for (int j = 0; j < dim; ++j) material[i] += c[j] * grad_u[i * dim + j];
    }
    if (!in.u_dot.empty())
      for (int a = 0; a < n; ++a)
        for (int i = 0; i < dim; ++i) material[i] += q.N[a] * in.u_dot[a * dim + i];
    const double w = q.weight;
    for (int a = 0; a < n; ++a) {
      const double* Ga = &q.G[a * dim];
      for (int i = 0; i < dim; ++i) {
        double visc = 0.0;
        for (int j = 0; j < dim; ++j) visc += Ga[j] * grad_u[i * dim + j];
        r[a * dim + i] += w * (rho * q.N[a] * material[i] + mu * visc - p * Ga[i] - q.N[a] * f[i]);
      }
    }
    for (int k = 0; k < nv; ++k) r[nu + k] -= w * q.M[k] * div;
    if (stabilized)
      add_stabilization(in, st, q, c.data(), grad_u.data(), material.data(), f.data(), r, K);
    if (K.empty()) continue;
    for (int b = 0; b < n; ++b) {
      double s = 0.0;
      for (int j = 0; j < dim; ++j) s += c[j] * q.G[b * dim + j];
      c_G[b] = s;
    }
    // material = Du/Dt with dc/du = du/du (w does not depend on u). Every column carries
    // state_weight, the velocity block the mass term.
    const double cw = in.state_weight;
    for (int a = 0; a < n; ++a) {
      const double* Ga = &q.G[a * dim];
      const double rNa = rho * q.N[a] * w;
      for (int b = 0; b < n; ++b) {
        const double* Gb = &q.G[b * dim];
        double GaGb = 0.0;
        for (int j = 0; j < dim; ++j) GaGb += Ga[j] * Gb[j];
        const double diag = cw * (w * mu * GaGb + rNa * c_G[b]) + in.mass_weight * rNa * q.N[b];
        for (int i = 0; i < dim; ++i) {
          double* row = &K[(a * dim + i) * nd + b * dim];
          for (int j = 0; j < dim; ++j) row[j] += cw * rNa * q.N[b] * grad_u[i * dim + j];
          row[i] += diag;
        }
      }
      for (int k = 0; k < nv; ++k) {
        const double wM = w * q.M[k];
        for (int i = 0; i < dim; ++i) {
          K[(a * dim + i) * nd + nu + k] -= cw * wM * Ga[i];
          K[(nu + k) * nd + a * dim + i] -= cw * wM * Ga[i];
        }
      }
    }
  }
  return true;
}

std::array<double, 4> error_integrals(const FluidElementInput& in, const ExactVelocity& u_exact,
                                      const ExactPressure& p_exact) {
  const int dim = in.dim;
  const auto rule = fem::quadrature(in.cell, 3 * fem::order(in.cell) + 2);
  std::array<double, 4> out{};
  Point q;
  std::array<double, 3> u{}, ue{};
  std::array<double, 9> grad_u{};
  double p = 0.0;
  for (int iq = 0; iq < rule.n_points; ++iq) {
    if (!evaluate(in, &rule.points[iq * dim], rule.weights[iq], q)) continue;
    interpolate(in, q, u.data(), grad_u.data(), p);
    ue = {0.0, 0.0, 0.0};
    if (u_exact) u_exact(q.x.data(), ue.data());
    double e2 = 0.0;
    for (int i = 0; i < dim; ++i) e2 += (u[i] - ue[i]) * (u[i] - ue[i]);
    const double ep = p_exact ? p - p_exact(q.x.data()) : 0.0;
    out[0] += q.weight * e2;
    out[1] += q.weight * ep * ep;
    out[2] += q.weight * ep;
    out[3] += q.weight;
  }
  return out;
}

} // namespace seam::fluid
