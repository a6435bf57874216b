#pragma once
// Self and multi-body contact (`surface: [groups...]`; ALGORITHMS.md §6 and §10): one surface
// made of one or more boundary groups is both the slave and the master side of a contact
// interface. At every search the facet pairs that face each other are found on one tree over
// the whole surface (search::find_self_pairs: normal cones, no pairs of neighbours sharing a
// node) and each pair is given a slave and a master facet (search::assign_roles: roles
// alternate across the contact pairs, as in 4C's self-contact binary tree; in each connected
// group of pairs the lowest facet is slave). The multipliers live on the slave nodes of the
// current search; every other node of the surface has D_jj = 0 and stays inactive.
#include "seam/io/config.hpp"
#include "seam/mesh/mesh.hpp"
#include "seam/meshtying/interface_side.hpp"
#include "seam/mortar/interface.hpp"
#include "seam/mortar/linearization.hpp"
#include "seam/search/tree.hpp"

#include <array>
#include <span>
#include <vector>

namespace seam::contact {

/// A normal of facet f of `side` (any length, out of the body).
std::array<double, 3> facet_normal(const meshtying::InterfaceSide& side, local_index f);

/// One facet region with the facets of all `groups` (a facet listed in two groups is taken
/// once), sorted by (cell, local facet) as every facet region. Located InputError for a group
/// without facets.
mesh::Region surface_region(const mesh::Mesh& mesh, std::span<const io::RegionRef> groups);
/// Its side: facet f of the side is facet f of the region.
meshtying::InterfaceSide extract_surface(const mesh::Mesh& mesh,
                                         std::span<const io::RegionRef> groups);

/// The self-contact search tree of `side` (normal cones on), its volumes widened by
/// `inflation`.
search::Tree self_contact_tree(const meshtying::InterfaceSide& side, double inflation);

/// The oriented (slave, master) candidate pairs of `side` at its current coordinates, sorted:
/// the tree is refitted, the self pairs found, pairs whose facets do not face each other are
/// dropped (normals not opposed, or either facet's centroid more than half the inflation
/// behind the other facet: the two faces of a thin wall are not a contact pair), and the
/// roles assigned.
void self_contact_pairs(search::Tree& tree, const meshtying::InterfaceSide& side,
                        std::vector<mortar::CandidatePair>& out);

/// The slave facets of the current pairs as a facet set over the surface's nodes. The mortar
/// integration and the averaged nodal normals use these facets only, so that the normal of a
/// node is that of the faces that touch (a body's corner that touches with one face keeps that
/// face's normal, as on a slave/master interface whose slave side is that face), and facets
/// that are only master never enter a slave normal.
struct SlavePatch {
  std::vector<fem::CellType> types;
  std::vector<local_index> offsets{0};
  std::vector<local_index> nodes;
  std::vector<local_index> index; ///< per surface facet: its number here, -1 if not slave
  mortar::NodeFacets adjacency;   ///< node -> facets of the patch

  mortar::FacetSet facet_set(const meshtying::InterfaceSide& side) const {
    return {side.dim, side.coordinates, types, offsets, nodes};
  }
};

/// The patch of the slave facets of `pairs` (surface facet numbers).
void build_slave_patch(const meshtying::InterfaceSide& side,
                       std::span<const mortar::CandidatePair> pairs, SlavePatch& out);

} // namespace seam::contact
