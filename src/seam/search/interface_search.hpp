#pragma once
// What the mortar layer uses: the search of one slave/master interface kept between Newton
// iterations, multi-body search, and the dynamic slave/master assignment of self contact.
#include "seam/common/types.hpp"
#include "seam/search/facets.hpp"
#include "seam/search/traversal.hpp"
#include "seam/search/tree.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace seam::search {

struct SearchOptions {
  BoundingVolume volume = BoundingVolume::kdop;
  /// Inflation = inflation_factor * the shortest edge of both surfaces (ALGORITHMS.md Sect. 6).
  double inflation_factor = 0.3;
  /// Absolute inflation; when >= 0 it replaces inflation_factor * l_min. A search over one
  /// rank's part of a distributed interface passes the value of the whole interface here, so
  /// that every rank widens the volumes alike.
  double inflation = -1.0;
  double rebuild_factor = 1.5; ///< see TreeOptions::rebuild_factor
};

/// Candidate pairs of one mortar interface. Build once; per Newton iteration call update()
/// with the current (and optionally step-start) coordinates, then find_pairs().
class InterfaceSearch {
public:
  InterfaceSearch(const FacetSurface& slave, const FacetSurface& master,
                  const SearchOptions& options = {});

  /// Refits both trees (rebuilding one whose quality has degraded). Coordinates have the layout
  /// of the surfaces given to the constructor.
  void update(std::span<const double> slave_coords, std::span<const double> master_coords,
              std::span<const double> slave_old_coords = {},
              std::span<const double> master_old_coords = {});

  /// Runs the dual-tree traversal; the result stays valid until the next call.
  const std::vector<CandidatePair>& find_pairs();
  const std::vector<CandidatePair>& pairs() const { return pairs_; }

  double inflation() const { return slave_.inflation(); }
  const Tree& slave_tree() const { return slave_; }
  const Tree& master_tree() const { return master_; }

private:
  InterfaceSearch(const FacetSurface& slave, const FacetSurface& master,
                  const TreeOptions& options);

  Tree slave_;
  Tree master_;
  std::vector<CandidatePair> pairs_;
};

/// A candidate pair between facet facet_a of body body_a and facet facet_b of body body_b;
/// body_a < body_b, or body_a == body_b and facet_a < facet_b for self contact.
struct BodyPair {
  int body_a;
  local_index facet_a;
  int body_b;
  local_index facet_b;
};

/// Multi-body contact: the pairs between all bodies (one tree each, same dimension and volume),
/// plus each body's self-contact pairs if include_self (trees then need normal cones unless
/// options.min_normal_angle <= 0).
std::vector<BodyPair> find_body_pairs(std::span<const Tree> bodies, bool include_self,
                                      const SelfContactOptions& options = {});

/// Dynamic slave/master roles for self contact (Yang & Laursen 2008: roles alternate along
/// contact pairs): two-colours the graph of `pairs` so that paired facets get different roles
/// and returns each pair as (slave, master). Edges are taken in order of decreasing angle
/// between the facet normals (the most clearly facing pairs first), so that where the graph has
/// odd cycles (e.g. through a fold) only the weakest pairs are left unalternated; those keep
/// the lower facet number as slave. In each connected group of pairs the lowest facet number
/// is slave. `tree` is the self-contact tree (with normal cones) that produced the pairs.
std::vector<CandidatePair> assign_roles(const Tree& tree, std::span<const CandidatePair> pairs);
/// The same with the facet normals given instead of the tree: axis[f] is the axis of facet f's
/// normal cone (facet_normal_cone) for every facet f of the pairs; axis.size() facets in all.
std::vector<CandidatePair> assign_roles(std::span<const std::array<double, 3>> axis,
                                        std::span<const CandidatePair> pairs);

/// A facet's role in assign_roles with roles kept: none yet, slave or master (the two colours).
enum class Role : std::int8_t { none = -1, slave = 0, master = 1 };
/// assign_roles with the roles of earlier searches kept (one entry per facet, axis.size()):
/// a facet with a role keeps it, and the pairs are coloured around those roles (a group of pairs
/// joined to a facet with a role takes its colours from it; a group without one gets the lowest
/// facet slave, as above); a pair of two facets of the same role is oriented as an odd cycle,
/// lower facet slave. The facets of `pairs` without a role get the role they were given. With
/// every entry none, the pairs are oriented as by assign_roles above.
std::vector<CandidatePair> assign_roles(std::span<const std::array<double, 3>> axis,
                                        std::span<const CandidatePair> pairs,
                                        std::span<Role> roles);

} // namespace seam::search
