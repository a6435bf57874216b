// seam-bench search: seam's tree search against brute force and CGAL's box_intersection_d on
// two nearly touching wavy surfaces (BENCHMARKS.md, "Search").
#include "registry.hpp"

#include "seam/search/facets.hpp"
#include "seam/search/traversal.hpp"
#include "seam/search/tree.hpp"

#ifdef SEAM_HAVE_CGAL
#include <CGAL/Box_intersection_d/Box_with_info_d.h>
#include <CGAL/box_intersection_d.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <linux/perf_event.h>
#include <sys/ioctl.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace {

using namespace seam::search;
using seam::local_index;

/// CPU seconds of this thread. Everything timed here is single-threaded, and on a shared
/// machine CPU time is what the code costs, where wall time would include waiting for a core.
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

/// Core clock cycles of this thread in user space, from the kernel's performance counters
/// (Linux; available() is false elsewhere or when the counters are not accessible). On a
/// shared machine the clock frequency changes with the load of the other cores; cycles do not,
/// so they show the scaling of the code itself next to the CPU time.
class CycleCounter {
public:
  CycleCounter() {
#if defined(__linux__)
    perf_event_attr attr{};
    attr.type = PERF_TYPE_HARDWARE;
    attr.size = sizeof(attr);
    attr.config = PERF_COUNT_HW_CPU_CYCLES;
    attr.exclude_kernel = 1;
    attr.exclude_hv = 1;
    fd_ = static_cast<int>(syscall(SYS_perf_event_open, &attr, 0, -1, -1, 0));
#endif
  }
  ~CycleCounter() {
#if defined(__linux__)
    if (fd_ >= 0) close(fd_);
#endif
  }
  CycleCounter(const CycleCounter&) = delete;
  CycleCounter& operator=(const CycleCounter&) = delete;
  bool available() const {
    return fd_ >= 0;
  }
  double read() const {
    long long v = 0;
#if defined(__linux__)
    if (fd_ >= 0 && ::read(fd_, &v, sizeof(v)) != static_cast<ssize_t>(sizeof(v))) v = 0;
#endif
    return double(v);
  }

private:
  int fd_ = -1;
};

const CycleCounter& cycle_counter() {
  static const CycleCounter counter;
  return counter;
}

struct Surface {
  int dim;
  std::vector<double> coords;
  std::vector<local_index> offsets{0}, conn;
  FacetSurface view() const { return {dim, coords, offsets, conn}; }
};

// Wave shared by both surfaces: amplitude 0.05, wavelength 0.5 on the unit square/interval.
double wave(double x, double y) {
  return 0.05 * std::sin(4.0 * std::numbers::pi * x) * std::sin(4.0 * std::numbers::pi * y);
}

/// Triangulated grid n_x x n_y over [0,1]^2 (shifted by (sx, sy)), lifted onto the wave plus z0;
/// `flip` splits the cells along the other diagonal, so two surfaces do not match.
Surface wavy_triangles(int nx, int ny, double sx, double sy, double z0, bool flip) {
  Surface s{3, {}, {0}, {}};
  s.coords.reserve(3 * std::size_t(nx + 1) * (ny + 1));
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double x = double(i) / nx + sx, y = double(j) / ny + sy;
      s.coords.insert(s.coords.end(), {x, y, z0 + wave(x, 0.25 + y)});
    }
  s.conn.reserve(6 * std::size_t(nx) * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const local_index a = j * (nx + 1) + i, b = a + 1, c = a + nx + 2, d = a + nx + 1;
      if (flip)
        s.conn.insert(s.conn.end(), {a, b, d, b, c, d});
      else
        s.conn.insert(s.conn.end(), {a, b, c, a, c, d});
      s.offsets.push_back(static_cast<local_index>(s.conn.size() - 3));
      s.offsets.push_back(static_cast<local_index>(s.conn.size()));
    }
  return s;
}

/// Polyline of n segments over [0,1] (shifted by sx) on the wave plus y0.
Surface wavy_polyline(int n, double sx, double y0) {
  Surface s{2, {}, {0}, {}};
  for (int i = 0; i <= n; ++i) {
    const double x = double(i) / n + sx;
    s.coords.insert(s.coords.end(), {x, y0 + wave(x, 0.125)});
  }
  for (int i = 0; i < n; ++i) {
    s.conn.insert(s.conn.end(), {i, i + 1});
    s.offsets.push_back(static_cast<local_index>(s.conn.size()));
  }
  return s;
}

