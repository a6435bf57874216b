#include "seam/problem/assembly.hpp"

#include "seam/common/error.hpp"
#include "seam/fem/cell.hpp"
#include "seam/solid/element.hpp"
#include "seam/solid/loads.hpp"

#include <array>

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

} // namespace

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
  std::array<double, max_dofs> minus_r{};

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
    if (tangent)
      tangent->add_values(dofs, dofs,
                          std::span<const double>(d.K.data(), static_cast<std::size_t>(nd) * nd));
  }

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
        status.inverted = true;
        continue;
      }
      add_load(nd);
    }
  }

  residual.assemble();
  if (tangent) tangent->assemble();
  if (external) external->assemble();
  return status;
}

} // namespace seam::problem
