// The evaluation of FsiSystem (fsi_system.hpp): g(t), T_c x + g, the rates of a step, and
// the assembly of R^T r and R^T J T_c.
#include "seam/fsi/fsi_system.hpp"

#include "seam/ale/mesh_motion.hpp"
#include "seam/common/error.hpp"
#include "seam/common/timer.hpp"
#include "seam/solid/element.hpp"
#include "seam/solid/mass.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace seam::fsi {

namespace {

// The pseudo-elastic mesh's Poisson ratio (as FluidMeshMotion).
constexpr double mesh_poisson = 0.3;

} // namespace

FsiSystem::History FsiSystem::History::from_rho_inf(double rho, double dt, std::size_t n_raw) {
  History h;
  h.dt = dt;
  // Chung & Hulbert 1993 (as dynamic_solver.cpp) and Jansen, Whiting & Hulbert 2000 (as
  // ale::GeneralizedAlpha): 1 - s_af = f_af = 1 / (1 + rho), the same intermediate time.
  h.s_am = (2 * rho - 1) / (rho + 1);
  h.s_af = rho / (rho + 1);
  h.beta = 0.25 * (1 - h.s_am + h.s_af) * (1 - h.s_am + h.s_af);
  h.s_gamma = 0.5 - h.s_am + h.s_af;
  const auto ga = ale::GeneralizedAlpha::from_rho_inf(rho);
  h.f_am = ga.alpha_m;
  h.f_af = ga.alpha_f;
  h.f_gamma = ga.gamma;
  h.old.assign(n_raw, 0.0);
  h.rate.assign(n_raw, 0.0);
  h.accel.assign(n_raw, 0.0);
  return h;
}

void FsiSystem::rates(std::span<const double> raw, std::vector<double>& rate,
                      std::vector<double>& accel) const {
  const auto& h = *history_;
  const double dt = h.dt;
  rate.assign(n_raw(), 0.0);
  accel.assign(n_raw(), 0.0);
  for (std::size_t a = 0; a < n_raw(); ++a) {
    if (a < base_f_) {
      accel[a] = (raw[a] - h.old[a] - dt * h.rate[a]) / (h.beta * dt * dt) -
                 (1 - 2 * h.beta) / (2 * h.beta) * h.accel[a];
      rate[a] = h.rate[a] + dt * ((1 - h.s_gamma) * h.accel[a] + h.s_gamma * accel[a]);
    } else {
      rate[a] = (raw[a] - h.old[a]) / (h.f_gamma * dt) - (1 - h.f_gamma) / h.f_gamma * h.rate[a];
    }
  }
}

std::vector<double> FsiSystem::prescribed(double t) const {
  const int dim = dim_;
  std::vector<double> g(n_raw(), 0.0);
  for (std::size_t a = 0; a < n_raw(); ++a) {
    if (prescribed_[a] < 0) continue;
    const auto n = a < base_f_ ? a / dim : (a - base_f_) / (dim + 1);
    const double* x = node_x(n);
    g[a] = values_[prescribed_[a]](t, x[0], x[1], dim == 3 ? x[2] : 0.0);
  }
  // m_G = P d_G: prescribed structure displacements move the interface mesh too. u_G = P v
  // with v_{n+1} = c d_{n+1} + h, c = gamma / (beta dt) and h from the state at t_n:
  //   h = v_n + dt (1 - gamma) a_n + dt gamma (-(d_n + dt v_n) / (beta dt^2)
  //       - (1 - 2 beta) / (2 beta) a_n)   (Newmark's relations, Chung & Hulbert 1993).
  const auto* hs = history_;
  for (const auto& cp : couplings_)
    for (std::size_t j = 0; j < cp.fluid_nodes.size(); ++j)
      for (int i = 0; i < dim; ++i) {
        double v = 0.0, u = 0.0;
        for (auto q = cp.offsets[j]; q < cp.offsets[j + 1]; ++q) {
          const auto k = d_dof(cp.structure_nodes[q], i);
          v += cp.weights[q] * g[k];
          if (hs) {
            const double dt = hs->dt, b = hs->beta, gm = hs->s_gamma;
            const double h = hs->rate[k] + dt * (1 - gm) * hs->accel[k] +
                             dt * gm *
                                 (-(hs->old[k] + dt * hs->rate[k]) / (b * dt * dt) -
                                  (1 - 2 * b) / (2 * b) * hs->accel[k]);
            u += cp.weights[q] * (gm / (b * dt) * g[k] + h);
          }
        }
        g[m_dof(cp.fluid_nodes[j], i)] = v;
        g[f_dof(cp.fluid_nodes[j], i)] = u;
      }
  return g;
}

