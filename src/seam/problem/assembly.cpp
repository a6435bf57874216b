#include "seam/problem/assembly.hpp"

#include "seam/common/error.hpp"
#include "seam/fem/cell.hpp"
#include "seam/problem/diagnostics.hpp"
#include "seam/solid/algorithmic_force.hpp"
#include "seam/solid/element.hpp"
#include "seam/solid/loads.hpp"
#include "seam/solid/mass.hpp"

#include <array>
#include <cstdio>
#include <optional>

namespace seam::problem {

namespace {

constexpr int max_dofs = fem::max_cell_nodes * 3;

/// Per-cell gather buffers (fixed size: nothing is allocated per cell).
struct CellData {
  int n = 0; ///< nodes
  std::array<double, max_dofs> X{}, u{}, r{};
  std::array<PetscInt, max_dofs> dofs{};
  std::array<double, max_dofs * max_dofs> K{};
};

/// Gathers reference coordinates, displacements and global dofs of the given mesh nodes.
void gather(const Discretization& disc, std::span<const double> u_local,
            std::span<const std::int32_t> nodes, CellData& d) {
  const int dim = disc.dim();
  const auto& x = disc.mesh().x;
  d.n = static_cast<int>(nodes.size());
  for (int a = 0; a < d.n; ++a)
    for (int i = 0; i < dim; ++i) {
      const auto node = nodes[a];
      d.X[a * dim + i] = x[static_cast<std::size_t>(node) * dim + i];
      d.u[a * dim + i] = u_local[disc.local_dof(node, i)];
      d.dofs[a * dim + i] = disc.global_dof(node, i);
    }
}

/// SEAM_CONTACT_TRACE: the cell of an inverted element, its nodes and their positions at the
/// start of the step and at the trial end point (docs/contact_dynamics.md, "Diagnosing a
/// stalled Newton step").
void trace_inverted_cell(const Discretization& disc, std::int32_t c, const CellData& n,
                         const CellData& next) {
  const int dim = disc.dim();
  const auto nodes = disc.mesh().cell(c);
  std::printf("  inverted cell %lld:", static_cast<long long>(disc.cell_gid(c)));
  for (int a = 0; a < n.n; ++a) {
    std::printf(" node %lld", static_cast<long long>(disc.node_gid(nodes[a])));
    for (const auto* dd : {&n, &next}) {
      std::printf(" (");
      for (int i = 0; i < dim; ++i)
        std::printf("%s%.6f", i ? ", " : "", dd->X[a * dim + i] + dd->u[a * dim + i]);
      std::printf(")");
    }
  }
  std::printf("\n");
  std::fflush(stdout);
}

} // namespace

bool add_loads(const Model& model, const Discretization& disc, std::span<const double> u_local,
               double t, la::Vector& residual, la::Matrix* tangent, double tangent_scale,
               la::Vector* external) {
  const auto& mesh = disc.mesh();
  const int dim = disc.dim();
  bool inverted = false;
  CellData d;
  std::array<double, max_dofs> minus_r{};
  // Loads: each kernel returns its contribution to r = f_int - f_ext (minus the load).
  auto add_load = [&](int nd) {
    const std::span<const PetscInt> dofs(d.dofs.data(), nd);
    residual.add_values(dofs, std::span<const double>(d.r.data(), nd));
    if (external) {
      for (int k = 0; k < nd; ++k) minus_r[k] = -d.r[k];
      external->add_values(dofs, std::span<const double>(minus_r.data(), nd));
    }
  };
  std::array<std::int32_t, fem::max_facet_nodes> facet_nodes{};
  for (const auto& load : model.surface_loads) {
    for (const auto& f : load.facets) {
      const auto type = mesh.cell_type[f.cell];
      const auto local = fem::facet_nodes(type, f.local);
      const auto cell_nodes = mesh.cell(f.cell);
      for (std::size_t a = 0; a < local.size(); ++a) facet_nodes[a] = cell_nodes[local[a]];
      gather(disc, u_local, std::span<const std::int32_t>(facet_nodes.data(), local.size()), d);
      const int nd = d.n * dim;
      solid::FacetInput in{fem::facet_type(type, f.local), dim,
                           std::span<const double>(d.X.data(), nd),
                           std::span<const double>(d.u.data(), nd), 0};
      if (load.type == io::BoundaryType::pressure) {
        const auto& p = load.value[0];
        const auto pressure = [&](const double* X) {
          return p(t, X[0], X[1], dim == 3 ? X[2] : 0.0);
        };
        solid::follower_pressure(
            in, pressure, std::span<double>(d.r.data(), nd),
            tangent ? std::span<double>(d.K.data(), static_cast<std::size_t>(nd) * nd)
                    : std::span<double>());
        if (tangent) {
          if (tangent_scale != 1.0)
            for (std::size_t k = 0; k < static_cast<std::size_t>(nd) * nd; ++k)
              d.K[k] *= tangent_scale;
          const std::span<const PetscInt> dofs(d.dofs.data(), nd);
          tangent->add_values(
              dofs, dofs, std::span<const double>(d.K.data(), static_cast<std::size_t>(nd) * nd));
        }
      } else {
        const auto traction = [&](const double* X, double* value) {
          for (int i = 0; i < dim; ++i) value[i] = 0.0;
          for (std::size_t k = 0; k < load.components.size(); ++k)
            value[load.components[k]] = load.value[k](t, X[0], X[1], dim == 3 ? X[2] : 0.0);
        };
        solid::dead_traction(in, traction, std::span<double>(d.r.data(), nd));
      }
      add_load(nd);
    }
  }
  for (const auto& load : model.body_loads) {
    const auto force = [&](const double* X, double* value) {
      for (int i = 0; i < dim; ++i) value[i] = 0.0;
      for (std::size_t k = 0; k < load.components.size(); ++k)
        value[load.components[k]] = load.value[k](t, X[0], X[1], dim == 3 ? X[2] : 0.0);
    };
    for (auto c : load.cells) {
      gather(disc, u_local, mesh.cell(c), d);
      const int nd = d.n * dim;
      solid::ElementInput in{mesh.cell_type[c],
                             dim,
                             model.plane,
                             model.materials[model.cell_material[c]],
                             std::span<const double>(d.X.data(), nd),
                             std::span<const double>(d.u.data(), nd),
                             0};
      if (solid::body_force(in, force, std::span<double>(d.r.data(), nd)) !=
          solid::KernelStatus::ok) {
        inverted = true;
        continue;
      }
      add_load(nd);
    }
  }

  return inverted;
}

AssemblyStatus assemble(const Model& model, const Discretization& disc, const la::Vector& u,
                        double t, la::Vector& residual, la::Matrix* tangent, la::Vector* external) {
  const auto& mesh = disc.mesh();
  const int dim = disc.dim();
  residual.zero();
  if (tangent) tangent->zero();
  if (external) external->zero();
  AssemblyStatus status;

  la::Vector::LocalView u_view(u, false);
  const auto u_local = u_view.values();
  CellData d;

  std::optional<la::BlockAdder> blocks;
  if (tangent) blocks.emplace(*tangent);
  for (auto c : disc.local_cells()) {
    const auto type = mesh.cell_type[c];
    gather(disc, u_local, mesh.cell(c), d);
    const int nd = d.n * dim;
    solid::ElementInput in{type,
                           dim,
                           model.plane,
                           model.materials[model.cell_material[c]],
                           std::span<const double>(d.X.data(), nd),
                           std::span<const double>(d.u.data(), nd),
                           0};
    const auto res = solid::internal_force(
        in, std::span<double>(d.r.data(), nd),
        tangent ? std::span<double>(d.K.data(), static_cast<std::size_t>(nd) * nd)
                : std::span<double>());
    if (res.status != solid::KernelStatus::ok) {
      status.inverted = true;
      continue;
    }
    status.strain_energy += res.energy;
    const std::span<const PetscInt> dofs(d.dofs.data(), nd);
    residual.add_values(dofs, std::span<const double>(d.r.data(), nd));
    if (blocks)
      blocks->add(dofs, std::span<const double>(d.K.data(), static_cast<std::size_t>(nd) * nd));
  }
  if (blocks) blocks->finish();

  status.inverted =
      status.inverted || add_loads(model, disc, u_local, t, residual, tangent, 1.0, external);
  residual.assemble();
  if (tangent) tangent->assemble();
  if (external) external->assemble();
  return status;
}

void assemble_mass(const Model& model, const Discretization& disc, la::Matrix& M) {
  const auto& mesh = disc.mesh();
  const int dim = disc.dim();
  M.zero();
  CellData d;
  const std::vector<double> no_displacement(
      static_cast<std::size_t>(disc.n_owned_dofs()) + disc.local_nodes().size() * dim, 0.0);
  la::BlockAdder blocks(M);
  for (auto c : disc.local_cells()) {
    gather(disc, no_displacement, mesh.cell(c), d);
    const int nd = d.n * dim;
    const auto status =
        solid::consistent_mass(mesh.cell_type[c], dim, std::span<const double>(d.X.data(), nd),
                               model.materials[model.cell_material[c]].density,
                               std::span<double>(d.K.data(), static_cast<std::size_t>(nd) * nd));
    if (status != solid::KernelStatus::ok)
      SEAM_THROW(InputError, "cell ", c, " of the mesh is inverted (det dX/dxi <= 0)");
    const std::span<const PetscInt> dofs(d.dofs.data(), nd);
    blocks.add(dofs, std::span<const double>(d.K.data(), static_cast<std::size_t>(nd) * nd));
  }
  blocks.finish();
  M.assemble();
}

AssemblyStatus assemble_algorithmic(const Model& model, const Discretization& disc,
                                    const la::Vector& u_n, const la::Vector& u_next, double t_mid,
                                    la::Vector& residual, la::Matrix* tangent,
                                    la::Vector* external) {
  const auto& mesh = disc.mesh();
  const int dim = disc.dim();
  residual.zero();
  if (tangent) tangent->zero();
  if (external) external->zero();
  AssemblyStatus status;
  la::Vector::LocalView n_view(u_n, false), next_view(u_next, false);
  const auto un = n_view.values();
  const auto unext = next_view.values();
  CellData d, d_next;
  std::optional<la::BlockAdder> blocks;
  if (tangent) blocks.emplace(*tangent);
  for (auto c : disc.local_cells()) {
    gather(disc, un, mesh.cell(c), d);
    gather(disc, unext, mesh.cell(c), d_next);
    const int nd = d.n * dim;
    solid::AlgorithmicInput in;
    in.cell = mesh.cell_type[c];
    in.dim = dim;
    in.plane = model.plane;
    in.material = model.materials[model.cell_material[c]];
    in.X = std::span<const double>(d.X.data(), nd);
    in.u_n = std::span<const double>(d.u.data(), nd);
    in.u_next = std::span<const double>(d_next.u.data(), nd);
    const auto res = solid::algorithmic_internal_force(
        in, std::span<double>(d.r.data(), nd),
        tangent ? std::span<double>(d.K.data(), static_cast<std::size_t>(nd) * nd)
                : std::span<double>());
    if (res.status != solid::KernelStatus::ok) {
      status.inverted = true;
      if (contact_trace_level() >= 1) trace_inverted_cell(disc, c, d, d_next);
      continue;
    }
    status.strain_energy += res.energy_next;
    const std::span<const PetscInt> dofs(d.dofs.data(), nd);
    residual.add_values(dofs, std::span<const double>(d.r.data(), nd));
    if (blocks)
      blocks->add(dofs, std::span<const double>(d.K.data(), static_cast<std::size_t>(nd) * nd));
  }
  if (blocks) blocks->finish();
  // Loads at the midpoint configuration; d(u_mid)/d(u_next) = 1/2.
  std::vector<double> mid(un.size());
  for (std::size_t i = 0; i < mid.size(); ++i) mid[i] = 0.5 * (un[i] + unext[i]);
  status.inverted =
      status.inverted || add_loads(model, disc, mid, t_mid, residual, tangent, 0.5, external);
  residual.assemble();
  if (tangent) tangent->assemble();
  if (external) external->assemble();
  return status;
}

} // namespace seam::problem
