#include "seam/parallel/rcb.hpp"

#include "seam/common/error.hpp"
#include "seam/parallel/exchange.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace seam::parallel {

namespace {

constexpr double kWeightScale = 0x1p50; // global weight sum in integer units

/// Search state of one cut: the interval [a, b) of the cut axis (phase 1) or the id range
/// [ga, gb) inside the slab [a, b) (phase 2) that holds the target weight.
struct CutSearch {
  int phase = 1; // 1 coordinate, 2 id, 0 done
  int rounds = 0;
  double a = 0.0, b = 0.0;
  global_index ga = 0, gb = 0;
  std::int64_t below = 0;  // weight of the points before the interval
  std::int64_t target = 0; // weight the low side should get
  std::int64_t total = 0;

  double edge(int j, int n_bins) const {
    if (j <= 0) return a;
    if (j >= n_bins) return b;
    return std::min(b, a + (b - a) * (static_cast<double>(j) / n_bins));
  }
  int coordinate_bin(double x, int n_bins) const {
    int j = static_cast<int>(std::clamp((x - a) / (b - a) * n_bins, 0.0, n_bins - 1.0));
    while (j > 0 && x < edge(j, n_bins)) --j;
    while (j < n_bins - 1 && x >= edge(j + 1, n_bins)) ++j;
    return j;
  }
  global_index id_width(int n_bins) const { return (gb - ga + n_bins - 1) / n_bins; }
  global_index id_edge(int j, int n_bins) const {
    return std::min(gb, ga + static_cast<global_index>(j) * id_width(n_bins));
  }
};

} // namespace

Rcb::Rcb(int dim, const RcbOptions& options) : dim_(dim), options_(options) {
  SEAM_CHECK(dim >= 1 && dim <= 3, InputError, "rcb: dimension must be 1, 2 or 3, got ", dim);
  SEAM_CHECK(options.n_bins >= 2 && options.tolerance >= 0.0 && options.max_rounds >= 1, InputError,
             "rcb: n_bins >= 2, tolerance >= 0 and max_rounds >= 1 required");
}

void Rcb::partition(MPI_Comm comm, std::span<const double> points, std::span<const double> weights,
                    std::span<const global_index> ids, std::span<int> parts) {
  run(comm, points, weights, ids, parts, false);
}

void Rcb::repartition(MPI_Comm comm, std::span<const double> points,
                      std::span<const double> weights, std::span<const global_index> ids,
                      std::span<int> parts) {
  run(comm, points, weights, ids, parts, true);
}

int Rcb::part_of(const double* x, global_index id) const {
  SEAM_ASSERT(has_cuts());
  int n = 0;
  while (nodes_[n].low >= 0) n = nodes_[n].cut.low_side(x, id) ? nodes_[n].low : nodes_[n].high;
  return nodes_[n].first_part;
}

std::vector<RcbCut> Rcb::cuts() const {
  std::vector<RcbCut> out;
  for (const auto& n : nodes_)
    if (n.low >= 0) out.push_back(n.cut);
  return out;
}

void Rcb::shape(int n_parts) {
  n_parts_ = n_parts;
  nodes_.assign(1, Node{0, n_parts, {}, -1, -1});
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    if (nodes_[k].n_parts < 2) continue;
    const int first = nodes_[k].first_part, np = nodes_[k].n_parts, n_low = np / 2;
    nodes_[k].low = static_cast<int>(nodes_.size());
    nodes_[k].high = nodes_[k].low + 1;
    nodes_.push_back({first, n_low, {}, -1, -1});
    nodes_.push_back({first + n_low, np - n_low, {}, -1, -1});
  }
}

void Rcb::restore(int n_parts, std::span<const RcbCut> cuts) {
  bool bad = n_parts < 1 || cuts.size() != static_cast<std::size_t>(n_parts - 1);
  for (const auto& c : cuts) bad |= c.axis < 0 || c.axis >= dim_;
  SEAM_CHECK(!bad, InputError, "rcb: a tree of ", n_parts, " parts has ", n_parts - 1,
             " cuts along axes below ", dim_, ", got ", cuts.size());
  shape(n_parts);
  std::size_t next = 0;
  for (auto& node : nodes_)
    if (node.low >= 0) node.cut = cuts[next++];
}

