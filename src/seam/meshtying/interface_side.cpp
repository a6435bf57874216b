#include "seam/meshtying/interface_side.hpp"

#include <algorithm>

namespace seam::meshtying {

InterfaceSide extract_side(const mesh::Mesh& mesh, const mesh::Region& region) {
  InterfaceSide side;
  side.dim = mesh.dim;
  std::vector<std::int32_t> facet_mesh_nodes;
  for (std::int32_t f = 0; f < region.n_facets(); ++f) {
    const auto c = region.facet_cell[f];
    const auto type = mesh.cell_type[c];
    const auto local = fem::facet_nodes(type, region.facet_local[f]);
    const auto cell = mesh.cell(c);
    side.types.push_back(fem::facet_type(type, region.facet_local[f]));
    for (int k : local) facet_mesh_nodes.push_back(cell[k]);
    side.offsets.push_back(static_cast<local_index>(facet_mesh_nodes.size()));
  }
  side.mesh_nodes = facet_mesh_nodes;
  std::sort(side.mesh_nodes.begin(), side.mesh_nodes.end());
  side.mesh_nodes.erase(std::unique(side.mesh_nodes.begin(), side.mesh_nodes.end()),
                        side.mesh_nodes.end());
  side.nodes.reserve(facet_mesh_nodes.size());
  for (auto n : facet_mesh_nodes)
    side.nodes.push_back(static_cast<local_index>(
        std::lower_bound(side.mesh_nodes.begin(), side.mesh_nodes.end(), n) -
        side.mesh_nodes.begin()));
  side.update_coordinates(mesh);
  return side;
}

void InterfaceSide::update_coordinates(const mesh::Mesh& mesh,
                                       std::span<const double> displacement) {
  coordinates.resize(mesh_nodes.size() * static_cast<std::size_t>(dim));
  for (std::size_t i = 0; i < mesh_nodes.size(); ++i)
    for (int c = 0; c < dim; ++c) {
      const auto k = static_cast<std::size_t>(mesh_nodes[i]) * dim + c;
      coordinates[i * dim + c] = mesh.x[k] + (displacement.empty() ? 0.0 : displacement[k]);
    }
}

void side_part(const InterfaceSide& side, std::span<const std::int64_t> facet_ids,
               std::span<const std::int64_t> node_ids, std::span<const local_index> facets,
               std::vector<local_index>& scratch, parallel::SurfacePart& out) {
  const int dim = side.dim;
  out.dim = dim;
  out.facet_ids.clear();
  out.offsets.assign(1, 0);
  out.connectivity.clear();
  out.node_ids.clear();
  out.coords.clear();
  scratch.assign(side.mesh_nodes.size(), -1);
  for (const auto f : facets) {
    const auto fi = static_cast<std::size_t>(f);
    out.facet_ids.push_back(facet_ids[fi]);
    for (auto k = side.offsets[fi]; k < side.offsets[fi + 1]; ++k) {
      const auto n = static_cast<std::size_t>(side.nodes[static_cast<std::size_t>(k)]);
      if (scratch[n] < 0) {
        scratch[n] = out.n_nodes();
        out.node_ids.push_back(node_ids[n]);
        for (int c = 0; c < dim; ++c) out.coords.push_back(side.coordinates[n * dim + c]);
      }
      out.connectivity.push_back(scratch[n]);
    }
    out.offsets.push_back(static_cast<local_index>(out.connectivity.size()));
  }
}

} // namespace seam::meshtying
