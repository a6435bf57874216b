#include "seam/parallel/ghosting.hpp"

#include "seam/common/error.hpp"
#include "seam/parallel/exchange.hpp"
#include "seam/search/kdop.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

namespace seam::parallel {

namespace {

template <int Dim>
void boxes_of(const search::FacetSurface& s, double inflation, std::vector<Box>& out,
              std::span<const double> old_coords) {
  out.resize(s.n_facets());
  for (local_index f = 0; f < s.n_facets(); ++f) {
    // The axis slabs of search's k-DOP: same projections (the coordinates), same widening.
    search::KdopBuilder<Dim, Dim> b;
    for (local_index k = s.offsets[f]; k < s.offsets[f + 1]; ++k) {
      const std::size_t i = static_cast<std::size_t>(s.connectivity[k]) * Dim;
      b.add_point(s.coords.data() + i);
      if (!old_coords.empty()) b.add_point(old_coords.data() + i);
    }
    const auto k = b.finish(inflation);
    Box& box = out[f];
    for (int d = 0; d < Dim; ++d) {
      box.lo[d] = k.lo[d];
      box.hi[d] = k.hi[d];
    }
  }
}

Box empty_box() {
  Box b;
  b.lo.fill(std::numeric_limits<float>::infinity());
  b.hi.fill(-std::numeric_limits<float>::infinity());
  return b;
}

void grow(Box& m, const Box& b, int dim) {
  for (int d = 0; d < dim; ++d) {
    m.lo[d] = std::min(m.lo[d], b.lo[d]);
    m.hi[d] = std::max(m.hi[d], b.hi[d]);
  }
}

Box merged(int dim, std::span<const Box> boxes) {
  Box m = empty_box();
  for (const Box& b : boxes) grow(m, b, dim);
  return m;
}

// Splits the boxes `order` into k clusters by median splits of their centres; appends the
// clusters' boxes.
void split(int dim, std::span<const Box> boxes, std::span<local_index> order, int k,
           std::vector<Box>& out) {
  if (order.empty()) return;
  if (k <= 1 || order.size() == 1) {
    Box m = empty_box();
    for (const local_index f : order) grow(m, boxes[f], dim);
    out.push_back(m);
    return;
  }
  Box range = empty_box(); // of the centres (times two)
  for (const local_index f : order) {
    Box c;
    for (int d = 0; d < dim; ++d) c.lo[d] = c.hi[d] = boxes[f].lo[d] + boxes[f].hi[d];
    grow(range, c, dim);
  }
  int axis = 0;
  for (int d = 1; d < dim; ++d)
    if (range.hi[d] - range.lo[d] > range.hi[axis] - range.lo[axis]) axis = d;
  const std::size_t mid = order.size() / 2;
  std::nth_element(
      order.begin(), order.begin() + mid, order.end(), [&](local_index a, local_index b) {
        return boxes[a].lo[axis] + boxes[a].hi[axis] < boxes[b].lo[axis] + boxes[b].hi[axis];
      });
  split(dim, boxes, order.subspan(0, mid), k / 2, out);
  split(dim, boxes, order.subspan(mid), k - k / 2, out);
}

} // namespace

void facet_boxes(const search::FacetSurface& surface, double inflation, std::vector<Box>& out,
                 std::span<const double> old_coords) {
  SEAM_CHECK(old_coords.empty() || old_coords.size() == surface.coords.size(), InputError,
             "facet_boxes: step-start coordinates must have the layout of the coordinates");
  if (surface.dim == 2)
    boxes_of<2>(surface, inflation, out, old_coords);
  else
    boxes_of<3>(surface, inflation, out, old_coords);
}

std::vector<Box> cluster_boxes(int dim, std::span<const Box> boxes, int max_boxes) {
  SEAM_CHECK(max_boxes >= 1, InputError, "cluster_boxes: max_boxes must be >= 1");
  std::vector<local_index> order(boxes.size());
  std::iota(order.begin(), order.end(), 0);
  std::vector<Box> out;
  split(dim, boxes, order, max_boxes, out);
  return out;
}

SurfacePart ghost_overlapping(MPI_Comm comm, std::span<const Box> region, const SurfacePart& master,
                              double inflation, ExchangeStats* stats) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  std::vector<std::int64_t> box_offsets;
  const std::vector<Box> all = allgatherv<Box>(comm, region, box_offsets);
  const int dim = master.dim; // only used where this rank has master facets
  std::vector<Box> rank_box(size);
  for (int r = 0; r < size; ++r)
    rank_box[r] =
        merged(dim, std::span(all).subspan(box_offsets[r], box_offsets[r + 1] - box_offsets[r]));

