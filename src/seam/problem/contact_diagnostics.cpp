// Diagnostics of the contact state for a stalled Newton step (docs/contact_dynamics.md,
// "Diagnosing a stalled Newton step"): what the pairs, gap blocks and statuses are at the
// last evaluate(), and which slave node a row of the Newton system belongs to.
#include "seam/problem/contact_constraint.hpp"
#include "seam/problem/diagnostics.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string_view>
#include <tuple>

namespace seam::problem {

int contact_trace_level() {
  static const int level = [] {
    const char* v = std::getenv("SEAM_CONTACT_TRACE");
    if (v == nullptr) return 0;
    const std::string_view text(v);
    return text == "1" ? 1 : text == "2" ? 2 : text == "3" ? 3 : 0;
  }();
  return level;
}

void trace_gap_pairs(const std::string& name, std::vector<contact::GapPairRecord>& records) {
  static std::map<std::string, std::vector<contact::GapPairRecord>> last;
  const auto key = [](const contact::GapPairRecord& r) {
    return std::tie(r.slave_nodes[0], r.slave_nodes[1], r.master_nodes[0], r.master_nodes[1]);
  };
  const auto less = [&key](const auto& a, const auto& b) { return key(a) < key(b); };
  std::sort(records.begin(), records.end(), less);
  auto& before = last[name];
  const char* status[] = {"block", "pre-check", "no overlap"};
  const auto print = [&](const char* what, const contact::GapPairRecord& r,
                         const contact::GapPairRecord* old) {
    std::printf("  %s pair %s: slave %lld-%lld master %lld-%lld: %s%s, n_s.n_m %.6f, g~ "
                "%.4e %.4e",
                name.c_str(), what, static_cast<long long>(r.slave_nodes[0]),
                static_cast<long long>(r.slave_nodes[1]), static_cast<long long>(r.master_nodes[0]),
                static_cast<long long>(r.master_nodes[1]), status[r.status],
                r.kept ? " (kept)" : "", r.alignment, r.gap[0], r.gap[1]);
    if (old)
      std::printf("; was %s%s, n_s.n_m %.6f, g~ %.4e %.4e", status[old->status],
                  old->kept ? " (kept)" : "", old->alignment, old->gap[0], old->gap[1]);
    std::printf("\n");
  };
  std::size_t i = 0, j = 0;
  while (i < records.size() || j < before.size()) {
    if (j == before.size() || (i < records.size() && less(records[i], before[j]))) {
      if (records[i].status == 0) print("new", records[i], nullptr);
      ++i;
    } else if (i == records.size() || less(before[j], records[i])) {
      if (before[j].status == 0) print("gone", before[j], nullptr);
      ++j;
    } else {
      if (records[i].status != before[j].status) print("changed", records[i], &before[j]);
      ++i;
      ++j;
    }
  }
  std::fflush(stdout);
  before = records;
}

std::vector<std::string> ContactConstraint::trace() const {
  std::vector<std::string> out;
  for (const auto& s : sides_) {
    std::uint64_t hash = 1469598103934665603ull;
    std::size_t pairs = s.itf.n_candidates();
    if (s.search && s.search->self()) {
      // The pair set over all ranks (the same on every rank).
      const auto set = s.search->pair_set();
      pairs = static_cast<std::size_t>(set.count);
      hash = set.hash;
    }
    int active = 0, rows = 0;
    for (std::size_t j = 0; j < s.active.size(); ++j) {
      active += s.active[j] != 0;
      rows += s.discrete_gradient && s.em_row[j] != 0;
    }
    char roles[200] = "";
    if (s.search && s.search->self()) {
      const auto c = s.search->role_changes();
      std::snprintf(roles, sizeof roles,
                    ", role changes so far: between steps %lld (pairs found again exchanged %lld), "
                    "within %lld; pairs of facets of the same role %lld",
                    static_cast<long long>(c.between), static_cast<long long>(c.persisting),
                    static_cast<long long>(c.within),
                    static_cast<long long>(s.search->same_role_pairs()));
    }
    char line[480];
    std::snprintf(line, sizeof line,
                  "%s: pairs %zu (hash %016llx%s), gap blocks %zu (hash %016llx; pairs "
                  "dropped: pre-check %ld, no overlap %ld, of which unconverged projections "
                  "%ld), active %d, gap rows %d%s",
                  s.itf.name().c_str(), pairs, static_cast<unsigned long long>(hash),
                  s.pairs_held ? ", held" : "", s.em_blocks,
                  static_cast<unsigned long long>(s.em_blocks_hash), s.em_rejections[0],
                  s.em_rejections[1], s.em_rejections[2], active, rows, roles);
    out.emplace_back(line);
  }
  return out;
}

std::string ContactConstraint::describe_multiplier(std::size_t k) const {
  const int dim = disc_.dim();
  for (const auto& s : sides_) {
    const std::size_t width = s.friction ? static_cast<std::size_t>(dim) : 1;
    const std::size_t n = s.active.size() * width;
    if (k >= n) {
      k -= n;
      continue;
    }
    const std::size_t j = k / width;
    const auto node = s.itf.slave().mesh_nodes[j];
    char line[320];
    std::snprintf(line, sizeof line,
                  "%s slave node %lld (%s, lambda %.4e, g~ %.4e, D %.4e, gap row %d)",
                  s.itf.name().c_str(), static_cast<long long>(node_id(node)),
                  s.active[j] ? "active" : "inactive", s.lambda[k], s.gap[j], s.D[j],
                  s.discrete_gradient ? static_cast<int>(s.em_row[j]) : -1);
    return line;
  }
  return "?";
}

std::string ContactConstraint::describe_node(std::int32_t node) const {
  std::string out;
  for (const auto& s : sides_) {
    const auto& nodes = s.itf.slave().mesh_nodes;
    for (std::size_t j = 0; j < nodes.size(); ++j) {
      if (nodes[j] != node) continue;
      char line[200];
      std::snprintf(line, sizeof line, "%s%s: %s, g~ %.3e", out.empty() ? "" : "; ",
                    s.itf.name().c_str(), s.active[j] ? "active" : "inactive", s.gap[j]);
      out += line;
    }
  }
  return out;
}

} // namespace seam::problem