/// Seconds per call of `f` in steady state: one warm-up call, then the calls are grouped into
/// samples of at least `min_sample` seconds (so that a 1e3-facet case is timed over thousands
/// of calls, not one that the timer and the first touch of the data dominate), and the fastest
/// of `repeat` samples is divided by its number of calls. `inner` returns the calls per sample,
/// `cycles` the fewest clock cycles per call of any sample (-1 without a cycle counter).
template <class F>
double steady_seconds(int repeat, double min_sample, F&& f, long* inner = nullptr,
                      double* cycles = nullptr) {
  f();
  long n = 1;
  for (;;) {
    const double t0 = cpu_seconds();
    for (long k = 0; k < n; ++k) f();
    if (cpu_seconds() - t0 >= min_sample || n >= (1L << 24)) break;
    n *= 2;
  }
  double best = 1e300, fewest = 1e300;
  const CycleCounter& counter = cycle_counter();
  for (int r = 0; r < repeat; ++r) {
    const double c0 = counter.read();
    const double t0 = cpu_seconds();
    for (long k = 0; k < n; ++k) f();
    best = std::min(best, (cpu_seconds() - t0) / double(n));
    fewest = std::min(fewest, (counter.read() - c0) / double(n));
  }
  if (inner != nullptr) *inner = n;
  if (cycles != nullptr) *cycles = counter.available() ? fewest : -1.0;
  return best;
}

struct SeamTimes {
  double build_s = 0, build_query_s = 0, refit_s = 0, query_s = 0, refit_query_s = 0;
  long inner = 1;                   // calls per timed sample of refit + query
  double refit_query_cycles = -1;   // clock cycles per refit + query (-1: not measured)
  std::vector<CandidatePair> pairs; // sorted
};

/// Build, build + first query, refit (to the moved master, with the step-start positions),
/// query, and refit + query in one loop (the figure of the scaling target), each in steady
/// state (steady_seconds). The trees after the last refit are left in `kept`.
SeamTimes time_seam(const Surface& s, const Surface& m, const std::vector<double>& m_new,
                    TreeOptions opt, int repeat, double min_sample, std::vector<Tree>& kept) {
  SeamTimes t;
  std::vector<CandidatePair> pairs;
  auto build = [&] {
    kept.clear();
    kept.emplace_back(s.view(), opt);
    kept.emplace_back(m.view(), opt);
  };
  t.build_s = steady_seconds(repeat, min_sample, build);
  // Build and a first query: fresh trees and a pair vector with no capacity yet.
  t.build_query_s = steady_seconds(repeat, min_sample, [&] {
    build();
    std::vector<CandidatePair> fresh;
    find_pairs(kept[0], kept[1], fresh);
  });
  auto refit = [&] {
    kept[0].update(s.coords);
    kept[1].update(m_new, m.coords);
  };
  t.refit_s = steady_seconds(repeat, min_sample, refit);
  t.query_s = steady_seconds(repeat, min_sample, [&] { find_pairs(kept[0], kept[1], pairs); });
  t.refit_query_s = steady_seconds(
      repeat, min_sample,
      [&] {
        refit();
        find_pairs(kept[0], kept[1], pairs);
      },
      &t.inner, &t.refit_query_cycles);
  std::sort(pairs.begin(), pairs.end());
  t.pairs = std::move(pairs);
  return t;
}

