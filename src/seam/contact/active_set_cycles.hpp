#pragma once
// Cycling guard of the semi-smooth Newton (primal-dual active set) method. Near a change of the
// contact zone the set of active nodes (or the stick/slip statuses with friction) can return to
// one it had a few iterations before without converging: the method has no global convergence
// guarantee for contact problems (Hueeber & Wohlmuth 2005; Hintermueller, Ito & Kunisch 2002,
// whose monotonicity argument needs an M-matrix), and a corner of one block hitting another
// face first was seen to cycle through four sets. When the statuses asked for return to those
// of k iterations ago (2 <= k <= max_period) while they differ from the ones in use (and, for
// k >= 3, the statuses in use equal those of k iterations before them: the cycle has repeated
// for two iterations), the guard gives every node that changed within the cycle the largest status
// it had in it (inactive < stick < slip): the union of the active sets of the cycle. The caller
// keeps that choice for the rest of the step. Period 2 is the guard this replaces.
#include <cstddef>
#include <deque>
#include <functional>
#include <vector>

namespace seam::contact {

class ActiveSetCycles {
public:
  /// Periods 2 .. max_period are recognized. Cycles in separate parts of a large contact zone
  /// superpose to the least common multiple of their periods (the 200 rings of examples/rings
  /// at t = 0.6939: one part alternating with period 2, another with period 5, the whole set
  /// with period 10, for 30 iterations), so twelve; a cycle is caught after about one period
  /// and a half, within a step's iteration limit (typically 25 to 30). A longer cycle is left
  /// to the step cut.
  static constexpr std::size_t max_period = 12;

  /// A new step (or a restart of the search) from the statuses in use.
  void start(const std::vector<char>& current) {
    history_.assign(1, current);
    retractable_ = false;
  }

  /// `next`: the statuses the conditions ask for at this iterate (one char per node). If they
  /// equal those of k iterations ago and differ from the last ones (for k >= 3 the last ones
  /// also equal those k iterations before them), `next` becomes the
  /// per-node maximum over the k sets of the cycle, `alternating` marks the nodes whose status
  /// changed within it, and k is returned; otherwise 0 (`alternating` all zero). The result is
  /// recorded as the newest set.
  /// `agree`, if given, turns this part's comparison of two sets into the whole's (e.g. equal
  /// on every rank, when each rank holds the statuses of part of the nodes); called in the
  /// same order on every part.
  using Agree = std::function<bool(bool)>;
  std::size_t guard(std::vector<char>& next, std::vector<char>& alternating,
                    const Agree& agree = {});

  /// Forgets the set recorded by the last guard() (if any since start() or the last retract()):
  /// a shortened Newton correction (line search) decides the statuses again at a point of
  /// the same iteration, which then stands for it; recorded twice, the set would stretch a
  /// cycle beyond the periods compared (a period-2 cycle went unseen that way).
  void retract();

private:
  std::deque<std::vector<char>> history_; ///< oldest first; back() = the statuses in use
  bool retractable_ = false;
};

} // namespace seam::contact