void Rcb::run(MPI_Comm comm, std::span<const double> points, std::span<const double> weights,
              std::span<const global_index> ids, std::span<int> parts, bool keep_axes) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  const std::size_t n = ids.size();
  bool bad =
      points.size() != n * dim_ || parts.size() != n || (!weights.empty() && weights.size() != n);
  for (const double w : weights) bad |= !(w >= 0.0 && std::isfinite(w));
  for (const double x : points) bad |= !std::isfinite(x);
  check_collectively(comm, bad,
                     "rcb: need dim finite coordinates, one non-negative weight (or none) and "
                     "one id and part slot per point");

  // The tree shape depends only on the number of parts; keep the axes if asked and possible.
  std::vector<Node> old = std::move(nodes_);
  keep_axes = keep_axes && n_parts_ == size && !old.empty();
  shape(size);
  if (keep_axes)
    for (std::size_t k = 0; k < nodes_.size(); ++k) nodes_[k].cut.axis = old[k].cut.axis;

  // Integer weights: exact sums, hence identical decisions on every rank.
  double total = 0.0;
  for (const double w : weights) total += w;
  MPI_Allreduce(MPI_IN_PLACE, &total, 1, MPI_DOUBLE, MPI_SUM, comm);
  const bool unit = !(total > 0.0);
  std::int64_t n_global = static_cast<std::int64_t>(n);
  MPI_Allreduce(MPI_IN_PLACE, &n_global, 1, MPI_INT64_T, MPI_SUM, comm);
  const double scale =
      unit ? kWeightScale / std::max<std::int64_t>(n_global, 1) : kWeightScale / total;
  std::vector<std::int64_t> w(n);
  for (std::size_t i = 0; i < n; ++i) w[i] = std::llround((unit ? 1.0 : weights[i]) * scale);
  global_index id_range[2] = {std::numeric_limits<global_index>::max(),
                              std::numeric_limits<global_index>::max()}; // min, -max
  for (const global_index id : ids) {
    id_range[0] = std::min(id_range[0], id);
    id_range[1] = std::min(id_range[1], -id);
  }
  MPI_Allreduce(MPI_IN_PLACE, id_range, 2, MPI_INT64_T, MPI_MIN, comm);

  const int n_bins = options_.n_bins;
  n_rounds_ = 0;
  std::vector<int> node_of(n, 0);
  std::vector<int> level{0};
  std::vector<double> box;
  std::vector<std::int64_t> hist;
  std::vector<CutSearch> search;
  while (!level.empty()) {
    // Only inner nodes are split; slot_of maps a tree node to its place in this level.
    std::vector<int> active;
    for (const int k : level)
      if (nodes_[k].n_parts > 1) active.push_back(k);
    if (active.empty()) break;
    const auto n_active = static_cast<int>(active.size());
    std::vector<int> slot_of(nodes_.size(), -1);
    for (int s = 0; s < n_active; ++s) slot_of[active[s]] = s;

    // Bounding box (as minima of lo and -hi) and weight of every node of the level.
    box.assign(static_cast<std::size_t>(n_active) * 2 * dim_,
               std::numeric_limits<double>::infinity());
    hist.assign(n_active, 0);
    for (std::size_t i = 0; i < n; ++i) {
      const int s = slot_of[node_of[i]];
      if (s < 0) continue;
      for (int d = 0; d < dim_; ++d) {
        box[(s * 2) * dim_ + d] = std::min(box[(s * 2) * dim_ + d], points[i * dim_ + d]);
        box[(s * 2 + 1) * dim_ + d] = std::min(box[(s * 2 + 1) * dim_ + d], -points[i * dim_ + d]);
      }
      hist[s] += w[i];
    }
    MPI_Allreduce(MPI_IN_PLACE, box.data(), static_cast<int>(box.size()), MPI_DOUBLE, MPI_MIN,
                  comm);
    MPI_Allreduce(MPI_IN_PLACE, hist.data(), n_active, MPI_INT64_T, MPI_SUM, comm);

    search.assign(n_active, {});
    for (int s = 0; s < n_active; ++s) {
      Node& node = nodes_[active[s]];
      CutSearch& c = search[s];
      c.total = hist[s];
      const double* lo = &box[(s * 2) * dim_];
      const double* neg_hi = &box[(s * 2 + 1) * dim_];
      if (!keep_axes) {
        node.cut.axis = 0;
        for (int d = 1; d < dim_; ++d)
          if (-neg_hi[d] - lo[d] > -neg_hi[node.cut.axis] - lo[node.cut.axis]) node.cut.axis = d;
      }
      const int ax = node.cut.axis;
      if (c.total == 0 || !(lo[ax] <= -neg_hi[ax])) { // no weight to split: any plane will do
        c.phase = 0;
        node.cut.lo = node.cut.hi = std::isfinite(lo[ax]) ? lo[ax] : 0.0;
        continue;
      }
      c.a = lo[ax];
      c.b = std::nextafter(-neg_hi[ax], std::numeric_limits<double>::infinity());
      c.target =
          std::llround(static_cast<long double>(c.total) * (node.n_parts / 2) / node.n_parts);
    }

    // Histogram rounds, one Allreduce each for all cuts of the level.
    const auto tolerance_of = [&](const CutSearch& c) {
      return static_cast<std::int64_t>(options_.tolerance * static_cast<double>(c.total));
    };
    while (std::any_of(search.begin(), search.end(), [](const auto& c) { return c.phase; })) {
      ++n_rounds_;
      hist.assign(static_cast<std::size_t>(n_active) * n_bins, 0);
      // Per bin the least and (negated) greatest coordinate: a heavy bin narrows to its own
      // points, and a bin whose points share one coordinate is recognized at once.
      box.assign(hist.size() * 2, std::numeric_limits<double>::infinity());
      for (std::size_t i = 0; i < n; ++i) {
        const int s = slot_of[node_of[i]];
        if (s < 0 || !search[s].phase) continue;
        const CutSearch& c = search[s];
        const double x = points[i * dim_ + nodes_[active[s]].cut.axis];
        if (!(x >= c.a && x < c.b)) continue;
        int j = 0;
        if (c.phase == 1) {
          j = c.coordinate_bin(x, n_bins);
        } else {
          if (ids[i] < c.ga || ids[i] >= c.gb) continue;
          j = static_cast<int>((ids[i] - c.ga) / c.id_width(n_bins));
        }
        const std::size_t b = static_cast<std::size_t>(s) * n_bins + j;
        hist[b] += w[i];
        box[2 * b] = std::min(box[2 * b], x);
        box[2 * b + 1] = std::min(box[2 * b + 1], -x);
      }
      MPI_Allreduce(MPI_IN_PLACE, hist.data(), static_cast<int>(hist.size()), MPI_INT64_T, MPI_SUM,
                    comm);
      MPI_Allreduce(MPI_IN_PLACE, box.data(), static_cast<int>(box.size()), MPI_DOUBLE, MPI_MIN,
                    comm);
      for (int s = 0; s < n_active; ++s) {
        CutSearch& c = search[s];
        if (!c.phase) continue;
        RcbCut& cut = nodes_[active[s]].cut;
        const std::int64_t* h = &hist[static_cast<std::size_t>(s) * n_bins];
        std::int64_t cum = c.below;
        int j = 0;
        for (; j < n_bins - 1 && cum + h[j] < c.target; ++j) cum += h[j];
        const bool lower = c.target - cum <= cum + h[j] - c.target; // nearer bin edge
        ++c.rounds;
        const bool light = h[j] <= tolerance_of(c);
        if (c.phase == 1) {
          const double e0 = c.edge(j, n_bins), e1 = c.edge(j + 1, n_bins);
          const std::size_t b = static_cast<std::size_t>(s) * n_bins + j;
          const double x_min = box[2 * b], x_max = -box[2 * b + 1];
          if (light) {
            cut.lo = cut.hi = lower ? e0 : e1;
            c.phase = 0;
          } else if (x_min == x_max || c.rounds >= options_.max_rounds) {
            // A heavy slab of equal coordinates (a row of a structured mesh): split it by id.
            const double b_end = std::nextafter(x_max, std::numeric_limits<double>::infinity());
            c = {2, 0, x_min, b_end, id_range[0], -id_range[1] + 1, cum, c.target, c.total};
          } else {
            c.a = x_min;
            c.b = std::nextafter(x_max, std::numeric_limits<double>::infinity());
            c.below = cum;
          }
        } else {
          const global_index g0 = c.id_edge(j, n_bins), g1 = c.id_edge(j + 1, n_bins);
          if (light || g1 - g0 <= 1 || c.rounds >= options_.max_rounds) {
            cut.lo = c.a;
            cut.hi = c.b;
            cut.id_cut = lower ? g0 : g1;
            c.phase = 0;
          } else {
            c.ga = g0;
            c.gb = g1;
            c.below = cum;
          }
        }
      }
    }

    std::vector<int> next;
    for (const int k : active) {
      next.push_back(nodes_[k].low);
      next.push_back(nodes_[k].high);
    }
    for (std::size_t i = 0; i < n; ++i) {
      const Node& node = nodes_[node_of[i]];
      if (slot_of[node_of[i]] < 0) continue;
      node_of[i] = node.cut.low_side(&points[i * dim_], ids[i]) ? node.low : node.high;
    }
    level = std::move(next);
  }
  for (std::size_t i = 0; i < n; ++i) parts[i] = nodes_[node_of[i]].first_part;
}

