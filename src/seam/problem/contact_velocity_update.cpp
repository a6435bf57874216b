#include "seam/problem/contact_velocity_update.hpp"

#include "seam/common/error.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <vector>

namespace seam::problem {

namespace {

/// Takes up to G out of the kinetic energy along the velocity direction `delta`:
/// v <- v - s delta with s the root of smaller magnitude of 1/2 a s^2 - b s + G = 0,
/// a = delta^T M delta, b = v^T M delta; without a real root s = b / a, which removes all the
/// kinetic energy along delta, b^2 / (2 a). Returns the energy removed.
double remove_along(const la::Matrix& M, const la::Vector& delta, double G, la::Vector& v,
                    la::Vector& work, double& s) {
  s = 0.0;
  M.mult(delta, work);
  const double a = delta.dot(work), b = v.dot(work);
  if (!(a > 0.0) || !(G > 0.0)) return 0.0;
  const double disc = b * b - 2.0 * a * G;
  s = disc >= 0.0 ? 2.0 * G / (b + std::copysign(std::sqrt(disc), b)) : b / a;
  v.axpy(-s, delta);
  v.update_ghosts();
  return disc >= 0.0 ? G : b * b / (2.0 * a);
}

/// The velocity of a contact patch relative to its rigid motion. The patch S is the nodes
/// where d is nonzero grown by `layers` layers of cells (the nodes M couples to it; every node
/// of the mesh for layers < 0), without the prescribed dofs; delta = P_S (v - R c) with R the rigid
/// motions of the whole mesh at x_{n+1} (translations, rotations about the patch's centroid) and c
/// from R^T M P_S (v - R c) = 0, so that M delta has no resultant and no moment: v - s delta keeps
/// both momenta for any s. Returns the number of patch nodes.
std::int64_t patch_deformation_velocity(const Discretization& disc, const la::Matrix& M,
                                        const la::Vector& u, const la::Vector& v,
                                        const la::Vector& d, std::span<const PetscInt> prescribed,
                                        int layers, la::Vector& delta, la::Vector& mask,
                                        la::Vector& work) {
  const int dim = disc.dim();
  const auto n_owned = static_cast<std::size_t>(disc.n_owned_nodes());
  const auto& X = disc.mesh().x;
  const auto nodes = disc.local_nodes();
  // The patch as an indicator over the owned dofs (every component of a node).
  const auto flag_nodes = [&](const la::Vector& source) {
    la::Vector::LocalView in(source, false), out(mask, true);
    for (std::size_t i = 0; i < n_owned; ++i) {
      bool any = false;
      for (int c = 0; c < dim; ++c) any = any || in.values()[i * dim + c] != 0.0;
      for (int c = 0; c < dim; ++c) out.values()[i * dim + c] = any ? 1.0 : 0.0;
    }
  };
  if (layers < 0) {
    la::Vector::LocalView out(mask, true);
    for (auto& x : out.values()) x = 1.0;
  } else {
    flag_nodes(d);
  }
  for (int l = 0; l < layers; ++l) {
    M.mult(mask, work);
    flag_nodes(work);
  }
  std::int64_t n_patch = 0;
  double centroid[4] = {0, 0, 0, 0};
  {
    la::Vector::LocalView m(mask, true), uv(u, false);
    const PetscInt first = disc.first_owned_dof();
    for (const PetscInt dof : prescribed)
      if (dof >= first && dof < first + disc.n_owned_dofs())
        m.values()[static_cast<std::size_t>(dof - first)] = 0.0;
    for (std::size_t i = 0; i < n_owned; ++i) {
      if (m.values()[i * dim] == 0.0 && m.values()[i * dim + dim - 1] == 0.0) continue;
      ++n_patch;
      centroid[3] += 1.0;
      for (int c = 0; c < dim; ++c)
        centroid[c] += X[static_cast<std::size_t>(nodes[i]) * dim + c] + uv.values()[i * dim + c];
    }
  }
  disc.comm().sum_in_place(std::span<double>(centroid, 4));
  n_patch = static_cast<std::int64_t>(centroid[3]);
  if (n_patch == 0) return 0;
  // The rigid motions at x_{n+1}: dim translations and 1 (2D) or 3 rotations.
  const int n_modes = dim == 2 ? 3 : 6;
  std::vector<la::Vector> modes, patch_modes;
  for (int k = 0; k < n_modes; ++k) {
    modes.push_back(disc.make_vector());
    patch_modes.push_back(disc.make_vector());
    la::Vector::LocalView r(modes.back(), true), pr(patch_modes.back(), true), m(mask, false),
        uv(u, false);
    for (std::size_t i = 0; i < n_owned; ++i) {
      double y[3] = {0, 0, 0}, e[3] = {0, 0, 0};
      for (int c = 0; c < dim; ++c)
        y[c] = X[static_cast<std::size_t>(nodes[i]) * dim + c] + uv.values()[i * dim + c] -
               centroid[c] / centroid[3];
      if (k < dim) {
        e[k] = 1.0;
      } else { // rotation about axis z (2D) or axis k - 3: a x y
        const int axis = dim == 2 ? 2 : k - 3;
        double w[3] = {0, 0, 0};
        w[axis] = 1.0;
        e[0] = w[1] * y[2] - w[2] * y[1];
        e[1] = w[2] * y[0] - w[0] * y[2];
        e[2] = w[0] * y[1] - w[1] * y[0];
      }
      for (int c = 0; c < dim; ++c) {
        r.values()[i * dim + c] = e[c];
        pr.values()[i * dim + c] = e[c] * m.values()[i * dim + c];
      }
    }
  }
  // delta = P_S v first; then the normal equations A c = R^T M P_S v, A = R^T M P_S R.
  {
    la::Vector::LocalView vv(v, false), m(mask, false), out(delta, true);
    for (std::size_t i = 0; i < n_owned * static_cast<std::size_t>(dim); ++i)
      out.values()[i] = vv.values()[i] * m.values()[i];
  }
  using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
  using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;
  Small A(n_modes, n_modes);
  SmallVector rhs(n_modes);
  M.mult(delta, work);
  for (int k = 0; k < n_modes; ++k) rhs(k) = modes[static_cast<std::size_t>(k)].dot(work);
  for (int l = 0; l < n_modes; ++l) {
    M.mult(patch_modes[static_cast<std::size_t>(l)], work);
    for (int k = 0; k < n_modes; ++k) A(k, l) = modes[static_cast<std::size_t>(k)].dot(work);
  }
  // A is not symmetric (M P_S); a patch that does not span every rigid motion (a few nodes in
  // a line) makes it singular, where a least-squares solution serves as well.
  const SmallVector coefficients = A.colPivHouseholderQr().solve(rhs);
  for (int l = 0; l < n_modes; ++l)
    delta.axpy(-coefficients(l), patch_modes[static_cast<std::size_t>(l)]);
  return n_patch;
}

} // namespace

double remove_from_patch(const Discretization& disc, const la::Matrix& M,
                         std::span<const PetscInt> prescribed, const la::Vector& u,
                         const la::Vector& seed, int layers, double G, la::Vector& v,
                         std::int64_t& patch_nodes, double& s) {
  la::Vector delta = disc.make_vector(), mask = disc.make_vector(), work = disc.make_vector();
  patch_nodes =
      patch_deformation_velocity(disc, M, u, v, seed, prescribed, layers, delta, mask, work);
  s = 0.0;
  return patch_nodes > 0 ? remove_along(M, delta, G, v, work, s) : 0.0;
}

ContactGainRemoval
remove_contact_gain(const Discretization& disc, const ContactConstraint& contact,
                    const la::Matrix& M, std::span<const PetscInt> prescribed, const la::Vector& u,
                    double energy, const std::function<bool(la::Vector&, la::Vector&)>& mass_solve,
                    la::Vector& v) {
  ContactGainRemoval r;
  la::Vector d = disc.make_vector(), obstacle = disc.make_vector();
  const auto gain = contact.impact_gain(d, obstacle);
  r.gain = gain.gain;
  r.nodes = gain.nodes;
  if (!(gain.gain > 1e-13 * energy)) return r;
  r.acted = true;
  // Two layers of cells around the nodes of d: in the 10-ring pile continued past t = 0.35
  // (examples/rings) no layer leaves 2.8 of 4.9 in the step to t = 0.36, one 0.58, two none.
  constexpr int layers = 2;
  la::Vector b = disc.make_vector(), y = disc.make_vector(), work = disc.make_vector();
  b.copy_from(d);
  if (!mass_solve(b, y))
    SEAM_THROW(SolverError, "the mass matrix solve of the contact velocity update failed");
  r.impulse = remove_along(M, y, gain.gain, v, work, r.mu);
  if (r.impulse < gain.gain) {
    // The patch around the nodes of both (the obstacles' rows take no impulse).
    la::Vector seed = disc.make_vector();
    {
      const la::Vector::LocalView a(d, false), o(obstacle, false), out(seed, true);
      for (std::size_t i = 0; i < out.values().size(); ++i)
        out.values()[i] = std::abs(a.values()[i]) + std::abs(o.values()[i]);
    }
    r.patch = remove_from_patch(disc, M, prescribed, u, seed, layers, gain.gain - r.impulse, v,
                                r.patch_nodes, r.s);
  }
  return r;
}

} // namespace seam::problem