#ifdef SEAM_HAVE_CGAL
/// CGAL's box_intersection_d on the axis-aligned parts of the trees' facet volumes, timed like
/// seam (steady state, fastest of `repeat` samples of at least `min_sample` seconds). It
/// reorders its input, so every call gets its own copy of the boxes, made outside the timing.
template <int D>
double time_cgal(const Tree& slave, const Tree& master, std::ptrdiff_t cutoff, int repeat,
                 double min_sample, std::size_t expected, std::vector<CandidatePair>& out) {
  using Box = CGAL::Box_intersection_d::Box_with_info_d<float, D, local_index,
                                                        CGAL::Box_intersection_d::ID_EXPLICIT>;
  auto make = [](const Tree& t) {
    std::vector<float> lo, hi;
    t.facet_boxes(lo, hi);
    std::vector<Box> boxes;
    boxes.reserve(t.n_facets());
    for (local_index f = 0; f < t.n_facets(); ++f)
      boxes.emplace_back(lo.data() + std::size_t(f) * D, hi.data() + std::size_t(f) * D, f);
    return boxes;
  };
  const std::vector<Box> bs = make(slave), bm = make(master);
  out.reserve(expected); // as warm as seam's reused pair vector
  std::vector<std::vector<Box>> a, b;
  auto sample = [&](long n) {
    a.assign(n, bs);
    b.assign(n, bm);
    const double t0 = cpu_seconds();
    for (long k = 0; k < n; ++k) {
      out.clear();
      CGAL::box_intersection_d(
          a[k].begin(), a[k].end(), b[k].begin(), b[k].end(),
          [&](const Box& x, const Box& y) {
            out.push_back({x.info(), y.info()});
          },
          cutoff, CGAL::Box_intersection_d::CLOSED, CGAL::Box_intersection_d::BIPARTITE);
    }
    return (cpu_seconds() - t0) / double(n);
  };
  sample(1); // warm-up
  long n = 1;
  while (sample(n) * double(n) < min_sample && n < (1L << 20)) n *= 2;
  double best = 1e300;
  for (int r = 0; r < repeat; ++r) best = std::min(best, sample(n));
  std::sort(out.begin(), out.end());
  return best;
}
#endif

void help() {
  std::printf(
      "usage: seam-bench search --dim 2|3 --facets N [--json] [--cgal-cutoff C[,C2,...]]\n"
      "                         [--repeat R] [--min-sample S] [--leaf-size L]\n"
      "  Two nearly touching wavy surfaces (triangles in 3D, polylines in 2D) of about N\n"
      "  facets each; gap 0.5 h, inflation 0.3 h (h the grid spacing), master moved by ~0.05 h\n"
      "  over the step. Times seam's tree (k-DOP and AABB) build, refit and query, brute\n"
      "  force (N <= 2e4) and CGAL box_intersection_d on the same inflated boxes.\n"
      "  Every figure is the fastest of R samples (default 5, 3 for N > 1e5) of repeated calls\n"
      "  lasting at least S CPU seconds each (default 0.05), divided by the calls per sample.\n"
      "  --cgal-cutoff: CGAL's cutoff (default 10000); with a list the fastest is reported.\n"
      "  --json prints one JSON object as the last line.\n");
}

