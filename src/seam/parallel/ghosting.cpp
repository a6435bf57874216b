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

} // namespace seam::parallel
