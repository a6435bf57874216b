#include "seam/problem/model.hpp"

#include "seam/common/error.hpp"
#include "seam/mesh/locate.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <span>
#include <sstream>

namespace seam::problem {

solid::MaterialModel to_solid(io::MaterialModel m) {
  switch (m) {
  case io::MaterialModel::linear_elastic:
    return solid::MaterialModel::linear_elastic;
  case io::MaterialModel::saint_venant_kirchhoff:
    return solid::MaterialModel::saint_venant_kirchhoff;
  case io::MaterialModel::neo_hooke:
    return solid::MaterialModel::neo_hooke;
  case io::MaterialModel::newtonian_fluid:
    break; // a fluid has no solid model (flow/fluid_model.cpp, fsi/fsi_setup.cpp)
  }
  return solid::MaterialModel::linear_elastic;
}

namespace {

std::string describe_regions(const mesh::Mesh& mesh) {
  std::ostringstream s;
  for (std::size_t i = 0; i < mesh.regions.size(); ++i)
    s << (i ? ", " : "") << mesh.regions[i].name << " (dim " << mesh.regions[i].dim << ")";
  return mesh.regions.empty() ? std::string("none (the mesh has no physical groups)") : s.str();
}

// A probe outside the mesh is an input error (CONTRACT.md); found here so that `seam check`
// reports it too, with the mesh's extent to show where the points may lie.
// Collective: each rank looks among the cells it assembles, which together are the mesh.
void check_probes(const io::Config& config, const Discretization& disc) {
  if (config.output.probes.empty()) return;
  const auto& mesh = disc.mesh();
  const auto& comm = disc.comm();
  const mesh::PointLocator locator(mesh, disc.local_cells());
  const auto dim = static_cast<std::size_t>(mesh.dim);
  for (const auto& probe : config.output.probes) {
    const bool found = locator.locate(std::span<const double>(probe.point.data(), dim)).has_value();
    if (comm.any(found)) continue;
    std::array<double, 3> lower, upper;
    lower.fill(std::numeric_limits<double>::infinity());
    upper.fill(-std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < mesh.x.size(); ++i) {
      lower[i % dim] = std::min(lower[i % dim], mesh.x[i]);
      upper[i % dim] = std::max(upper[i % dim], mesh.x[i]);
    }
    for (std::size_t a = 0; a < dim; ++a) {
      lower[a] = comm.min(lower[a]);
      upper[a] = comm.max(upper[a]);
    }
    std::ostringstream s;
    s << "probe (";
    for (std::size_t a = 0; a < dim; ++a) s << (a ? ", " : "") << probe.point[a];
    s << ") lies outside the mesh; expected a point of the mesh, which spans ";
    for (std::size_t a = 0; a < dim; ++a)
      s << (a ? " x " : "") << '[' << lower[a] << ", " << upper[a] << ']';
    io::fail_at(probe.mark, s.str());
  }
}

} // namespace

const mesh::Region& find_region(const mesh::Mesh& mesh, const io::RegionRef& ref,
                                std::initializer_list<int> dims, std::string_view what) {
  const mesh::Region* any = nullptr;
  for (const auto& r : mesh.regions) {
    if (r.name != ref.name) continue;
    if (std::find(dims.begin(), dims.end(), r.dim) != dims.end()) return r;
    any = &r;
  }
  std::ostringstream msg;
  if (any) {
    msg << "region '" << ref.name << "' has dimension " << any->dim << ", but " << what
        << " needs a region of dimension";
    for (int d : dims) msg << ' ' << d;
  } else {
    msg << "no region '" << ref.name << "' in the mesh; available: " << describe_regions(mesh);
  }
  io::fail_at(ref.mark, msg.str());
}

SurfaceLoad surface_load(const mesh::Mesh& mesh, const io::BoundaryCondition& bc,
                         const std::function<bool(std::int32_t)>& is_local_cell) {
  const auto& region =
      find_region(mesh, bc.region, {mesh.dim - 1},
                  bc.type == io::BoundaryType::pressure ? "a pressure load" : "a traction load");
  SurfaceLoad load{bc.type, {}, bc.components, bc.value};
  for (std::int32_t f = 0; f < region.n_facets(); ++f)
    if (is_local_cell(region.facet_cell[f]))
      load.facets.push_back({region.facet_cell[f], region.facet_local[f]});
  return load;
}

BodyLoad body_load(const mesh::Mesh& mesh, const io::BoundaryCondition& bc,
                   const std::function<bool(std::int32_t)>& is_local_cell) {
  const auto& region = find_region(mesh, bc.region, {mesh.dim}, "a body force");
  BodyLoad load{{}, bc.components, bc.value};
  for (auto c : region.cells)
    if (is_local_cell(c)) load.cells.push_back(c);
  return load;
}

Model build_model(const io::Config& config, const Discretization& disc) {
  const auto& mesh = disc.mesh();
  const int dim = mesh.dim;
  if (dim != config.dimension)
    io::fail_at(config.mesh.mark, "the mesh is " + std::to_string(dim) + "D but `dimension` is " +
                                      std::to_string(config.dimension));
  Model model;
  model.dim = dim;
  if (dim == 2)
    model.plane = config.plane == io::PlaneMode::stress ? solid::PlaneMode::plane_stress
                                                        : solid::PlaneMode::plane_strain;

  // Materials and bodies: every cell must belong to exactly one body.
  std::map<std::string, int> material_index;
  for (const auto& [name, m] : config.materials) {
    material_index[name] = static_cast<int>(model.materials.size());
    model.materials.push_back({to_solid(m.model), m.young, m.poisson, m.density});
    model.material_names.push_back(name);
  }
  model.cell_material.assign(mesh.n_cells(), -1);
  for (const auto& body : config.bodies) {
    const auto& region = find_region(mesh, body.region, {dim}, "a body");
    const int mat = material_index.at(body.material);
    for (auto c : region.cells) model.cell_material[c] = mat;
  }
  // Counted over the owned cells, so that every rank sees the whole mesh's count.
  std::int64_t uncovered = 0;
  for (auto c : disc.local_cells()) uncovered += model.cell_material[c] < 0 ? 1 : 0;
  uncovered = disc.comm().sum(uncovered);
  if (uncovered > 0) {
    std::ostringstream s;
    s << uncovered << " of " << disc.n_global_cells()
      << " cells belong to no body (every cell needs a material); bodies cover the regions";
    for (const auto& b : config.bodies) s << " '" << b.region.name << "'";
    s << "; regions of dimension " << dim << " in the mesh:";
    for (const auto& r : mesh.regions)
      if (r.dim == dim) s << " '" << r.name << "'";
    io::Mark mark;
    mark.file = config.source.string();
    mark.key_path = "bodies";
    if (!config.bodies.empty()) mark = config.bodies.front().mark;
    io::fail_at(mark, s.str());
  }

  // Boundary conditions.
  const auto is_local = [&](std::int32_t c) { return disc.is_local_cell(c); };
  std::vector<DirichletDof> dirichlet;
  for (const auto& bc : config.boundary_conditions) {
    switch (bc.type) {
    case io::BoundaryType::dirichlet: {
      // Any dimension: points, edges, faces, even a whole body.
      const auto& region = find_region(mesh, bc.region, {0, 1, 2, 3}, "a Dirichlet condition");
      ReactionRegion reaction{region.name, {}};
      for (std::size_t k = 0; k < bc.components.size(); ++k) {
        const int expr = static_cast<int>(model.dirichlet_values.size());
        model.dirichlet_values.push_back(bc.value[k]);
        model.dirichlet_marks.push_back(bc.mark);
        for (auto n : region.nodes)
          if (disc.owns_node(n))
            dirichlet.push_back({disc.global_dof(n, bc.components[k]), n, expr});
      }
      for (auto n : region.nodes)
        if (disc.owns_node(n)) reaction.owned_nodes.push_back(n);
      model.reaction_regions.push_back(std::move(reaction));
      break;
    }
    case io::BoundaryType::pressure:
    case io::BoundaryType::traction:
      model.surface_loads.push_back(surface_load(mesh, bc, is_local));
      break;
    case io::BoundaryType::velocity:
      find_region(mesh, bc.region, {0, 1, 2, 3}, "a velocity condition");
      io::fail_at(bc.mark, "type 'velocity' prescribes a fluid's velocity, but region '" +
                               bc.region.name +
                               "' belongs to no fluid body (a solid's motion is prescribed "
                               "with type 'dirichlet')");
    case io::BoundaryType::mesh_displacement:
      find_region(mesh, bc.region, {0, 1, 2, 3}, "a mesh displacement condition");
      io::fail_at(bc.mark, "type 'mesh_displacement' moves the mesh of a fluid body (ALE), but "
                           "region '" +
                               bc.region.name +
                               "' belongs to no fluid body (a solid's motion is prescribed "
                               "with type 'dirichlet')");
    case io::BoundaryType::body_force:
      model.body_loads.push_back(body_load(mesh, bc, is_local));
      break;
    }
  }
  // A dof prescribed twice keeps the later condition.
  std::stable_sort(dirichlet.begin(), dirichlet.end(),
                   [](const DirichletDof& a, const DirichletDof& b) { return a.dof < b.dof; });
  for (std::size_t i = 0; i < dirichlet.size(); ++i)
    if (i + 1 == dirichlet.size() || dirichlet[i + 1].dof != dirichlet[i].dof)
      model.dirichlet.push_back(dirichlet[i]);

  for (const auto& ic : config.initial_conditions)
    find_region(mesh, ic.region, {0, 1, 2, 3}, "an initial condition");
  for (const auto& itf : config.interfaces) {
    find_region(mesh, itf.slave, {dim - 1}, "an interface side");
    if (itf.master) find_region(mesh, *itf.master, {dim - 1}, "an interface side");
    for (const auto& group : itf.surface) find_region(mesh, group, {dim - 1}, "an interface side");
  }
  check_probes(config, disc);
  return model;
}

} // namespace seam::problem
