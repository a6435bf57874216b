#include "seam/problem/fsi_system.hpp"

#include "seam/ale/mesh_motion.hpp"
#include "seam/common/error.hpp"
#include "seam/mesh/facets.hpp"
#include "seam/problem/model.hpp"
#include "seam/solid/element.hpp"
#include "seam/solid/mass.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

namespace seam::problem {

namespace {

// The pseudo-elastic mesh's Poisson ratio (as FluidMeshMotion).
constexpr double mesh_poisson = 0.3;

solid::MaterialModel solid_model(io::MaterialModel m) {
  switch (m) {
  case io::MaterialModel::saint_venant_kirchhoff:
    return solid::MaterialModel::saint_venant_kirchhoff;
  case io::MaterialModel::neo_hooke:
    return solid::MaterialModel::neo_hooke;
  default:
    return solid::MaterialModel::linear_elastic;
  }
}

std::string point_text(const mesh::Mesh& mesh, std::int32_t n) {
  std::string s = "(";
  for (int i = 0; i < mesh.dim; ++i)
    s += (i ? ", " : "") + std::to_string(mesh.x[static_cast<std::size_t>(n) * mesh.dim + i]);
  return s + ")";
}

} // namespace

FsiSystem::FsiSystem(const io::Config& config, const mesh::Mesh& mesh,
                     const std::vector<meshtying::TiedInterface>& interfaces, Comm comm)
    : config_(&config), mesh_(&mesh), comm_(comm), dim_(mesh.dim) {
  const int dim = dim_;
  n_nodes_ = static_cast<std::size_t>(mesh.n_nodes());
  base_f_ = n_nodes_ * dim;
  base_m_ = base_f_ + n_nodes_ * (dim + 1);
  plane_ = dim == 3                                ? solid::PlaneMode::none
           : config.plane == io::PlaneMode::stress ? solid::PlaneMode::plane_stress
                                                   : solid::PlaneMode::plane_strain;

  // Bodies: a fluid or a solid material per cell.
  std::map<std::string, int> fluid_index, solid_index;
  for (const auto& [name, m] : config.materials) {
    if (m.is_fluid()) {
      fluid_index[name] = static_cast<int>(fluids_.size());
      fluids_.push_back({m.density, m.viscosity});
    } else {
      solid_index[name] = static_cast<int>(solids_.size());
      solids_.push_back({solid_model(m.model), m.young, m.poisson, m.density});
    }
  }
  cell_fluid_.assign(mesh.n_cells(), -1);
  cell_solid_.assign(mesh.n_cells(), -1);
  std::vector<int> cell_body(mesh.n_cells(), -1);
  for (std::size_t b = 0; b < config.bodies.size(); ++b) {
    const auto& body = config.bodies[b];
    const bool is_fluid = config.materials.at(body.material).is_fluid();
    if (!is_fluid && body.mesh_motion)
      io::fail_at(body.mark, "body '" + body.region.name +
                                 "' is a solid: mesh_motion applies only to fluid bodies");
    if (is_fluid && body.mesh_motion &&
        body.mesh_motion->model != io::MeshMotionModel::pseudo_elastic)
      io::fail_at(body.mesh_motion->mark,
                  "in a run with an 'fsi' interface the fluid mesh follows the structure: "
                  "mesh_motion must be 'pseudo_elastic'");
    for (auto c : find_region(mesh, body.region, {dim}, "a body").cells) {
      const auto type = mesh.cell_type[c];
      if (is_fluid && !fluid::is_taylor_hood(type) && !fluid::is_stabilized(type))
        io::fail_at(body.mark, "fluid body '" + body.region.name + "' has " +
                                   std::string(fem::name(type)) +
                                   " cells; seam's fluids use tri6, quad9, tet10, hex27 "
                                   "(Taylor-Hood) or tri3, quad4, tet4, hex8 (stabilized)");
      cell_fluid_[c] = is_fluid ? fluid_index.at(body.material) : -1;
      cell_solid_[c] = is_fluid ? -1 : solid_index.at(body.material);
      cell_body[c] = static_cast<int>(b);
    }
  }
  const auto uncovered = std::count(cell_body.begin(), cell_body.end(), -1);
  if (uncovered > 0)
    io::fail_at(config.bodies.front().mark,
                std::to_string(uncovered) + " of " + std::to_string(mesh.n_cells()) +
                    " cells belong to no body (every cell needs a material)");

  solid_node_.assign(n_nodes_, 0);
  fluid_node_.assign(n_nodes_, 0);
  pressure_node_.assign(n_nodes_, 0);
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c) {
    const auto nodes = mesh.cell(c);
    const int nv = fem::n_vertices(mesh.cell_type[c]);
    for (std::size_t a = 0; a < nodes.size(); ++a) {
      if (cell_fluid_[c] >= 0) {
        fluid_node_[nodes[a]] = 1;
        if (static_cast<int>(a) < nv) pressure_node_[nodes[a]] = 1;
      } else {
        solid_node_[nodes[a]] = 1;
      }
    }
  }
  for (std::size_t n = 0; n < n_nodes_; ++n)
    if (solid_node_[n] && fluid_node_[n])
      io::fail_at(config.bodies.front().mark,
                  "node " + std::to_string(n) + " at " +
                      point_text(mesh, static_cast<std::int32_t>(n)) +
                      " belongs to a fluid and a solid cell; the fluid and the structure are "
                      "separate meshes (own nodes) joined by an 'fsi' interface");