void FsiSystem::expand(std::span<const double> x, std::span<const double> g,
                       std::vector<double>& raw) const {
  raw.assign(g.begin(), g.end());
  for (std::size_t a = 0; a < n_raw(); ++a) {
    const auto begin = columns_.offsets[a], end = columns_.offsets[a + 1];
    if (std::any_of(held_column_.begin() + begin, held_column_.begin() + end,
                    [](std::ptrdiff_t p) { return p < 0; }))
      continue;
    const double scale = column_scale(a);
    for (auto q = begin; q < end; ++q)
      raw[a] += scale * columns_.weight[q] * x[static_cast<std::size_t>(held_column_[q])];
  }
}

fluid::EnergyIntegrals FsiSystem::fluid_energy(std::span<const double> raw,
                                               std::span<const double> rate) const {
  const int dim = dim_;
  fluid::EnergyIntegrals sum;
  constexpr std::size_t nmax = fem::max_cell_nodes;
  std::array<double, nmax * 3> x{}, u{}, w{};
  std::array<double, nmax> p{};
  for (auto c : local_cells_) {
    if (cell_fluid_[c] < 0) continue;
    const auto nodes = mesh_->cell(c);
    const auto nd = nodes.size() * dim;
    for (std::size_t a = 0; a < nodes.size(); ++a)
      for (int i = 0; i < dim; ++i) {
        const auto k = a * dim + i;
        x[k] = mesh_->x[static_cast<std::size_t>(nodes[a]) * dim + i] + raw[m_dof(nodes[a], i)];
        u[k] = raw[f_dof(nodes[a], i)];
        w[k] = rate.empty() ? 0.0 : rate[m_dof(nodes[a], i)];
      }
    fluid::FluidElementInput in;
    in.cell = mesh_->cell_type[c];
    in.dim = dim;
    in.fluid = fluids_[cell_fluid_[c]];
    in.x = std::span<const double>(x.data(), nd);
    in.u = std::span<const double>(u.data(), nd);
    in.p = std::span<const double>(p.data(), static_cast<std::size_t>(fem::n_vertices(in.cell)));
    if (!rate.empty()) in.mesh_velocity = std::span<const double>(w.data(), nd);
    const auto e = fluid::energy_integrals(in);
    sum.kinetic += e.kinetic;
    sum.dissipation += e.dissipation;
    sum.convection += e.convection;
    sum.mesh_transport += e.mesh_transport;
  }
  sum.kinetic = comm_.sum(sum.kinetic);
  sum.dissipation = comm_.sum(sum.dissipation);
  sum.convection = comm_.sum(sum.convection);
  sum.mesh_transport = comm_.sum(sum.mesh_transport);
  return sum;
}

