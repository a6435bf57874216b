#include "seam/meshtying/tied_interface.hpp"

#include "seam/common/error.hpp"
#include "seam/search/interface_search.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace seam::meshtying {

namespace {

const mesh::Region& side_region(const mesh::Mesh& mesh, const io::RegionRef& ref) {
  const auto* r = mesh.find_region(ref.name, mesh.dim - 1);
  if (!r)
    io::fail_at(ref.mark, "no boundary region '" + ref.name + "' of dimension " +
                              std::to_string(mesh.dim - 1) + " in the mesh");
  return *r;
}

} // namespace

std::vector<TiedInterface> setup_mesh_tying(const io::Config& config, mesh::Mesh& mesh,
                                            PhaseTimers& timers) {
  std::vector<TiedInterface> out;
  for (const auto& itf : config.interfaces) {
    if (itf.type != io::InterfaceType::mesh_tying) continue;
    TiedInterface t;
    t.name = itf.name;
    t.multiplier = itf.multiplier;
    t.strategy = itf.strategy;
    t.slave = extract_side(mesh, side_region(mesh, itf.slave));
    t.master = extract_side(mesh, side_region(mesh, *itf.master));

    std::vector<std::int32_t> shared;
    std::set_intersection(t.slave.mesh_nodes.begin(), t.slave.mesh_nodes.end(),
                          t.master.mesh_nodes.begin(), t.master.mesh_nodes.end(),
                          std::back_inserter(shared));
    if (!shared.empty())
      io::fail_at(itf.mark, "the slave side '" + itf.slave.name + "' and the master side '" +
                                itf.master->name + "' share " + std::to_string(shared.size()) +
                                " nodes; mesh tying couples two separate meshes");

    std::vector<mortar::CandidatePair> candidates;
    {
      ScopedTimer timer(timers, "search");
      search::InterfaceSearch finder(t.slave.surface(), t.master.surface());
      for (const auto& p : finder.find_pairs()) candidates.push_back({p.slave, p.master});
    }
    {
      ScopedTimer timer(timers, "mortar");
      mortar::MortarOptions options;
      options.multiplier = itf.multiplier == io::Multiplier::dual ? mortar::Multiplier::dual
                                                                  : mortar::Multiplier::standard;
      t.operators = mortar::assemble_mortar_operators(t.slave.facet_set(), t.master.facet_set(),
                                                      candidates, options);
      if (t.operators.n_pairs_integrated == 0)
        io::fail_at(itf.mark, "the sides '" + itf.slave.name + "' and '" + itf.master->name +
                                  "' do not overlap: no slave facet faces a master facet");
      // Mesh initialization: D X_S = M X_M exactly, so that the tying constraint on the
      // displacements is also one on the positions (patch test on curved interfaces,
      // conservation of angular momentum).
      const auto moved = mortar::initialize_slave_coordinates(t.operators, t.slave.coordinates,
                                                              t.master.coordinates);
      const int dim = mesh.dim;
      for (std::size_t i = 0; i < t.slave.mesh_nodes.size(); ++i) {
        double d2 = 0.0;
        for (int c = 0; c < dim; ++c) {
          const double delta = moved[i * dim + c] - t.slave.coordinates[i * dim + c];
          d2 += delta * delta;
          mesh.x[static_cast<std::size_t>(t.slave.mesh_nodes[i]) * dim + c] = moved[i * dim + c];
        }
        t.max_relocation = std::max(t.max_relocation, std::sqrt(d2));
      }
      t.slave.coordinates = moved;
    }
    out.push_back(std::move(t));
  }
  return out;
}

} // namespace seam::meshtying
