#pragma once
// The pressure convection-diffusion (PCD) preconditioner of the Schur complement of a
// Taylor-Hood Navier-Stokes Jacobian (Kay, Loghin & Wathen 2002; Elman, Silvester & Wathen 2014,
// sec. 9.2), applied as the Schur block of the fluid's fieldsplit (docs/fluid.md, "Solving").
//
// The Jacobian's blocks are [F, -s G^T; -s G, 0] with G_kl = int M_k div N_l and, per
// fluid::FluidElementInput, F = s (mu L + rho N + Newton's reaction term) + m rho M_u (s the
// state weight, m the mass weight). Its Schur complement S = -s^2 G F^-1 G^T is approximated by
// the commutator argument G F^-1 G^T ~ A_p F_p^-1 M_p with the same operator on the pressure
// space, F_p = s (mu A_p + rho N_p) + m rho M_p (Picard: without the reaction term), so
//   S^-1 ~ -(1 / s^2) M_p^-1 F_p A_p^-1,
// applied as in the "BRM1" variant of Blechta and Rehor's FENaPack (its docs, "Mathematical
// background"), with the mass matrix weighted by 1/mu, M~ = int M_k M_l / mu, and the convection
// K~ = int s rho M_k (c . grad M_l) / mu; the mass term of generalized-alpha enters as in
// FENaPack's PCDR, through a Laplacian of its own, A_r = int grad M_k . grad M_l / rho (the
// Cahouet-Chabard term: S ~ -(s^2 / (m rho)) B M_u^-1 B^T when the mass dominates):
//   S^-1 ~ -(1 / s^2) [M~^-1 (s I + K~ A_p^-1) + m A_r^-1],
// which for steady flow and a constant mu is M_p^-1 F_p A_p^-1 with F_p's diffusion taken as
// exactly A_p's. A_p^-1 and A_r^-1 are one BoomerAMG V-cycle each, M~^-1 a few
// Jacobi-preconditioned CG iterations.
//
// On a moving mesh (ALE) the momentum equations convect with c = u - w (w the mesh velocity) and
// are integrated on the current configuration; so are the PCD operators: K~ convects with u - w,
// and M~, A_p, A_r and the facet normals that find the inflow are those of the configuration
// the Newton step integrates on, rebuilt (with A_p's and A_r's AMG hierarchies) when it moves.
//
// Boundary conditions: A_p carries a zero Dirichlet condition on the vertices of the inflow
// (boundary facets whose nodes all have the velocity prescribed, with c . n < 0 on average),
// Neumann conditions elsewhere (Elman, Silvester & Wathen 2014, sec. 9.2.2; FENaPack's BRM1).
// The alternative, Dirichlet on the outflow (where the traction is given) in A_p and F_p with
// the same operator order, was measured and diverges once the convection enters (docs/fluid.md,
// "Solving"); it belongs to the reversed order (I + A_p^-1 K~) M~^-1 with a Robin term on the
// inflow ("BRM2"), which is not built. Without an inflow (an enclosed flow, or a flow at rest)
// the Dirichlet vertices are those of the outflow facets, else the pinned pressure vertex. A_r
// carries them on the outflow facets (or the pin), as B M_u^-1 B^T does: Neumann where the
// velocity is prescribed.
//
// Tied fluid subdomains (mesh tying condenses the velocity only, u = T u~): the pressure rows
// and the zero pressure block are unchanged, S couples the two sides' pressures through G T.
// The operators are assembled per pressure space (block-diagonal across the interface, the
// pressure is not tied), and a side of a tied interface through which the flow enters its
// subdomain is that subdomain's inflow: A_p's Dirichlet vertices (docs/fluid.md, "PCD with
// tied fluid subdomains").
#include "seam/la/petsc.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace seam::flow {

class FluidLayout;
struct FluidModel;