void FsiSystem::add_block(std::span<const std::size_t> rows, std::span<const std::size_t> cols,
                          std::span<const double> K, std::vector<PetscInt>* I,
                          std::vector<PetscInt>* J, std::vector<double>& V) const {
  // R^T K T_c is summed within the block, over its condensed rows and columns (each once,
  // sorted), before it becomes triplets: the P^T and P weights of an interface node would
  // otherwise multiply the triplet count (a fluid cell on a non-matching 3D interface). Zeros
  // are kept: the pattern must not depend on the state.
  thread_local std::vector<PetscInt> ri, ci;
  thread_local std::vector<std::int64_t> col_offsets;
  thread_local std::vector<std::size_t> col_pos;
  thread_local std::vector<double> col_weight, L;
  const auto unique_of = [](const DofMap& map, std::span<const std::size_t> raw,
                            std::vector<PetscInt>& out) {
    out.clear();
    for (auto a : raw)
      for (auto p = map.offsets[a]; p < map.offsets[a + 1]; ++p) out.push_back(map.index[p]);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  };
  unique_of(rows_, rows, ri);
  unique_of(columns_, cols, ci);
  if (ri.empty() || ci.empty()) return;
  const auto local = [](const std::vector<PetscInt>& u, PetscInt i) {
    return static_cast<std::size_t>(std::lower_bound(u.begin(), u.end(), i) - u.begin());
  };
  col_offsets.assign(1, 0);
  col_pos.clear();
  col_weight.clear();
  for (auto c : cols) {
    for (auto q = columns_.offsets[c]; q < columns_.offsets[c + 1]; ++q) {
      col_pos.push_back(local(ci, columns_.index[q]));
      col_weight.push_back(columns_.weight[q] * column_scale(c));
    }
    col_offsets.push_back(static_cast<std::int64_t>(col_pos.size()));
  }
  const auto nc = ci.size();
  L.assign(ri.size() * nc, 0.0);
  for (std::size_t a = 0; a < rows.size(); ++a)
    for (auto p = rows_.offsets[rows[a]]; p < rows_.offsets[rows[a] + 1]; ++p) {
      double* row = L.data() + local(ri, rows_.index[p]) * nc;
      const double wp = rows_.weight[p];
      for (std::size_t b = 0; b < cols.size(); ++b) {
        const double k = wp * K[a * cols.size() + b];
        for (auto q = col_offsets[b]; q < col_offsets[b + 1]; ++q)
          row[col_pos[q]] += k * col_weight[q];
      }
    }
  V.insert(V.end(), L.begin(), L.end());
  if (!I) return;
  for (auto r : ri)
    for (auto c : ci) {
      I->push_back(r);
      J->push_back(c);
    }
}

