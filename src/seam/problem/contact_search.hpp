#pragma once
// The search of a two-body contact interface distributed over the ranks (seed paper Sect. 3;
// docs/parallel.md, "Contact: master facets ghosted"): at every search each rank sends the
// master facets of the cells it assembles to the ranks whose slave elements their bounding
// boxes can meet (parallel::ghost_masters), and searches its own slave elements against the
// master facets it received (parallel::DistributedSearch). The pairs go to the interface
// (ContactInterface::set_candidates); together the ranks' pairs are those of one whole search.
//
// The interface still holds both sides whole on every rank (the placement reads them); what
// this removes is every rank's search against the whole master surface.
#include "seam/contact/contact_interface.hpp"
#include "seam/parallel/distributed_search.hpp"

#include <mpi.h>

#include <vector>

namespace seam::problem {

class ContactSearch {
public:
  /// `held_masters`: the master facets (side-local) this rank hands in, each on one rank (e.g.
  /// those of the cells it assembles). Switches `itf` to the external search.
  ContactSearch(MPI_Comm comm, contact::ContactInterface& itf,
                std::vector<local_index> held_masters);

  /// Collective. The candidate pairs of the owned slave facets of `itf` at its last place().
  void find(contact::ContactInterface& itf);

  /// Master facets this rank received at the last find() (its own ones included).
  local_index n_received() const { return search_.stats().n_ghosts; }
  const parallel::SearchStats& stats() const { return search_.stats(); }

private:
  std::vector<local_index> held_masters_;
  parallel::DistributedSearch search_;
  parallel::SurfacePart slave_part_, master_part_;
  std::vector<mortar::CandidatePair> pairs_;
};

} // namespace seam::problem