  // The fsi interfaces: sides of the right kind, P = D^-1 M.
  std::size_t k = 0;
  for (const auto& itf : config.interfaces) {
    if (itf.type != io::InterfaceType::fsi)
      io::fail_at(itf.mark, "interface '" + itf.name + "' of type '" +
                                std::string(io::to_string(itf.type)) +
                                "' in a run with an 'fsi' interface: a fluid-structure run "
                                "holds 'fsi' interfaces only in this version of seam");
    const auto& t = interfaces.at(k++);
    const auto check_side = [&](const std::vector<std::int32_t>& nodes, const std::vector<char>& ok,
                                const std::string& group, const char* key, const char* what) {
      for (auto n : nodes)
        if (!ok[n])
          io::fail_at(itf.mark, "interface '" + itf.name + "': its '" + key + "' group '" + group +
                                    "' has node " + std::to_string(n) + " at " +
                                    point_text(mesh, n) + " that is not on a " + what +
                                    " body; 'fluid' names a boundary group of the fluid, "
                                    "'structure' one of the structure");
    };
    check_side(t.slave.mesh_nodes, fluid_node_, itf.slave.name, "fluid", "fluid");
    check_side(t.master.mesh_nodes, solid_node_, itf.master->name, "structure", "solid");
    const auto& ops = t.operators;
    FsiCoupling cp;
    cp.name = t.name;
    cp.fluid_nodes = t.slave.mesh_nodes;
    const std::size_t ns = cp.fluid_nodes.size();
    std::vector<double> diag(ns, 0.0);
    for (const auto& e : ops.D) {
      if (e.row != e.col) SEAM_THROW(InternalError, "fsi: D of a dual basis is not diagonal");
      diag[e.row] = e.value;
    }
    double d_max = 0.0;
    for (double v : diag) d_max = std::max(d_max, std::abs(v));
    for (std::size_t j = 0; j < ns; ++j)
      if (!(diag[j] > 1e-12 * d_max))
        io::fail_at(itf.mark, "interface '" + itf.name + "': fluid node " +
                                  std::to_string(cp.fluid_nodes[j]) + " at " +
                                  point_text(mesh, cp.fluid_nodes[j]) +
                                  " faces no structure facet (the fluid group must lie on the "
                                  "structure group)");
    // tilde = D^-1 M; with a modified quadratic basis d_S = T d~_S (tying_constraint.cpp).
    std::vector<std::map<std::int32_t, double>> tilde(ns), P(ns);
    for (const auto& e : ops.M) tilde[e.row][t.master.mesh_nodes[e.col]] += e.value / diag[e.row];
    if (ops.T.empty()) {
      P = tilde;
    } else {
      for (const auto& e : ops.T)
        for (const auto& [m, v] : tilde[e.col]) P[e.row][m] += e.value * v;
    }
    for (std::size_t j = 0; j < ns; ++j) {
      for (const auto& [m, v] : P[j]) {
        cp.structure_nodes.push_back(m);
        cp.weights.push_back(v);
      }
      cp.offsets.push_back(static_cast<std::int64_t>(cp.structure_nodes.size()));
    }
    cp.d_diagonal = diag;
    for (double v : diag) cp.d_total += v;
    couplings_.push_back(std::move(cp));
  }
  // Per mesh node: (coupling, side-local index) of a fluid interface node; the first wins.
  std::vector<std::pair<int, std::int32_t>> on_interface(n_nodes_, {-1, -1});
  for (std::size_t c = 0; c < couplings_.size(); ++c)
    for (std::size_t j = 0; j < couplings_[c].fluid_nodes.size(); ++j) {
      auto& slot = on_interface[couplings_[c].fluid_nodes[j]];
      if (slot.first < 0) slot = {static_cast<int>(c), static_cast<std::int32_t>(j)};
    }