  std::vector<Box> boxes;
  facet_boxes(master.view(), inflation, boxes);
  // Destinations, grouped by rank: a rank's box first, then its clusters.
  std::vector<std::int64_t> send_offsets(size + 1, 0);
  std::vector<local_index> send;
  for (int r = 0; r < size; ++r) {
    for (local_index f = 0; f < master.n_facets(); ++f) {
      if (!overlap(boxes[f], rank_box[r], dim)) continue;
      for (std::int64_t b = box_offsets[r]; b < box_offsets[r + 1]; ++b)
        if (overlap(boxes[f], all[b], dim)) {
          send.push_back(f);
          break;
        }
    }
    send_offsets[r + 1] = static_cast<std::int64_t>(send.size());
  }
  return send_facets(comm, master, send_offsets, send, stats);
}

SurfacePart ghost_masters(MPI_Comm comm, const SurfacePart& slave, const SurfacePart& master,
                          double inflation, const GhostingOptions& options, ExchangeStats* stats) {
  check_collectively(comm, options.boxes_per_rank < 1, "ghosting: boxes_per_rank must be >= 1");
  std::vector<Box> boxes;
  facet_boxes(slave.view(), inflation, boxes);
  const std::vector<Box> region = cluster_boxes(slave.dim, boxes, options.boxes_per_rank);
  return ghost_overlapping(comm, region, master, inflation, stats);
}

VerletGhosts::VerletGhosts(MPI_Comm comm, double inflation, double skin,
                           const GhostingOptions& options)
    : comm_(comm), inflation_(inflation), skin_(std::max(skin, 0.0)), options_(options) {
  SEAM_CHECK(inflation >= 0.0, InputError, "ghosting: inflation must be >= 0");
}

bool VerletGhosts::still_valid(const SurfacePart& part, const std::vector<global_index>& ids,
                               const std::vector<double>& coords) const {
  if (part.facet_ids != ids || part.coords.size() != coords.size()) return false;
  // Half the skin, less a margin for the round-off of positions and boxes.
  const double half = 0.5 * skin_ * (1.0 - 1e-6), limit = half * half;
  const auto dim = static_cast<std::size_t>(part.dim);
  for (std::size_t i = 0; i < coords.size(); i += dim) {
    double d2 = 0.0;
    for (std::size_t c = 0; c < dim; ++c) {
      const double d = part.coords[i + c] - coords[i + c];
      d2 += d * d;
    }
    if (d2 > limit) return false;
  }
  return true;
}

bool VerletGhosts::update(const SurfacePart& slave, const SurfacePart& master,
                          std::span<const double> positions,
                          std::span<const global_index> position_ids) {
  ++n_updates_;
  int reuse = exchanged_ && skin_ > 0.0 && still_valid(slave, slave_ids_, slave_coords_) &&
              still_valid(master, master_ids_, master_coords_);
  MPI_Allreduce(MPI_IN_PLACE, &reuse, 1, MPI_INT, MPI_LAND, comm_);
  if (reuse) {
    SEAM_CHECK(!positions.empty(), InputError,
               "ghosting: reused ghosts need the current node positions");
    const auto dim = static_cast<std::size_t>(ghosts_.dim);
    for (std::size_t i = 0; i < ghosts_.node_ids.size(); ++i) {
      const auto id = ghosts_.node_ids[i];
      auto at = static_cast<std::size_t>(id);
      if (!position_ids.empty()) {
        const auto it = std::lower_bound(position_ids.begin(), position_ids.end(), id);
        SEAM_CHECK(it != position_ids.end() && *it == id, InternalError, "ghosting: node ", id,
                   " of a reused ghost has no position");
        at = static_cast<std::size_t>(it - position_ids.begin());
      }
      for (std::size_t c = 0; c < dim; ++c) ghosts_.coords[i * dim + c] = positions[at * dim + c];
    }
    return false;
  }
  // Half the skin on each side: the boxes of two facets may then approach by the whole skin.
  ghosts_ = ghost_masters(comm_, slave, master, inflation_ + 0.5 * skin_, options_, &stats_);
  exchanged_ = true;
  ++n_exchanges_;
  slave_ids_ = slave.facet_ids;
  master_ids_ = master.facet_ids;
  slave_coords_ = slave.coords;
  master_coords_ = master.coords;
  return true;
}

} // namespace seam::parallel
