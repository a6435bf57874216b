#pragma once
// Self and multi-body contact (`surface: [groups...]`; ALGORITHMS.md §6 and §10): one surface
// made of one or more boundary groups is both the slave and the master side of a contact
// interface. At every search the facet pairs that face each other are found on a self-contact
// tree (search::find_self_pairs: normal cones, no pairs of neighbours sharing a node; over the
// whole surface, or in a run over the ranks over each rank's facets and those ghosted to it,
// problem/contact_search.hpp) and each pair is given a slave and a master facet
// (search::assign_roles: roles alternate across the contact pairs, as in 4C's self-contact binary
// tree; in each connected group of pairs the lowest facet is slave). The multipliers live on the
// slave nodes of the current search; every other node of the surface has D_jj = 0 and stays
// inactive. In a run (problem/contact_search.hpp) the roles are kept within a time step: those of
// the step's first search hold through its Newton iterations, and a facet that meets anew later
// in the step takes a role once; and from step to step: a facet of a pair that persists from the
// last converged step keeps its role.
#include "seam/io/config.hpp"
#include "seam/mesh/mesh.hpp"
#include "seam/meshtying/interface_side.hpp"
#include "seam/mortar/interface.hpp"
#include "seam/mortar/linearization.hpp"
#include "seam/search/interface_search.hpp"
#include "seam/search/traversal.hpp"
#include "seam/search/tree.hpp"

#include <array>
#include <span>
#include <vector>

namespace seam::contact {

/// A normal of facet f of `side` (any length, out of the body).
std::array<double, 3> facet_normal(const meshtying::InterfaceSide& side, local_index f);

/// One facet region with the facets of all `groups` (a facet listed in two groups is taken
/// once), sorted by (cell, local facet) as every facet region. Located InputError for a group
/// without facets, unless `part` (the mesh is a rank's part: the caller checks the groups
/// over all parts).
mesh::Region surface_region(const mesh::Mesh& mesh, std::span<const io::RegionRef> groups,
                            bool part = false);
/// Its side: facet f of the side is facet f of the region.
meshtying::InterfaceSide extract_surface(const mesh::Mesh& mesh,
                                         std::span<const io::RegionRef> groups, bool part = false);

/// The self-contact search tree of `surface` (normal cones on), its volumes widened by
/// `inflation`.
search::Tree self_contact_tree(const search::FacetSurface& surface, double inflation);

/// The oriented (slave, master) candidate pairs of `side` at its current coordinates, sorted:
/// the tree (over the whole side) is refitted, the self pairs found, those that face each
/// other kept (keep_facing_pairs) and the roles assigned (orient_pairs).
void self_contact_pairs(search::Tree& tree, const meshtying::InterfaceSide& side,
                        std::vector<mortar::CandidatePair>& out);

/// Appends to `out` the self pairs of `found` (facets of `side`) whose facets face each other:
/// normals opposed, and neither facet's centroid more than half the search inflation behind
/// the other facet (the two faces of a thin wall are not a contact pair).
void keep_facing_pairs(const meshtying::InterfaceSide& side, double inflation,
                       std::span<const search::CandidatePair> found,
                       std::vector<search::CandidatePair>& out);

/// The roles of the facing self pairs `pairs` of the whole surface (facets of `side`, each pair
/// once, in any order and either orientation): search::assign_roles on the pairs sorted as
/// (lower, higher) facet, so that the roles depend only on which pairs there are. The oriented
/// pairs, sorted by (slave, master).
void orient_pairs(const meshtying::InterfaceSide& side,
                  std::span<const search::CandidatePair> pairs,
                  std::vector<mortar::CandidatePair>& out);

/// A facing self pair with the axes of its facets' normal cones (as the self-contact tree has
/// them) at the positions of the rank that found it: the distributed search gathers these, so
/// that orienting the pairs of other ranks reads no position of their facets.
struct FacingPair {
  search::CandidatePair pair;
  std::array<double, 3> slave_axis, master_axis;
};

/// `pairs` (facets of `side`) with their axes at the side's current coordinates.
void with_axes(const meshtying::InterfaceSide& side, std::span<const search::CandidatePair> pairs,
               std::vector<FacingPair>& out);

/// orient_pairs with the axes given with the pairs; `n_facets`: the surface's facets.
/// `roles` (empty, or one per facet): the roles kept from the earlier searches of the step
/// (search::assign_roles with roles kept), completed with those of the facets that meet anew.
/// The roles of a connected group of pairs depend on its pairs (their order among themselves)
/// and its facets' kept roles only: the pairs of some whole groups, their facets numbered in
/// the same order, are oriented as in the whole graph (the distributed search decides each
/// group on one rank: problem/contact_search.hpp).
void orient_pairs(local_index n_facets, std::span<const FacingPair> pairs,
                  std::vector<mortar::CandidatePair>& out, std::span<search::Role> roles = {});

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