int run_search(int argc, char** argv) {
  int dim = 3;
  long n_target = 10000;
  bool json = false;
  std::vector<long> cutoffs{10000};
  long cutoff = 10000; // the best of `cutoffs`
  int repeat = 0;
  double min_sample = 0.05;
  int leaf_size = TreeOptions{}.leaf_size;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) throw std::invalid_argument("missing value after " + a);
      return argv[++i];
    };
    if (a == "--dim")
      dim = std::atoi(value());
    else if (a == "--facets")
      n_target = std::lround(std::atof(value()));
    else if (a == "--json")
      json = true;
    else if (a == "--cgal-cutoff") {
      // One cutoff or a comma-separated list; the fastest is reported.
      cutoffs.clear();
      for (std::string list = value(); !list.empty();) {
        const auto comma = list.find(',');
        cutoffs.push_back(std::lround(std::atof(list.substr(0, comma).c_str())));
        list = comma == std::string::npos ? "" : list.substr(comma + 1);
      }
      if (cutoffs.empty() || *std::min_element(cutoffs.begin(), cutoffs.end()) < 1)
        throw std::invalid_argument("--cgal-cutoff needs positive values");
    } else if (a == "--leaf-size")
      leaf_size = std::atoi(value());
    else if (a == "--repeat")
      repeat = std::atoi(value());
    else if (a == "--min-sample")
      min_sample = std::atof(value());
    else if (a == "--help" || a == "-h") {
      help();
      return 0;
    } else
      throw std::invalid_argument("unknown option " + a);
  }
  if ((dim != 2 && dim != 3) || n_target < 2 || n_target > 50'000'000)
    throw std::invalid_argument("need --dim 2|3 and 2 <= --facets <= 5e7");
  if (repeat <= 0) repeat = n_target <= 100'000 ? 5 : 3;
  if (!(min_sample >= 0.0 && min_sample <= 10.0))
    throw std::invalid_argument("--min-sample needs 0 <= S <= 10 seconds");

  // Surfaces: slave on the wave, master 0.5 h above it on a shifted, differently split grid.
  Surface slave, master;
  double h;
  if (dim == 3) {
    const int nx = std::max(1, int(std::lround(std::sqrt(double(n_target) / 2.0))));
    const int ny = std::max(1, int(std::lround(double(n_target) / (2.0 * nx))));
    h = 1.0 / nx;
    slave = wavy_triangles(nx, ny, 0.0, 0.0, 0.0, false);
    master = wavy_triangles(nx, ny, 0.37 * h, 0.61 * h, 0.5 * h, true);
  } else {
    h = 1.0 / double(n_target);
    slave = wavy_polyline(int(n_target), 0.0, 0.0);
    master = wavy_polyline(int(n_target), 0.37 * h, 0.5 * h);
  }
  // Over the step the master moves by 0.05 h along x and towards the slave.
  std::vector<double> master_new = master.coords;
  for (std::size_t i = 0; i < master_new.size(); i += dim) {
    master_new[i] += 0.05 * h;
    master_new[i + dim - 1] -= 0.05 * h;
  }
  const long n_facets = slave.view().n_facets();
  TreeOptions opt;
  opt.leaf_size = leaf_size;
  opt.inflation = 0.3 * std::min(min_edge_length(slave.view()), min_edge_length(master.view()));

  std::vector<Tree> kdop_trees, aabb_trees;
  opt.volume = BoundingVolume::kdop;
  const SeamTimes k = time_seam(slave, master, master_new, opt, repeat, min_sample, kdop_trees);
  opt.volume = BoundingVolume::aabb;
  const SeamTimes x = time_seam(slave, master, master_new, opt, repeat, min_sample, aabb_trees);
  const char* kname = dim == 3 ? "18-DOP" : "8-DOP";

  double brute_s = -1;
  long brute_pairs = -1;
  bool brute_match = false;
  if (n_facets <= 20'000) {
    std::vector<CandidatePair> b;
    const double t0 = cpu_seconds();
    b = find_pairs_brute_force(kdop_trees[0], kdop_trees[1]);
    brute_s = cpu_seconds() - t0;
    brute_pairs = long(b.size());
    brute_match = b == k.pairs;
  }

  double cgal_s = -1;
  std::vector<std::pair<long, double>> cutoff_times;
  long cgal_pairs = -1;
  bool cgal_match = false;
#ifdef SEAM_HAVE_CGAL
  for (long cut : cutoffs) {
    std::vector<CandidatePair> c;
    const double t = dim == 3 ? time_cgal<3>(aabb_trees[0], aabb_trees[1], cut, repeat, min_sample,
                                             x.pairs.size(), c)
                              : time_cgal<2>(aabb_trees[0], aabb_trees[1], cut, repeat, min_sample,
                                             x.pairs.size(), c);
    cutoff_times.emplace_back(cut, t);
    if (cgal_s < 0 || t < cgal_s) {
      cgal_s = t;
      cutoff = cut;
      cgal_pairs = long(c.size());
      cgal_match = c == x.pairs;
    }
  }
