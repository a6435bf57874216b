#include "seam/fluid/navier_stokes.hpp"

#include "seam/common/dual_number.hpp"
#include "seam/common/error.hpp"
#include "seam/fluid/pressure_operators.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>

namespace seam::fluid {

namespace {

constexpr int max_nodes = fem::max_cell_nodes;
constexpr int max_dofs = max_nodes * 3 + 8;

// The kernel is written once on the scalar S of the mesh: S = double gives the residual and
// its Jacobian by (u, p); S = Dual<N> carries the derivatives of the residual by N of the
// node coordinates or mesh velocities (the shape derivatives of a moving mesh, needed where
// the mesh motion is an unknown, as in fluid-structure interaction).

// The quantities of one quadrature point: shape functions, their physical gradients, the
// weight times det J, the physical point.
template <class S> struct Point {
  std::array<double, max_nodes> N;
  std::array<S, max_nodes * 3> G; // dN_a/dx_i at [a * dim + i]
  std::array<double, 8> M;        // pressure shape functions
  std::array<S, 3> x;
  S weight;
};

// Geometry at reference point xi of the cell with nodes `x`; false if det J <= 0.
template <class S>
bool evaluate(const FluidElementInput& in, std::span<const S> x, const double* xi, double w,
              Point<S>& q) {
  const int dim = in.dim;
  const int n = fem::n_nodes(in.cell);
  std::array<double, max_nodes * 3> dN;
  fem::shape_values(in.cell, xi, q.N.data());
  fem::shape_gradients(in.cell, xi, dN.data());
  fem::shape_values(pressure_cell(in.cell), xi, q.M.data());
  std::array<S, 9> J, Jinv;
  J.fill(S(0.0));
  q.x.fill(S(0.0));
  for (int a = 0; a < n; ++a)
    for (int i = 0; i < dim; ++i) {
      add_product(q.x[i], x[a * dim + i], q.N[a]);
      for (int b = 0; b < dim; ++b) add_product(J[i * dim + b], x[a * dim + i], dN[a * dim + b]);
    }
  S det;
  if (dim == 2) {
    det = J[0] * J[3] - J[1] * J[2];
    Jinv = {J[3] / det, -J[1] / det, -J[2] / det, J[0] / det};
  } else {
    const auto c = [&](int r, int s) -> const S& { return J[r * 3 + s]; };
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
      S g(0.0);
      for (int b = 0; b < dim; ++b) add_product(g, Jinv[b * dim + i], dN[a * dim + b]);
      q.G[a * dim + i] = g;
    }
  q.weight = w * det;
  return true;
}

// Velocity, its gradient grad_u[i * dim + j] = du_i/dx_j and the pressure at a point.
template <class S>
void interpolate(const FluidElementInput& in, const Point<S>& q, S* u, S* grad_u, S& p) {
  const int dim = in.dim;
  const int n = fem::n_nodes(in.cell);
  for (int i = 0; i < dim; ++i) {
    u[i] = S(0.0);
    for (int j = 0; j < dim; ++j) grad_u[i * dim + j] = S(0.0);
  }
  for (int a = 0; a < n; ++a)
    for (int i = 0; i < dim; ++i) {
      const double ua = in.u[a * dim + i];
      u[i] += q.N[a] * ua;
      for (int j = 0; j < dim; ++j) add_product(grad_u[i * dim + j], q.G[a * dim + j], ua);
    }
  p = S(0.0);
  for (int k = 0; k < fem::n_vertices(in.cell); ++k) p += q.M[k] * in.p[k];
}

// The body force at the point x. The user's expression is evaluated on plain numbers; with
// dual coordinates its gradient comes from central differences of the expression (a smooth
// function of position), step 1e-6 of the point's size.
template <class S> void body_force(const FluidElementInput& in, const std::array<S, 3>& x, S* f) {
  std::array<double, 3> xv{}, fv{};
  for (int i = 0; i < in.dim; ++i) xv[static_cast<std::size_t>(i)] = value_of(x[i]);
  (*in.body_force)(xv.data(), fv.data());
  for (int i = 0; i < in.dim; ++i) f[i] = S(fv[static_cast<std::size_t>(i)]);
  if constexpr (is_dual<S>) {
    const double scale = std::max({1.0, std::abs(xv[0]), std::abs(xv[1]), std::abs(xv[2])});
    const double h = 1e-6 * scale;
    std::array<double, 3> fp{}, fm{};
    for (int j = 0; j < in.dim; ++j) {
      auto xp = xv, xm = xv;
      xp[static_cast<std::size_t>(j)] += h;
      xm[static_cast<std::size_t>(j)] -= h;
      (*in.body_force)(xp.data(), fp.data());
      (*in.body_force)(xm.data(), fm.data());
      for (int i = 0; i < in.dim; ++i) {
        const double d =
            (fp[static_cast<std::size_t>(i)] - fm[static_cast<std::size_t>(i)]) / (2.0 * h);
        for (int k = 0; k < S::n_variables; ++k) f[i].gradient[k] += d * x[j].gradient[k];
      }
    }
  }
}

// Residual-based stabilization of equal-order linear cells (PSPG, SUPG, LSIC; Tezduyar 1991,
// Whiting & Jansen 2001), added at one quadrature point. The strong momentum residual
// R = rho Du/Dt + grad p - f (the viscous term vanishes on linear cells up to their
// bilinear part, neglected as usual) tests against tau_M (rho u . grad N_a) and -tau_M grad
// M_k, div u against tau_C div N_a, with
//   tau_M = ((2 rho / dt)^2 + (2 rho |u| / h)^2 + (12 mu / h^2)^2)^(-1/2),  tau_C = h^2 / (8 tau_M)
// (dt = 0 for steady flow); the derivatives of tau by u are in K, so Newton stays exact.
template <class S> struct Stabilization {
  S h = S(0.0);    // cell size: diameter of the circle (sphere) of the cell's area (volume)
  double dt = 0.0; // 0: steady
};

// `u` is the convective velocity c = u - w (ALE): the SUPG direction and tau's |c|.
template <class S>
void add_stabilization(const FluidElementInput& in, const Stabilization<S>& st, const Point<S>& q,
                       const S* u, const S* grad_u, const S* material, const S* f, std::span<S> r,
                       std::span<double> K) {
  using std::sqrt;
  const int dim = in.dim;
  const int n = fem::n_nodes(in.cell);
  const int nu = n * dim;
  const double rho = in.fluid.density, mu = in.fluid.viscosity;
  const S& w = q.weight;
  std::array<S, 3> R;
  S uu(0.0), div(0.0);
  for (int i = 0; i < dim; ++i) {
    S grad_p(0.0);
    for (int k = 0; k < n; ++k) add_product(grad_p, q.G[k * dim + i], in.p[k]);
    R[i] = rho * material[i] + grad_p - f[i];
    uu += u[i] * u[i];
    div += grad_u[i * dim + i];
  }
  const double A = st.dt > 0.0 ? std::pow(2.0 * rho / st.dt, 2) : 0.0;
  const S b = 2.0 * rho / st.h, c = 12.0 * mu / (st.h * st.h);
  const S B = b * b, C = c * c;
  const S tau = 1.0 / sqrt(A + B * uu + C);
  const S tau_c = st.h * st.h / (8.0 * tau);
  std::array<S, max_nodes> uG;
  for (int a = 0; a < n; ++a) {
    uG[a] = S(0.0);
    for (int j = 0; j < dim; ++j) uG[a] += u[j] * q.G[a * dim + j];
  }
  for (int a = 0; a < n; ++a)
    for (int i = 0; i < dim; ++i)
      r[a * dim + i] += w * (tau * rho * uG[a] * R[i] + tau_c * q.G[a * dim + i] * div);
  for (int k = 0; k < n; ++k) {
    S GR(0.0);
    for (int i = 0; i < dim; ++i) GR += q.G[k * dim + i] * R[i];
    r[nu + k] -= w * tau * GR;
  }
  if constexpr (std::is_same_v<S, double>) {
    if (K.empty()) return;
    const int nd = nu + n;
    const double cw = in.state_weight;
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
    // The pressure columns (weight 1 in the consistent initial state: p is an unknown there).
    const double pw = in.initial_rate ? 1.0 : cw;
    for (int l = 0; l < n; ++l) {
      const double* Gl = &q.G[l * dim];
      for (int a = 0; a < n; ++a)
        for (int i = 0; i < dim; ++i)
          K[(a * dim + i) * nd + nu + l] += w * tau * rho * uG[a] * pw * Gl[i];
      for (int k = 0; k < n; ++k) {
        double GG = 0.0;
        for (int i = 0; i < dim; ++i) GG += q.G[k * dim + i] * Gl[i];
        K[(nu + k) * nd + nu + l] -= w * tau * pw * GG;
      }
    }
  }
}

// The residual at the nodes `x` moving with the velocity `w` (empty: a fixed mesh), and with
// S = double its Jacobian by (u, p) (K empty to skip). False if the cell is inverted.
template <class S>
bool kernel(const FluidElementInput& in, std::span<const S> x, std::span<const S> mesh_velocity,
            std::span<S> r, std::span<double> K) {
  using std::cbrt;
  using std::sqrt;
  const int dim = in.dim;
  const int n = fem::n_nodes(in.cell);
  const int nv = fem::n_vertices(in.cell);
  const int nu = n * dim;
  const int nd = nu + nv;
  SEAM_ASSERT(static_cast<int>(r.size()) == nd &&
              (K.empty() || static_cast<int>(K.size()) == nd * nd));
  SEAM_ASSERT(nd <= max_dofs);
  std::fill(r.begin(), r.end(), S(0.0));
  std::fill(K.begin(), K.end(), 0.0);
  const double rho = in.fluid.density, mu = in.fluid.viscosity;
  // N_a u grad u is of degree 3 order (per direction on tensor cells, total on simplices).
  const auto rule = fem::quadrature(in.cell, 3 * fem::order(in.cell));
  Point<S> q;
  const bool stabilized = is_stabilized(in.cell);
  Stabilization<S> st;
  if (stabilized) {
    S volume(0.0);
    for (int iq = 0; iq < rule.n_points; ++iq) {
      if (!evaluate(in, x, &rule.points[iq * dim], rule.weights[iq], q)) return false;
      volume += q.weight;
    }
    st.h = dim == 2 ? 2.0 * sqrt(volume / M_PI) : cbrt(6.0 * volume / M_PI);
    st.dt = in.time_step;
  }
  std::array<S, 3> u, c, f, material;
  std::array<S, 9> grad_u;
  for (auto* v : {&u, &c, &f, &material}) v->fill(S(0.0));
  grad_u.fill(S(0.0));
  std::array<double, max_nodes> c_G{};
  S p(0.0);
  for (int iq = 0; iq < rule.n_points; ++iq) {
    if (!evaluate(in, x, &rule.points[iq * dim], rule.weights[iq], q)) return false;
    interpolate(in, q, u.data(), grad_u.data(), p);
    // The convective velocity c = u - w (ALE; w = 0 on a fixed mesh).
    c = u;
    if (!mesh_velocity.empty())
      for (int a = 0; a < n; ++a)
        for (int i = 0; i < dim; ++i) c[i] -= q.N[a] * mesh_velocity[a * dim + i];
    f.fill(S(0.0));
    if (in.body_force) body_force(in, q.x, f.data());
    S div(0.0);
    for (int i = 0; i < dim; ++i) {
      div += grad_u[i * dim + i];
      material[i] = S(0.0);
      for (int j = 0; j < dim; ++j) material[i] += c[j] * grad_u[i * dim + j];
    }
    if (!in.u_dot.empty())
      for (int a = 0; a < n; ++a)
        for (int i = 0; i < dim; ++i) material[i] += q.N[a] * in.u_dot[a * dim + i];
    const S& w = q.weight;
    for (int a = 0; a < n; ++a) {
      const S* Ga = &q.G[a * dim];
      for (int i = 0; i < dim; ++i) {
        S visc(0.0);
        for (int j = 0; j < dim; ++j) visc += Ga[j] * grad_u[i * dim + j];
        r[a * dim + i] += w * (rho * q.N[a] * material[i] + mu * visc - p * Ga[i] - q.N[a] * f[i]);
      }
    }
    // The continuity rows: - int M_k div u; in the consistent initial state of Taylor-Hood
    // cells - int M_k div u_dot, the time derivative of the constraint.
    S div_rows = div;
    if (in.initial_rate && !stabilized) {
      div_rows = S(0.0);
      for (int a = 0; a < n; ++a)
        for (int i = 0; i < dim; ++i) div_rows += q.G[a * dim + i] * in.u_dot[a * dim + i];
    }
    for (int k = 0; k < nv; ++k) r[nu + k] -= w * q.M[k] * div_rows;
    if (stabilized)
      add_stabilization(in, st, q, c.data(), grad_u.data(), material.data(), f.data(), r, K);
    if constexpr (std::is_same_v<S, double>) {
      if (K.empty()) continue;
      for (int b = 0; b < n; ++b) {
        double s = 0.0;
        for (int j = 0; j < dim; ++j) s += c[j] * q.G[b * dim + j];
        c_G[b] = s;
      }
      // material = Du/Dt with dc/du = du/du (w does not depend on u). Every column carries
      // state_weight, the velocity block the mass term. In the consistent initial state the
      // pressure columns carry 1 and the continuity rows of Taylor-Hood cells are by u_dot.
      const double cw = in.state_weight;
      const double pw = in.initial_rate ? 1.0 : cw;
      const double bw = in.initial_rate && !stabilized ? 1.0 : cw;
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
            K[(a * dim + i) * nd + nu + k] -= pw * wM * Ga[i];
            K[(nu + k) * nd + a * dim + i] -= bw * wM * Ga[i];
          }
        }
      }
    }
  }
  return true;
}