  // Conditions: the structure's displacement, the fluid's velocity.
  prescribed_.assign(n_raw(), -1);
  for (const auto& bc : config.boundary_conditions) {
    const auto& region = find_region(mesh, bc.region, {0, 1, 2, 3}, "a boundary condition");
    const auto n_fluid = std::count_if(region.nodes.begin(), region.nodes.end(),
                                       [&](std::int32_t n) { return fluid_node_[n] != 0; });
    switch (bc.type) {
    case io::BoundaryType::dirichlet:
      if (n_fluid > 0)
        io::fail_at(bc.mark, "type 'dirichlet' prescribes a solid's displacement, but region '" +
                                 bc.region.name +
                                 "' belongs to a fluid body; prescribe the fluid's velocity "
                                 "with type 'velocity'");
      break;
    case io::BoundaryType::velocity:
      if (n_fluid < static_cast<std::ptrdiff_t>(region.nodes.size()))
        io::fail_at(bc.mark, "type 'velocity' prescribes a fluid's velocity, but region '" +
                                 bc.region.name +
                                 "' belongs to a solid body (a solid's motion is prescribed "
                                 "with type 'dirichlet')");
      break;
    default:
      io::fail_at(bc.mark, "type '" + std::string(io::to_string(bc.type)) +
                               "' is not available yet in a run with an 'fsi' interface (only "
                               "'dirichlet' on the structure and 'velocity' on the fluid)");
    }
    for (std::size_t q = 0; q < bc.components.size(); ++q) {
      const int expr = static_cast<int>(values_.size());
      values_.push_back(bc.value[q]);
      for (auto n : region.nodes) {
        if (bc.type == io::BoundaryType::dirichlet) {
          prescribed_[d_dof(n, bc.components[q])] = expr;
        } else if (on_interface[n].first < 0) {
          // On the interface the coupling wins (CONTRACT.md): the structure's motion.
          prescribed_[f_dof(n, bc.components[q])] = expr;
        }
      }
    }
  }

  // Fluid boundary nodes off the interfaces hold their mesh position.
  std::vector<char> boundary(n_nodes_, 0);
  const auto exterior = mesh::exterior_facets(mesh);
  for (std::int32_t f = 0; f < exterior.size(); ++f) {
    const auto c = exterior.cell[f];
    if (cell_fluid_[c] < 0) continue;
    const auto nodes = mesh.cell(c);
    for (int a : fem::facet_nodes(mesh.cell_type[c], exterior.local[f])) boundary[nodes[a]] = 1;
  }