#endif

  const double rq = k.refit_query_s;
  std::printf("seam-bench search: %dD, %ld facets per surface, inflation %.3g (0.3 h_min), "
              "leaf size %d, CPU seconds per call, fastest of %d samples of >= %.3g s\n",
              dim, n_facets, opt.inflation, leaf_size, repeat, min_sample);
  std::printf("  %-22s %10s %10s %10s %10s %10s %11s %12s\n", "", "build", "build+query", "refit",
              "query", "refit+query", "pairs", "ns/facet r+q");
  auto row = [&](const char* name, const SeamTimes& t) {
    std::printf("  %-22s %10.3g %10.3g %10.3g %10.3g %10.3g %11zu %12.1f\n", name, t.build_s,
                t.build_query_s, t.refit_s, t.query_s, t.refit_query_s, t.pairs.size(),
                1e9 * t.refit_query_s / double(n_facets));
  };
  row((std::string("seam ") + kname).c_str(), k);
  row("seam AABB", x);
  std::printf("  refit + query timed over %ld calls per sample", k.inner);
  if (k.refit_query_cycles >= 0)
    std::printf("; %.0f clock cycles per facet (%s), %.0f (AABB)", k.refit_query_cycles / n_facets,
                kname, x.refit_query_cycles / n_facets);
  std::printf("\n");
  if (brute_s >= 0)
    std::printf("  %-22s %10.3g %46s %11ld   same pairs as seam %s: %s\n", "brute force", brute_s,
                "", brute_pairs, kname, brute_match ? "yes" : "NO");
  else
    std::printf("  brute force            skipped (N > 2e4)\n");
  if (cgal_s >= 0) {
    std::printf("  %-22s %10.3g %46s %11ld   same pairs as seam AABB: %s\n",
                "CGAL box_intersection_d", cgal_s, "", cgal_pairs, cgal_match ? "yes" : "NO");
    std::printf("  CGAL cutoff %ld%s, closed boxes, bipartite, on seam's inflated AABBs\n", cutoff,
                cutoffs.size() > 1 ? " (fastest tried)" : "");
    if (cutoff_times.size() > 1)
      for (const auto& [cut, t] : cutoff_times) std::printf("    cutoff %8ld: %.3g s\n", cut, t);
    std::printf("  ratios: CGAL / seam(refit+query) = %.2f, CGAL / seam(build+query) = %.2f, "
                "pairs seam %s / AABB = %.3f\n",
                cgal_s / rq, cgal_s / k.build_query_s, kname,
                double(k.pairs.size()) / double(x.pairs.size()));
  } else {
    std::printf("  CGAL: not available in this build\n");
  }
  if (brute_s >= 0) std::printf("  ratio: brute / seam(refit+query) = %.1f\n", brute_s / rq);

  if (json) {
    auto num = [](double v) { return v >= 0 ? std::to_string(v) : std::string("null"); };
    auto cnt = [](long v) { return v >= 0 ? std::to_string(v) : std::string("null"); };
    std::printf("{\"dim\": %d, \"facets\": %ld, \"pairs\": %zu, \"build_s\": %.6g, "
                "\"build_and_query_s\": %.6g, \"refit_s\": %.6g, \"query_s\": %.6g, "
                "\"refit_query_s\": %.6g, \"refit_query_calls_per_sample\": %ld, \"brute_s\": %s, "
                "\"brute_pairs\": %s, \"brute_match\": %s, \"cgal_s\": %s, \"cgal_pairs\": %s, "
                "\"cgal_cutoff\": %ld, \"cgal_match_aabb\": %s, \"aabb_build_s\": %.6g, "
                "\"aabb_refit_s\": %.6g, \"aabb_query_s\": %.6g, \"aabb_refit_query_s\": %.6g, "
                "\"aabb_pairs\": %zu, \"refit_query_ns_per_facet\": %.6g, "
                "\"refit_query_cycles_per_facet\": %s, "
                "\"cgal_over_refit_query\": %s, \"cgal_over_build_query\": %s}\n",
                dim, n_facets, k.pairs.size(), k.build_s, k.build_query_s, k.refit_s, k.query_s,
                k.refit_query_s, k.inner, num(brute_s).c_str(), cnt(brute_pairs).c_str(),
                brute_s >= 0 ? (brute_match ? "true" : "false") : "null", num(cgal_s).c_str(),
                cnt(cgal_pairs).c_str(), cutoff,
                cgal_s >= 0 ? (cgal_match ? "true" : "false") : "null", x.build_s, x.refit_s,
                x.query_s, x.refit_query_s, x.pairs.size(), 1e9 * rq / n_facets,
                num(k.refit_query_cycles / n_facets).c_str(),
                cgal_s >= 0 ? num(cgal_s / rq).c_str() : "null",
                cgal_s >= 0 ? num(cgal_s / k.build_query_s).c_str() : "null");
  }
  return (brute_s >= 0 && !brute_match) || (cgal_s >= 0 && !cgal_match) ? 1 : 0;
}

const seam::bench::Register registered{
    "search", "contact search: seam tree vs brute force and CGAL box_intersection_d", &run_search};

} // namespace