double part_imbalance(MPI_Comm comm, std::span<const double> weights, std::span<const int> parts,
                      int n_parts, std::vector<double>* part_weights) {
  std::vector<double> sum(n_parts, 0.0);
  bool bad = !weights.empty() && weights.size() != parts.size();
  for (std::size_t i = 0; i < parts.size() && !bad; ++i) {
    bad |= parts[i] < 0 || parts[i] >= n_parts;
    if (!bad) sum[parts[i]] += weights.empty() ? 1.0 : weights[i];
  }
  check_collectively(comm, bad, "part_imbalance: one weight (or none) and a valid part per point");
  MPI_Allreduce(MPI_IN_PLACE, sum.data(), n_parts, MPI_DOUBLE, MPI_SUM, comm);
  double max = 0.0, total = 0.0;
  for (const double s : sum) {
    max = std::max(max, s);
    total += s;
  }
  if (part_weights) *part_weights = sum;
  return total > 0.0 ? max / (total / n_parts) : 1.0;
}

std::int64_t count_moving(MPI_Comm comm, std::span<const int> parts) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::int64_t moving =
      std::count_if(parts.begin(), parts.end(), [rank](int p) { return p != rank; });
  MPI_Allreduce(MPI_IN_PLACE, &moving, 1, MPI_INT64_T, MPI_SUM, comm);
  return moving;
}

} // namespace seam::parallel