/// Whether the command line (after `--`) asks for PCD: `-fluid_schur pcd`; `selfp` (the
/// default) keeps the selfp approximation. Throws InputError for another value.
bool pcd_requested();

/// The weights of the Jacobian (fluid::FluidElementInput): the state weight s, the mass weight m
/// and the product of the weights of the pressure columns and continuity rows (s^2, or 1 in the
/// consistent initial state of generalized-alpha, whose Jacobian is by (u_dot, p)).
struct PcdWeights {
  double state = 1.0;
  double mass = 0.0;
  double coupling = 1.0;
};

class PressureConvectionDiffusion {
public:
  /// Collective. The fluid must be all Taylor-Hood cells (InputError otherwise).
  PressureConvectionDiffusion(const FluidModel& model, const FluidLayout& layout);
  ~PressureConvectionDiffusion();
  PressureConvectionDiffusion(const PressureConvectionDiffusion&) = delete;
  PressureConvectionDiffusion& operator=(const PressureConvectionDiffusion&) = delete;

  /// F_p at the velocity of `w` (the fluid's unknowns, ghosts up to date). On a moving mesh
  /// (ALE) `x` is the current configuration and `mesh_velocity` the mesh velocity (nodal, in
  /// mesh.x's layout; empty: the reference configuration, at rest): M~, A_p and A_r are those of
  /// the configuration x, and K~ convects with u - w, as the momentum equations do. Collective.
  void update(const la::Vector& w, const PcdWeights& weights, std::span<const double> x = {},
              std::span<const double> mesh_velocity = {});
  /// y = -(1 / coupling) [M~^-1 (s x + K~ A_p^-1 x) + m A_r^-1 x] on the pressure rows (the
  /// Schur block's layout).
  void apply(Vec x, Vec y) const;

private:
  /// Marks the Dirichlet vertices of A_p at the convective velocity u - w in `mark_` (owned
  /// and ghosts).
  void mark_dirichlet(std::span<const double> u, std::span<const double> mesh_velocity);
  /// M~ and A_p's triplets and the facet normals in the configuration x (nodal); returns an
  /// inverted cell of this rank, or -1.
  std::int32_t set_geometry(std::span<const double> x);

  const FluidModel& model_;
  const FluidLayout& layout_;
  std::vector<std::int32_t> cells_;      ///< local Taylor-Hood cells
  std::vector<PetscInt> rows_, cols_;    ///< triplets: n_v^2 per cell, pressure numbering
  std::vector<std::int32_t> dofs_;       ///< per triplet: the local pressure dofs of row and col
  std::vector<double> laplace_;          ///< per triplet: A_p without boundary conditions
  std::vector<double> mass_values_;      ///< per triplet: M~
  std::vector<double> geometry_;         ///< the configuration of M~, A_p, A_r (nodal)
  std::vector<double> values_;           ///< scratch: triplet values
  std::vector<std::int32_t> facet_cell_; ///< the exterior facets of local cells
  std::vector<std::int8_t> facet_local_;
  std::vector<char> facet_tied_; ///< per exterior facet: on a side of a tied interface
  std::vector<std::array<double, 3>> facet_normal_; ///< at the facet's centre, in geometry_
  la::Vector prescribed_;   ///< 1 at the prescribed velocity dofs, with ghosts
  la::Vector fallback_;     ///< 1 at the pressure dofs of the outflow vertices (or the pin)
  la::Vector mark_;         ///< the Dirichlet vertices of A_p now
  std::vector<char> fixed_; ///< per triplet: off the diagonal in a Dirichlet row or column
  la::Matrix Mp_, Ap_, Kp_, Ar_;
  KSP ksp_a_ = nullptr, ksp_m_ = nullptr, ksp_r_ = nullptr;
  Vec t1_ = nullptr, t2_ = nullptr;
  PetscInt n_owned_ = 0;
  double state_ = 1.0, mass_ = 0.0, coupling_ = 1.0;
};

} // namespace seam::flow