// dr/dx (by_velocity = false) or dr/dw (true), row-major n_element_dofs x (n_nodes * dim), by
// forward-mode differentiation in chunks of `chunk` variables.
bool mesh_derivative(const FluidElementInput& in, bool by_velocity, std::span<double> D) {
  constexpr int chunk = 8;
  using Scalar = Dual<chunk>;
  const int nx = fem::n_nodes(in.cell) * in.dim;
  const int nd = n_element_dofs(in.cell);
  SEAM_ASSERT(static_cast<int>(D.size()) == nd * nx);
  SEAM_ASSERT(static_cast<int>(in.x.size()) == nx);
  SEAM_ASSERT(in.mesh_velocity.empty() || static_cast<int>(in.mesh_velocity.size()) == nx);
  std::array<Scalar, max_nodes * 3> x, w;
  std::array<Scalar, max_dofs> r;
  for (int first = 0; first < nx; first += chunk) {
    for (int k = 0; k < nx; ++k) {
      const bool seed = k >= first && k < first + chunk;
      const double wk = in.mesh_velocity.empty() ? 0.0 : in.mesh_velocity[k];
      x[k] = !by_velocity && seed ? Scalar::variable(in.x[k], k - first) : Scalar(in.x[k]);
      w[k] = by_velocity && seed ? Scalar::variable(wk, k - first) : Scalar(wk);
    }
    const bool moving = by_velocity || !in.mesh_velocity.empty();
    if (!kernel<Scalar>(in, std::span<const Scalar>(x.data(), nx),
                        moving ? std::span<const Scalar>(w.data(), nx) : std::span<const Scalar>(),
                        std::span<Scalar>(r.data(), nd), {}))
      return false;
    for (int row = 0; row < nd; ++row)
      for (int k = first; k < std::min(nx, first + chunk); ++k)
        D[row * nx + k] = r[row].gradient[k - first];
  }
  return true;
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
  return kernel<double>(in, in.x, in.mesh_velocity, r, K);
}