  // Condensed numbering and the maps T_c (columns) and R (rows), raw dof by raw dof.
  PetscInt next = 0;
  std::vector<PetscInt> own(n_raw(), -1);
  for (std::size_t n = 0; n < n_nodes_; ++n)
    for (int i = 0; i < dim; ++i)
      if (solid_node_[n] && prescribed_[d_dof(n, i)] < 0) own[d_dof(n, i)] = next++;
  for (std::size_t n = 0; n < n_nodes_; ++n) {
    if (!fluid_node_[n]) continue;
    for (int i = 0; i < dim; ++i)
      if (on_interface[n].first < 0 && prescribed_[f_dof(n, i)] < 0) own[f_dof(n, i)] = next++;
    if (pressure_node_[n]) own[f_dof(n, dim)] = next++;
  }
  for (std::size_t n = 0; n < n_nodes_; ++n)
    if (fluid_node_[n] && on_interface[n].first < 0 && !boundary[n])
      for (int i = 0; i < dim; ++i) own[m_dof(n, i)] = next++;
  n_unknowns_ = next;
  const int size = comm.size(), rank = comm.rank();
  n_owned_ = next / size + (rank < next % size ? 1 : 0);
  first_owned_ = rank * (next / size) + std::min<PetscInt>(rank, next % size);

  // The structure dofs P maps an interface node to, component i.
  const auto for_master = [&](std::int32_t n, const auto& f) {
    const auto& cp = couplings_[on_interface[n].first];
    const auto j = on_interface[n].second;
    for (auto q = cp.offsets[j]; q < cp.offsets[j + 1]; ++q)
      f(cp.structure_nodes[q], cp.weights[q]);
  };
  velocity_row_.assign(n_raw(), 0);
  for (std::size_t a = 0; a < n_raw(); ++a) {
    if (own[a] >= 0) {
      columns_.add(own[a], 1.0);
      rows_.add(own[a], 1.0);
    } else if (a >= base_f_ && a < base_m_) {
      const auto n = static_cast<std::int32_t>((a - base_f_) / (dim + 1));
      const int i = static_cast<int>((a - base_f_) % (dim + 1));
      // The interface velocity's momentum row moves to the structure by P^T; its value is
      // u_G = P v(d) (column_scale: dv/dd; steady: the structure rests, u_G = 0).
      if (i < dim && fluid_node_[n] && on_interface[n].first >= 0) {
        velocity_row_[a] = 1;
        for_master(n, [&](std::int32_t s, double w) {
          if (own[d_dof(s, i)] >= 0) {
            rows_.add(own[d_dof(s, i)], w);
            columns_.add(own[d_dof(s, i)], w);
          }
        });
      }
    } else if (a >= base_m_) {
      const auto n = static_cast<std::int32_t>((a - base_m_) / dim);
      const int i = static_cast<int>((a - base_m_) % dim);
      if (fluid_node_[n] && on_interface[n].first >= 0)
        for_master(n, [&](std::int32_t s, double w) {
          if (own[d_dof(s, i)] >= 0) columns_.add(own[d_dof(s, i)], w);
        });
    }
    columns_.append_row();
    rows_.append_row();
  }

  // The pseudo-elastic mesh: E = (V_min / V_e)^chi over the fluid cells (Stein et al.).
  std::vector<std::int32_t> fluid_cells;
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c)
    if (cell_fluid_[c] >= 0) fluid_cells.push_back(c);
  const auto ratio = ale::jacobian_stiffening(mesh, fluid_cells, 1.0);
  mesh_young_.assign(mesh.n_cells(), 0.0);
  for (std::size_t q = 0; q < fluid_cells.size(); ++q) {
    const auto& body = config.bodies[cell_body[fluid_cells[q]]];
    double power = 1.0;
    if (body.mesh_motion)
      power = body.mesh_motion->stiffening == io::Stiffening::jacobian
                  ? body.mesh_motion->stiffening_power
                  : 0.0;
    mesh_young_[fluid_cells[q]] = std::pow(ratio[q], power);
  }

  // A contiguous block of cells per rank.
  const auto n_cells = static_cast<std::int64_t>(mesh.n_cells());
  for (std::int64_t c = n_cells * rank / size; c < n_cells * (rank + 1) / size; ++c)
    local_cells_.push_back(static_cast<std::int32_t>(c));
}

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
    const double* x = &mesh_->x[n * dim];
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
    const double scale = column_scale(a);
    for (auto q = columns_.offsets[a]; q < columns_.offsets[a + 1]; ++q)
      raw[a] += scale * columns_.weight[q] * x[columns_.index[q]];
  }
}