FsiSystem::Result FsiSystem::assemble(std::span<const double> raw, double /*t*/, la::Vector& r,
                                      la::Matrix* J, const Options& options) const {
  const auto& mesh = *mesh_;
  const int dim = dim_;
  const auto* hs = history_;
  Result out;
  out.raw_residual.assign(n_raw(), 0.0);
  auto& res = out.raw_residual;
  std::vector<double> mag(n_raw(), 0.0);
  const double start = wall_seconds();
  double condensing = 0.0; // time in add_block
  // A Jacobian made here before with the same options: values only (its triplets' order).
  const bool reuse =
      J && J->get() && J->get() == pattern_of_ && pattern_shape_ == options.shape_derivatives;
  std::vector<PetscInt> I, Jc;
  std::vector<double> V;
  if (reuse) V.reserve(pattern_size_);
  auto* pI = reuse ? nullptr : &I;
  auto* pJ = reuse ? nullptr : &Jc;
  const auto add = [&](std::span<const std::size_t> rows, std::span<const std::size_t> cols,
                       std::span<const double> K) {
    const double t0 = wall_seconds();
    add_block(rows, cols, K, pI, pJ, V);
    condensing += wall_seconds() - t0;
  };
  constexpr std::size_t nmax = fem::max_cell_nodes;
  std::array<double, nmax * 3> X{}, x{}, u{}, m{}, zero{}, ud{}, w{}, v{}, am{};
  std::array<double, nmax> p{};
  std::vector<std::size_t> f_rows, s_rows, m_rows;
  std::vector<double> re, Ke, Kx, Kw, Km, Ms;
  // Generalized-alpha: a value at the intermediate time, (1 - weight) old + weight new.
  const auto between = [&](std::size_t k, double weight) {
    return hs ? (1 - weight) * hs->old[k] + weight * raw[k] : raw[k];
  };
  for (auto c : local_cells_) {
    const auto type = mesh.cell_type[c];
    const auto nodes = mesh.cell(c);
    const auto nn = nodes.size();
    const auto nd = nn * dim;
    for (std::size_t a = 0; a < nn; ++a)
      for (int i = 0; i < dim; ++i) X[a * dim + i] = mesh.x[nodes[a] * dim + i];
    if (cell_solid_[c] >= 0) {
      s_rows.clear();
      for (std::size_t a = 0; a < nn; ++a)
        for (int i = 0; i < dim; ++i) s_rows.push_back(d_dof(nodes[a], i));
      // M a_{n+1-alpha_m} + f_int(d_{n+1-alpha_f}) (Chung & Hulbert 1993).
      const double wf = hs ? 1 - hs->s_af : 1.0;
      for (std::size_t k = 0; k < nd; ++k) u[k] = between(s_rows[k], wf);
      solid::ElementInput in;
      in.cell = type;
      in.dim = dim;
      in.plane = plane_;
      in.material = solids_[cell_solid_[c]];
      in.X = std::span<const double>(X.data(), nd);
      in.u = std::span<const double>(u.data(), nd);
      re.assign(nd, 0.0);
      Ke.assign(J ? nd * nd : 0, 0.0);
      const auto element = solid::internal_force(in, re, Ke);
      if (element.status != solid::KernelStatus::ok) {
        out.inverted = true;
        continue;
      }
      out.strain_energy += element.energy;
      if (hs) {
        // The energy at t_{n+1}, and the inertia.
        for (std::size_t k = 0; k < nd; ++k) u[k] = raw[s_rows[k]];
        out.strain_energy += solid::internal_force(in, {}, {}).energy - element.energy;
        const double dt = hs->dt, b = hs->beta;
        for (std::size_t k = 0; k < nd; ++k) {
          const auto q = s_rows[k];
          const double a_new = (raw[q] - hs->old[q] - dt * hs->rate[q]) / (b * dt * dt) -
                               (1 - 2 * b) / (2 * b) * hs->accel[q];
          am[k] = (1 - hs->s_am) * a_new + hs->s_am * hs->accel[q];
          v[k] = hs->rate[q] + dt * ((1 - hs->s_gamma) * hs->accel[q] + hs->s_gamma * a_new);
        }
        Ms.assign(nd * nd, 0.0);
        solid::consistent_mass(type, dim, in.X, in.material.density, Ms);
        for (std::size_t a = 0; a < nd; ++a)
          for (std::size_t b2 = 0; b2 < nd; ++b2) {
            re[a] += Ms[a * nd + b2] * am[b2];
            out.kinetic_energy += 0.5 * v[a] * Ms[a * nd + b2] * v[b2];
          }
        if (J)
          for (std::size_t k = 0; k < nd * nd; ++k)
            Ke[k] = wf * Ke[k] + (1 - hs->s_am) / (b * dt * dt) * Ms[k];
      }
      for (std::size_t a = 0; a < nd; ++a) {
        res[s_rows[a]] += re[a];
        mag[s_rows[a]] += std::abs(re[a]);
      }
      if (J) add(s_rows, s_rows, Ke);
      continue;
    }
    // Fluid cell on the mesh x = X + m (at t_{n+alpha_f}; Jansen, Whiting & Hulbert 2000: u and
    // p at n + alpha_f, du/dt and the mesh velocity dm/dt at n + alpha_m).
    const int nv = fem::n_vertices(type);
    const double wf = hs ? hs->f_af : 1.0;
    f_rows.clear();
    m_rows.clear();
    for (std::size_t a = 0; a < nn; ++a)
      for (int i = 0; i < dim; ++i) {
        f_rows.push_back(f_dof(nodes[a], i));
        m_rows.push_back(m_dof(nodes[a], i));
        const auto k = a * dim + i;
        u[k] = between(f_rows.back(), wf);
        m[k] = raw[m_rows.back()];
        x[k] = X[k] + between(m_rows.back(), wf);
        if (hs) {
          const double dt = hs->dt, gm = hs->f_gamma;
          const auto rate_at = [&](std::size_t q) {
            const double r_new = (raw[q] - hs->old[q]) / (gm * dt) - (1 - gm) / gm * hs->rate[q];
            return (1 - hs->f_am) * hs->rate[q] + hs->f_am * r_new;
          };
          ud[k] = rate_at(f_rows.back());
          w[k] = rate_at(m_rows.back());
        }
      }
    for (int a = 0; a < nv; ++a) {
      f_rows.push_back(f_dof(nodes[a], dim));
      p[a] = between(f_rows.back(), wf);
    }
    const auto ne = f_rows.size();
    fluid::FluidElementInput in;
    in.cell = type;
    in.dim = dim;
    in.fluid = fluids_[cell_fluid_[c]];
    in.x = std::span<const double>(x.data(), nd);
    in.u = std::span<const double>(u.data(), nd);
    in.p = std::span<const double>(p.data(), nv);
    const double rate_weight = hs ? hs->f_am / (hs->f_gamma * hs->dt) : 0.0;
    if (hs) {
      in.u_dot = std::span<const double>(ud.data(), nd);
      in.mesh_velocity = std::span<const double>(w.data(), nd);
      in.state_weight = wf;
      in.mass_weight = rate_weight;
      in.time_step = hs->dt;
    }
    re.assign(ne, 0.0);
    Ke.assign(J ? ne * ne : 0, 0.0);
    if (!fluid::navier_stokes(in, re, Ke)) {
      out.inverted = true;
      continue;
    }
    for (std::size_t a = 0; a < ne; ++a) {
      res[f_rows[a]] += re[a];
      mag[f_rows[a]] += std::abs(re[a]);
    }
    if (J) {
      add(f_rows, f_rows, Ke);
      if (options.shape_derivatives) {
        // d r / d m_{n+1} = alpha_f d r / dx + alpha_m / (gamma dt) d r / dw.
        Kx.assign(ne * nd, 0.0);
        Kw.assign(hs ? ne * nd : 0, 0.0);
        fluid::navier_stokes_mesh_derivatives(in, Kx, Kw);
        for (std::size_t k = 0; k < Kx.size(); ++k)
          Kx[k] = wf * Kx[k] + (hs ? rate_weight * Kw[k] : 0.0);
        add(f_rows, m_rows, Kx);
      }
    }
    // The pseudo-elastic mesh on the reference cell: r_m = K_m m (linear, at t_{n+1}).
    solid::ElementInput mi;
    mi.cell = type;
    mi.dim = dim;
    mi.plane = dim == 2 ? solid::PlaneMode::plane_strain : solid::PlaneMode::none;
    mi.material.young = mesh_young_[c];
    mi.material.poisson = mesh_poisson;
    mi.X = std::span<const double>(X.data(), nd);
    mi.u = std::span<const double>(zero.data(), nd);
    Km.assign(nd * nd, 0.0);
    solid::internal_force(mi, {}, Km);
    for (std::size_t a = 0; a < nd; ++a) {
      double val = 0.0;
      for (std::size_t b = 0; b < nd; ++b) val += Km[a * nd + b] * m[b];
      res[m_rows[a]] += val;
      for (std::size_t b = 0; b < nd; ++b) mag[m_rows[a]] += std::abs(Km[a * nd + b] * m[b]);
    }
    if (J) add(m_rows, m_rows, Km);
  }
  out.inverted = comm_.any(out.inverted);
  out.strain_energy = comm_.sum(out.strain_energy);
  out.kinetic_energy = comm_.sum(out.kinetic_energy);
  // The raw residual and its magnitudes summed on the owners of the nodes: this rank's
  // entries of the nodes it holds into a node-laid-out vector (two values per raw slot),
  // whose assembly sends the others' to their owners, which add them in rank order.
  const auto slots = raw_slots();
  {
    la::Vector summed(comm_.get(), static_cast<PetscInt>(n_owned_nodes_ * slots * 2));
    std::vector<PetscInt> at;
    std::vector<double> values;
    at.reserve(held_nodes_.size() * slots * 2);
    values.reserve(at.capacity());
    const auto put = [&](std::int32_t n, std::size_t a) {
      const auto slot = static_cast<PetscInt>((node_slot_[n] * slots + raw_slot(a)) * 2);
      at.push_back(slot);
      values.push_back(res[a]);
      at.push_back(slot + 1);
      values.push_back(mag[a]);
    };
    for (auto n : held_nodes_) {
      for (int i = 0; i < dim; ++i) {
        put(n, d_dof(n, i));
        put(n, m_dof(n, i));
      }
      for (int c = 0; c <= dim; ++c) put(n, f_dof(n, c));
    }
    summed.add_values(at, values);
    summed.assemble();
    std::fill(res.begin(), res.end(), 0.0);
    std::fill(mag.begin(), mag.end(), 0.0);
    la::Vector::LocalView view(summed, false);
    const auto v = view.values();
    const auto first = summed.owned_begin();
    for (std::size_t k = 0; k < at.size(); k += 2) {
      const auto local = at[k] - first;
      if (local < 0 || local >= static_cast<PetscInt>(v.size())) continue;
      const auto n = held_nodes_[k / (2 * slots)];
      // The raw dof of this slot, in the order put() visited them.
      const auto j = (k / 2) % slots;
      const auto a =
          j < static_cast<std::size_t>(2 * dim)
              ? (j % 2 == 0 ? d_dof(n, static_cast<int>(j / 2)) : m_dof(n, static_cast<int>(j / 2)))
              : f_dof(n, static_cast<int>(j - 2 * dim));
      res[a] = v[local];
      mag[a] = v[local + 1];
    }
  }
  for (std::size_t a = 0; a < n_raw(); ++a)
    if (rows_.offsets[a + 1] > rows_.offsets[a]) out.level += mag[a] * mag[a];
  out.level = std::sqrt(comm_.sum(out.level));

  // R^T r from the rows of the owned nodes: an interface node's momentum rows go through P^T
  // to structure unknowns that other ranks may own.
  std::vector<PetscInt> ids;
  std::vector<double> contributions;
  for (auto n : held_nodes_) {
    if (!owns_node(n)) continue;
    const auto add_rows = [&](std::size_t a) {
      for (auto q = rows_.offsets[a]; q < rows_.offsets[a + 1]; ++q) {
        ids.push_back(rows_.index[q]);
        contributions.push_back(rows_.weight[q] * res[a]);
      }
    };
    for (int i = 0; i < dim; ++i) {
      add_rows(d_dof(n, i));
      add_rows(m_dof(n, i));
    }
    for (int c = 0; c <= dim; ++c) add_rows(f_dof(n, c));
  }
  r = la::Vector(comm_.get(), n_owned_);
  r.add_values(ids, contributions);
  r.assemble();
  const double t0 = wall_seconds();
  if (J && reuse) {
    if (V.size() != pattern_size_)
      SEAM_THROW(InternalError, "the FSI Jacobian's pattern changed (", V.size(), " entries, ",
                 pattern_size_, " before)");
    J->set_triplet_values(V);
  } else if (J) {
    *J = la::Matrix::from_triplets(comm_.get(), n_owned_, I, Jc, V);
    pattern_of_ = J->get();
    pattern_shape_ = options.shape_derivatives;
    pattern_size_ = V.size();
  }
  condensing += wall_seconds() - t0;
  out.condensation_seconds = condensing;
  out.assembly_seconds = wall_seconds() - start - condensing;
  return out;
}