bool pressure_operators(fem::CellType cell, std::span<const double> x, std::span<const double> u,
                        std::span<const double> w, std::span<double> mass,
                        std::span<double> laplacian, std::span<double> convection) {
  SEAM_ASSERT(is_taylor_hood(cell));
  FluidElementInput in;
  in.cell = cell;
  in.dim = fem::dimension(cell);
  const int dim = in.dim;
  const int n = fem::n_nodes(cell);
  const int nv = fem::n_vertices(cell);
  SEAM_ASSERT(static_cast<int>(mass.size()) == nv * nv);
  for (auto* m : {&mass, &laplacian, &convection}) std::fill(m->begin(), m->end(), 0.0);
  // The linear pressure functions lie in the quadratic velocity space: M_k = sum_a M_k(xi_a)
  // N_a, so their physical gradients follow from the velocity's.
  std::array<double, 8 * max_nodes> Mk_at{};
  const auto ref = fem::reference_nodes(cell);
  for (int a = 0; a < n; ++a) {
    std::array<double, 8> Ma{};
    fem::shape_values(pressure_cell(cell), &ref[a * dim], Ma.data());
    for (int k = 0; k < nv; ++k) Mk_at[k * max_nodes + a] = Ma[k];
  }
  // The degree of the residual's rule (3 * order), exact for the convection on affine cells.
  const auto rule = fem::quadrature(cell, 3 * fem::order(cell));
  Point<double> q;
  std::array<double, 8 * 3> G{};
  for (int iq = 0; iq < rule.n_points; ++iq) {
    if (!evaluate(in, x, &rule.points[iq * dim], rule.weights[iq], q)) return false;
    std::array<double, 3> cq{};
    for (int a = 0; a < n; ++a)
      for (int i = 0; i < dim; ++i)
        cq[i] += q.N[a] * (u[a * dim + i] - (w.empty() ? 0.0 : w[a * dim + i]));
    for (int k = 0; k < nv; ++k)
      for (int i = 0; i < dim; ++i) {
        double g = 0.0;
        for (int a = 0; a < n; ++a) g += Mk_at[k * max_nodes + a] * q.G[a * dim + i];
        G[k * dim + i] = g;
      }
    for (int k = 0; k < nv; ++k)
      for (int l = 0; l < nv; ++l) {
        double gg = 0.0, cg = 0.0;
        for (int i = 0; i < dim; ++i) {
          gg += G[k * dim + i] * G[l * dim + i];
          cg += cq[i] * G[l * dim + i];
        }
        mass[k * nv + l] += q.weight * q.M[k] * q.M[l];
        laplacian[k * nv + l] += q.weight * gg;
        convection[k * nv + l] += q.weight * q.M[k] * cg;
      }
  }
  return true;
}

