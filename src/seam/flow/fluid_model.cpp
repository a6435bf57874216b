#include "seam/flow/fluid_model.hpp"

#include "seam/mesh/cell_geometry.hpp"
#include "seam/mesh/facets.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

namespace seam::flow {

using problem::body_load;
using problem::find_region;
using problem::surface_load;

namespace {

// What the fluid field of this version does not do yet, refused before anything is built.
void check_supported(const io::Config& config) {
  for (const auto& body : config.bodies)
    if (!config.materials.at(body.material).is_fluid())
      io::fail_at(body.mark, "body '" + body.region.name +
                                 "' is a solid in a run with fluid bodies but no 'fsi' "
                                 "interface: a fluid and a structure are joined by an interface "
                                 "of type 'fsi' (its 'fluid' and 'structure' groups)");
  for (const auto& itf : config.interfaces) {
    if (itf.type != io::InterfaceType::mesh_tying)
      io::fail_at(itf.mark, "interface '" + itf.name + "' of type '" +
                                std::string(io::to_string(itf.type)) +
                                "' in a run with fluid bodies: fluids are tied ('mesh_tying'); "
                                "fluid contact is not available in this version of seam");
    if (itf.strategy != io::Strategy::condensed)
      io::fail_at(itf.mark, "interface '" + itf.name +
                                "': fluid subdomains are tied with dual multipliers, condensed "
                                "(multiplier 'dual', strategy 'condensed'); the saddle-point "
                                "form is not available for fluids");
  }
  if (config.time.integrator == io::Integrator::energy_momentum)
    io::fail_at(config.time.mark,
                "time.integrator 'energy_momentum' is a scheme for solids; a fluid is integrated "
                "with 'generalized_alpha' (or solved steady with 'static')");
  if (!config.output.exact_displacement.empty()) {
    io::Mark mark;
    mark.file = config.source.string();
    mark.key_path = "output.exact_displacement";
    io::fail_at(mark, "a fluid has no displacement; give output.exact_velocity and "
                      "output.exact_pressure");
  }
}

// Per mesh node: whether it lies in a cell of a fluid body.
std::vector<char> fluid_nodes(const io::Config& config, const mesh::Mesh& mesh) {
  std::vector<char> in_fluid(mesh.n_nodes(), 0);
  for (const auto& body : config.bodies) {
    if (!config.materials.at(body.material).is_fluid()) continue;
    for (auto c : find_region(mesh, body.region, {mesh.dim}, "a body").cells)
      for (auto n : mesh.cell(c)) in_fluid[n] = 1;
  }
  return in_fluid;
}

} // namespace

bool has_fluid(const io::Config& config) {
  for (const auto& body : config.bodies)
    if (config.materials.at(body.material).is_fluid()) return true;
  return false;
}

FluidModel build_fluid_model(const io::Config& config, const FluidLayout& layout) {
  const auto& mesh = layout.mesh();
  const int dim = mesh.dim;
  if (dim != config.dimension)
    io::fail_at(config.mesh.mark, "the mesh is " + std::to_string(dim) + "D but `dimension` is " +
                                      std::to_string(config.dimension));
  // Conditions of the wrong kind for their body first: they are the user's likely slip.
  // Counted over the owned nodes (every cell around them is held), the same on every rank.
  const auto& comm = layout.comm();
  const auto in_fluid = fluid_nodes(config, mesh);
  for (const auto& bc : config.boundary_conditions) {
    const auto& region = find_region(mesh, bc.region, {0, 1, 2, 3}, "a boundary condition");
    std::int64_t fluid = 0, solid = 0;
    for (auto n : region.nodes)
      if (layout.owns_node(n)) ++(in_fluid[n] != 0 ? fluid : solid);
    fluid = comm.sum(fluid);
    solid = comm.sum(solid);
    if (bc.type == io::BoundaryType::dirichlet && fluid > 0)
      io::fail_at(bc.mark, "type 'dirichlet' prescribes a solid's displacement, but region '" +
                               bc.region.name +
                               "' belongs to a fluid body; prescribe the fluid's velocity with "
                               "type 'velocity'");
    if (bc.type == io::BoundaryType::velocity && solid > 0)
      io::fail_at(bc.mark, "type 'velocity' prescribes a fluid's velocity, but region '" +
                               bc.region.name +
                               "' belongs to a solid body (a solid's motion is prescribed with "
                               "type 'dirichlet')");
  }
  check_supported(config);

  FluidModel model;
  model.dim = dim;
  std::map<std::string, int> fluid_index;
  for (const auto& [name, m] : config.materials) {
    if (!m.is_fluid()) continue;
    fluid_index[name] = static_cast<int>(model.fluids.size());
    model.fluids.push_back({m.density, m.viscosity});
  }
  model.cell_fluid.assign(mesh.n_cells(), -1);
  for (const auto& body : config.bodies) {
    const auto& region = find_region(mesh, body.region, {dim}, "a body");
    for (auto c : region.cells) {
      const auto type = mesh.cell_type[c];
      if (!fluid::is_taylor_hood(type) && !fluid::is_stabilized(type))
        io::fail_at(body.mark,
                    "fluid body '" + body.region.name + "' has " + std::string(fem::name(type)) +
                        " cells; seam's fluids use Taylor-Hood elements on quadratic meshes "
                        "(tri6, quad9, tet10, hex27) or stabilized equal-order elements on "
                        "linear ones (tri3, quad4, tet4, hex8); serendipity cells are not "
                        "fluid cells");
      model.cell_fluid[c] = fluid_index.at(body.material);
    }
  }
  std::int64_t uncovered = 0;
  for (auto c : layout.local_cells()) uncovered += model.cell_fluid[c] < 0 ? 1 : 0;
  uncovered = comm.sum(uncovered);
  if (uncovered > 0)
    io::fail_at(config.bodies.front().mark,
                std::to_string(uncovered) + " of " + std::to_string(layout.n_global_cells()) +
                    " cells belong to no body (every cell needs a material)");

  // Velocity conditions (and, for the pinning rule below, which nodes have all components).
  const auto is_local = [&](std::int32_t c) { return layout.is_local_cell(c); };
  std::vector<FluidDirichletDof> dirichlet;
  std::vector<unsigned> prescribed(mesh.n_nodes(), 0); // bit i: component i prescribed
  bool loaded_boundary = false;
  for (const auto& bc : config.boundary_conditions) {
    switch (bc.type) {
    case io::BoundaryType::velocity: {
      const auto& region = find_region(mesh, bc.region, {0, 1, 2}, "a velocity condition");
      for (std::size_t k = 0; k < bc.components.size(); ++k) {
        const int expr = static_cast<int>(model.values.size());
        model.values.push_back(bc.value[k]);
        for (auto n : region.nodes)
          if (layout.owns_node(n))
            dirichlet.push_back({layout.global_dof(n, bc.components[k]), n, expr});
      }
      for (int component : bc.components)
        for (auto n : region.nodes) prescribed[n] |= 1u << component;
      break;
    }
    case io::BoundaryType::pressure:
    case io::BoundaryType::traction:
      model.surface_loads.push_back(surface_load(mesh, bc, is_local));
      loaded_boundary = true;
      break;
    case io::BoundaryType::body_force:
      model.body_loads.push_back(body_load(mesh, bc, is_local));
      break;
    case io::BoundaryType::dirichlet:
      break; // refused above
    case io::BoundaryType::mesh_displacement:
      break; // the mesh's motion (FluidMeshMotion)
    }
  }

  // A flow whose normal velocity is prescribed on the whole boundary determines its pressure
  // up to a constant: fix it at one vertex. A facet is closed where every node has the
  // component along the facet's normal prescribed (its largest normal component: slip walls
  // are given per axis).
  // The sides of tied interfaces are inside the flow: they close nothing and open nothing.
  bool open = loaded_boundary;
  std::vector<char> tied(mesh.n_nodes(), 0);
  for (const auto& itf : config.interfaces)
    for (const auto* side : {&itf.slave, itf.master ? &*itf.master : nullptr})
      if (side)
        for (auto n : find_region(mesh, *side, {dim - 1}, "an interface side").nodes) tied[n] = 1;
  // The exterior facets of this rank's cells (a facet of an owned cell is exterior in the
  // part only if it is in the mesh: the ghost layer holds the cell across it).
  const auto exterior = mesh::exterior_facets(mesh);
  for (std::int32_t f = 0; f < exterior.size() && !open; ++f) {
    const auto c = exterior.cell[f];
    if (!layout.is_local_cell(c)) continue;
    const auto type = mesh.cell_type[c];
    const auto facet = fem::facet_nodes(type, exterior.local[f]);
    if (std::all_of(facet.begin(), facet.end(), [&](int k) { return tied[mesh.cell(c)[k]] != 0; }))
      continue;
    const auto centre = mesh::reference_centre(fem::facet_type(type, exterior.local[f]));
    const auto normal = mesh::facet_normal(mesh, c, exterior.local[f], centre.data());
    int axis = 0;
    for (int i = 1; i < dim; ++i)
      if (std::abs(normal[i]) > std::abs(normal[axis])) axis = i;
    const auto cell = mesh.cell(c);
    for (int k : fem::facet_nodes(type, exterior.local[f]))
      if (!(prescribed[cell[k]] & (1u << axis))) open = true;
  }
  open = comm.any(open);
  if (!open) {
    // The vertex with the lowest id in the mesh as read, whatever the number of ranks.
    std::int32_t first = -1;
    for (std::int32_t n = 0; n < mesh.n_nodes(); ++n)
      if (layout.owns_node(n) && layout.has_pressure(n) &&
          (first < 0 || layout.node_gid(n) < layout.node_gid(first)))
        first = n;
    const auto id = first < 0 ? std::numeric_limits<std::int64_t>::max() : layout.node_gid(first);
    const bool lowest = -comm.max(-id) == id; // collective: before the test of `first`
    model.pressure_pinned = true;
    if (first >= 0 && lowest) {
      dirichlet.push_back(
          {layout.global_dof(first, dim), first, static_cast<int>(model.values.size())});
      model.values.emplace_back(0.0);
    }
  }
  model.tied_nodes = std::move(tied);
  std::stable_sort(dirichlet.begin(), dirichlet.end(),
                   [](const auto& a, const auto& b) { return a.dof < b.dof; });
  for (std::size_t i = 0; i < dirichlet.size(); ++i)
    if (i + 1 == dirichlet.size() || dirichlet[i + 1].dof != dirichlet[i].dof)
      model.dirichlet.push_back(dirichlet[i]);

  for (const auto& group : config.output.forces) {
    std::vector<std::int32_t> nodes;
    for (const auto& ref : group.regions) {
      const auto& region = find_region(mesh, ref, {dim - 1}, "a force group");
      nodes.insert(nodes.end(), region.nodes.begin(), region.nodes.end());
    }
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    ForceRegion force{group.name, {}};
    for (auto n : nodes)
      if (layout.owns_node(n)) force.owned_nodes.push_back(n);
    model.forces.push_back(std::move(force));
  }
  return model;
}

} // namespace seam::flow
