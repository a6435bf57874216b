#pragma once
// Pieces of the mesh-tying set-up shared by the replicated and the distributed form.
#include "seam/meshtying/tied_interface.hpp"

#include <cstdint>
#include <vector>

namespace seam::meshtying::detail {

/// Slave nodes (side-local) whose displacement is known: every component prescribed.
std::vector<char> bound_slave_nodes(const io::Config& config, const mesh::Mesh& mesh,
                                    const InterfaceSide& slave, mortar::Multiplier multiplier);
mortar::MortarOptions mortar_options(const io::Interface& itf, const InterfaceSide& slave,
                                     const InterfaceSide& master);
/// One interface with both sides whole in `mesh` (replicated form). `node_gid`: the mesh's
/// nodes' ids in the mesh as read (empty: their indices), for messages.
TiedInterface setup_whole(const io::Config& config, const io::Interface& itf, mesh::Mesh& mesh,
                          PhaseTimers& timers, io::InterfaceType type,
                          std::span<const std::int64_t> node_gid);
[[noreturn]] void fail_shared_nodes(const io::Interface& itf, const SharedNodes& shared, int dim);
[[noreturn]] void fail_no_overlap(const io::Interface& itf);

} // namespace seam::meshtying::detail