void FsiSystem::add_block(std::span<const std::size_t> rows, std::span<const std::size_t> cols,
                          std::span<const double> K, std::vector<PetscInt>& I,
                          std::vector<PetscInt>& J, std::vector<double>& V) const {
  for (std::size_t a = 0; a < rows.size(); ++a)
    for (auto p = rows_.offsets[rows[a]]; p < rows_.offsets[rows[a] + 1]; ++p)
      for (std::size_t b = 0; b < cols.size(); ++b) {
        const double k = K[a * cols.size() + b] * column_scale(cols[b]);
        if (k == 0.0) continue;
        for (auto q = columns_.offsets[cols[b]]; q < columns_.offsets[cols[b] + 1]; ++q) {
          I.push_back(rows_.index[p]);
          J.push_back(columns_.index[q]);
          V.push_back(rows_.weight[p] * columns_.weight[q] * k);
        }
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
  std::vector<PetscInt> I, Jc;
  std::vector<double> V;
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
      if (J) add_block(s_rows, s_rows, Ke, I, Jc, V);
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
      add_block(f_rows, f_rows, Ke, I, Jc, V);
      if (options.shape_derivatives) {
        // d r / d m_{n+1} = alpha_f d r / dx + alpha_m / (gamma dt) d r / dw.
        Kx.assign(ne * nd, 0.0);
        Kw.assign(hs ? ne * nd : 0, 0.0);
        fluid::navier_stokes_mesh_derivatives(in, Kx, Kw);
        for (std::size_t k = 0; k < Kx.size(); ++k)
          Kx[k] = wf * Kx[k] + (hs ? rate_weight * Kw[k] : 0.0);
        add_block(f_rows, m_rows, Kx, I, Jc, V);
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
    if (J) add_block(m_rows, m_rows, Km, I, Jc, V);
  }
  out.inverted = comm_.any(out.inverted);
  out.strain_energy = comm_.sum(out.strain_energy);
  out.kinetic_energy = comm_.sum(out.kinetic_energy);
  comm_.sum_in_place(res);
  comm_.sum_in_place(mag);
  for (std::size_t a = 0; a < n_raw(); ++a)
    if (rows_.offsets[a + 1] > rows_.offsets[a]) out.level += mag[a] * mag[a];
  out.level = std::sqrt(out.level);

  // R^T r: every rank sets the rows it owns from the summed raw residual.
  std::vector<double> owned(static_cast<std::size_t>(n_owned_), 0.0);
  for (std::size_t a = 0; a < n_raw(); ++a)
    for (auto q = rows_.offsets[a]; q < rows_.offsets[a + 1]; ++q) {
      const auto row = rows_.index[q] - first_owned_;
      if (row >= 0 && row < n_owned_) owned[row] += rows_.weight[q] * res[a];
    }
  r = la::Vector(comm_.get(), n_owned_);
  std::vector<PetscInt> ids(owned.size());
  for (std::size_t q = 0; q < ids.size(); ++q) ids[q] = first_owned_ + static_cast<PetscInt>(q);
  r.set_values(ids, owned);
  r.assemble();
  if (J) *J = la::Matrix::from_triplets(comm_.get(), n_owned_, I, Jc, V);
  return out;
}

} // namespace seam::problem
