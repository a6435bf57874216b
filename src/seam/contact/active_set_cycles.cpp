#include "seam/contact/active_set_cycles.hpp"

#include <algorithm>

namespace seam::contact {

std::size_t ActiveSetCycles::guard(std::vector<char>& next, std::vector<char>& alternating,
                                   const Agree& agree) {
  alternating.assign(next.size(), 0);
  const auto equal = [&](const std::vector<char>& a, const std::vector<char>& b) {
    return agree ? agree(a == b) : a == b;
  };
  const std::size_t m = history_.size();
  std::size_t period = 0;
  // The set k iterations before `next` is history_[m - k] (history_[m - 1] is one before).
  // A set seen once before is not yet a cycle of period k >= 3: a converging search may pass
  // through an earlier set again (a frictional drag in unit_problem did, and freezing it there
  // stopped the convergence). So for k >= 3 the set before `next` must have repeated with the
  // same period too; period 2 is caught at its first return, as before.
  const auto repeats = [&](std::size_t k) {
    if (!equal(history_[m - k], next)) return false;
    return k == 2 || (m >= k + 1 && equal(history_[m - 1 - k], history_[m - 1]));
  };
  if (m >= 2 && !equal(next, history_.back()))
    for (std::size_t k = 2; k <= max_period && k <= m; ++k)
      if (repeats(k)) {
        period = k;
        break;
      }
  if (period > 0)
    for (std::size_t i = m - period; i < m; ++i)
      for (std::size_t j = 0; j < next.size(); ++j) {
        if (history_[i][j] != next[j]) alternating[j] = 1;
        next[j] = std::max(next[j], history_[i][j]);
      }
  history_.push_back(next);
  retractable_ = true;
  // A cycle of period max_period compares with the sets max_period + 1 iterations back; one
  // more is kept for retract().
  while (history_.size() > max_period + 2) history_.pop_front();
  return period;
}

void ActiveSetCycles::retract() {
  if (retractable_ && history_.size() > 1) history_.pop_back();
  retractable_ = false;
}

} // namespace seam::contact
