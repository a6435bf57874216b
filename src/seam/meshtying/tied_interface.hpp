#pragma once
// Mesh tying interfaces (seed paper Sect. 2): the mortar operators D and M of each
// `type: mesh_tying` interface, computed once in the reference configuration, after the
// mesh initialization that makes D X_S = M X_M hold exactly (ALGORITHMS.md §4, §7).
#include "seam/common/timer.hpp"
#include "seam/io/config.hpp"
#include "seam/meshtying/interface_side.hpp"
#include "seam/mortar/interface.hpp"

#include <string>
#include <vector>

namespace seam::meshtying {

struct TiedInterface {
  std::string name;
  io::Multiplier multiplier = io::Multiplier::dual;
  io::Strategy strategy = io::Strategy::condensed;
  InterfaceSide slave, master;
  /// D (slave x slave) and M (slave x master) over side-local node numbers.
  mortar::MortarOperators operators;
  /// Largest distance a slave node was moved by the mesh initialization.
  double max_relocation = 0.0;
};

/// The boundary region (dimension mesh.dim - 1) an interface side names; a located InputError
/// if the mesh has none.
const mesh::Region& side_region(const mesh::Mesh& mesh, const io::RegionRef& ref);

/// Sets up every mesh-tying interface of the input: extracts both sides, searches candidate
/// pairs (k-DOP trees), integrates D and M, relocates the slave nodes of the mesh so that the
/// constraint holds exactly for the reference geometry. Throws InputError (located at the
/// interface in the YAML) for sides that share nodes or do not face each other.
/// `type` fsi: the same for the `fsi` interfaces (fluid side = slave, structure = master),
/// where the coupling wins over velocity conditions (no bound slave nodes).
std::vector<TiedInterface> setup_mesh_tying(const io::Config& config, mesh::Mesh& mesh,
                                            PhaseTimers& timers,
                                            io::InterfaceType type = io::InterfaceType::mesh_tying);

} // namespace seam::meshtying