bool navier_stokes_mesh_derivatives(const FluidElementInput& in, std::span<double> by_position,
                                    std::span<double> by_velocity) {
  if (!by_position.empty() && !mesh_derivative(in, false, by_position)) return false;
  return by_velocity.empty() || mesh_derivative(in, true, by_velocity);
}

EnergyIntegrals energy_integrals(const FluidElementInput& in) {
  const int dim = in.dim;
  const int n = fem::n_nodes(in.cell);
  const auto rule = fem::quadrature(in.cell, 3 * fem::order(in.cell));
  EnergyIntegrals out;
  Point<double> q;
  std::array<double, 3> u{}, w{};
  std::array<double, 9> grad_u{};
  double p = 0.0;
  for (int iq = 0; iq < rule.n_points; ++iq) {
    if (!evaluate(in, in.x, &rule.points[iq * dim], rule.weights[iq], q)) continue;
    interpolate(in, q, u.data(), grad_u.data(), p);
    double div_w = 0.0;
    w = {0.0, 0.0, 0.0};
    if (!in.mesh_velocity.empty())
      for (int a = 0; a < n; ++a)
        for (int i = 0; i < dim; ++i) {
          w[i] += q.N[a] * in.mesh_velocity[a * dim + i];
          div_w += q.G[a * dim + i] * in.mesh_velocity[a * dim + i];
        }
    double uu = 0.0, gg = 0.0, conv = 0.0;
    for (int i = 0; i < dim; ++i) {
      uu += u[i] * u[i];
      for (int j = 0; j < dim; ++j) {
        gg += grad_u[i * dim + j] * grad_u[i * dim + j];
        conv += (u[j] - w[j]) * grad_u[i * dim + j] * u[i];
      }
    }
    const double rho = in.fluid.density;
    out.kinetic += q.weight * 0.5 * rho * uu;
    out.dissipation += q.weight * in.fluid.viscosity * gg;
    out.convection += q.weight * rho * conv;
    out.mesh_transport += q.weight * 0.5 * rho * uu * div_w;
  }
  return out;
}

std::array<double, 4> error_integrals(const FluidElementInput& in, const ExactVelocity& u_exact,
                                      const ExactPressure& p_exact) {
  const int dim = in.dim;
  const auto rule = fem::quadrature(in.cell, 3 * fem::order(in.cell) + 2);
  std::array<double, 4> out{};
  Point<double> q;
  std::array<double, 3> u{}, ue{};
  std::array<double, 9> grad_u{};
  double p = 0.0;
  for (int iq = 0; iq < rule.n_points; ++iq) {
    if (!evaluate(in, in.x, &rule.points[iq * dim], rule.weights[iq], q)) continue;
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