void FsiSystem::owned_fields(std::vector<PetscInt>& structure, std::vector<PetscInt>& fluid,
                             std::vector<PetscInt>& mesh) const {
  structure.clear();
  fluid.clear();
  mesh.clear();
  for (PetscInt k = first_owned_; k < first_owned_ + n_owned_; ++k)
    (k < end_structure_ ? structure : k < end_fluid_ ? fluid : mesh).push_back(k);
}

std::vector<double> FsiSystem::structure_rigid_modes() const {
  const PetscInt begin = std::min(first_owned_, end_structure_);
  const PetscInt end = std::min(first_owned_ + n_owned_, end_structure_);
  const auto n = static_cast<std::size_t>(end - begin);
  const int n_modes = dim_ == 2 ? 3 : 6;
  std::vector<double> modes(n_modes * n, 0.0);
  for (std::size_t q = 0; q < n; ++q) {
    const auto a = structure_raw_[q];
    const auto node = a / dim_;
    const int i = static_cast<int>(a % dim_);
    const double* x = &mesh_->x[node * dim_];
    modes[i * n + q] = 1.0; // translations
    // Rotations about the coordinate axes: (-y, x, 0), and in 3D (0, -z, y), (z, 0, -x).
    const double r2[2] = {-x[1], x[0]};
    if (i < 2) modes[dim_ * n + q] = r2[i];
    if (dim_ == 3) {
      const double rx[3] = {0.0, -x[2], x[1]}, ry[3] = {x[2], 0.0, -x[0]};
      modes[4 * n + q] = rx[i];
      modes[5 * n + q] = ry[i];
    }
  }
  return modes;
}

} // namespace seam::fsi
