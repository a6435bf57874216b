// seam-bench linearization: cost of the linearized mortar kernel that finite-deformation
// contact evaluates every Newton iteration (ALGORITHMS.md §5). A slave grid and a turned,
// shifted master grid of similar size on a curved surface (3D: tri3, quad4, tri6, quad8; 2D:
// line2, line3); candidates by brute force (facet centres within the reach of the pair
// kernel's own pre-check). Per case, over the same overlapping pairs:
//   (a) integrate_pair, the value path (the baseline),
//   (b) linearize_pair: the same values and their derivatives,
//   (c) linearize_slave_facet per slave facet over its candidates (nodal normals chained in),
// in microseconds per pair / per slave facet, with the ratio (b)/(a). Goal: (b) <= 40 us for a
// linear 3D pair, <= 5 us for a line2 pair.
#include "allocation_counter.hpp"
#include "registry.hpp"
#include "surface.hpp"

#include "seam/mortar/interface.hpp"
#include "seam/mortar/linearization.hpp"
#include "seam/mortar/normals.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using seam::local_index;
using seam::fem::CellType;
namespace mortar = seam::mortar;

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

/// Best of `repeat` runs of f, each repeating f until 0.05 CPU seconds have passed; seconds
/// per call of f.
template <class F> double best_seconds(int repeat, F&& f) {
  double best = 1e300;
  for (int r = 0; r < repeat; ++r) {
    int calls = 0;
    const double t0 = cpu_seconds();
    double dt = 0.0;
    do {
      f();
      ++calls;
      dt = cpu_seconds() - t0;
    } while (dt < 0.05);
    best = std::min(best, dt / calls);
  }
  return best;
}

using seam::bench::Surface;
using seam::bench::surface_2d;

double bump(double x, double y) {
  return 0.1 * std::sin(std::numbers::pi * x) * std::sin(std::numbers::pi * y);
}

/// n x n cells of size h over [origin, origin + n h]^2 turned by `angle` about (0.5, 0.5), on
/// the bump, `lift` above it. The slave turns counter-clockwise seen from +z (normal up), the
/// master clockwise. Quadratic facets take their mid-side nodes from the lattice of spacing
/// h / 2; tri3 and tri6 split each cell along a diagonal.
Surface surface_3d(CellType type, int n, double h, double angle, double origin, double lift,
                   bool slave) {
  Surface s;
  const bool quadratic = type == CellType::tri6 || type == CellType::quad8;
  const int order = quadratic ? 2 : 1;
  const int m = order * n + 1;
  const double c = std::cos(angle), sn = std::sin(angle);
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) {
      const double u = origin + i * h / order - 0.5, v = origin + j * h / order - 0.5;
      const double x = 0.5 + c * u - sn * v, y = 0.5 + sn * u + c * v;
      s.coords.insert(s.coords.end(), {x, y, bump(x, y) + lift});
    }
  const auto id = [m](int i, int j) { return static_cast<local_index>(j * m + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int I = order * i, J = order * j, o = order;
      const local_index a = id(I, J), b = id(I + o, J), cc = id(I + o, J + o), d = id(I, J + o);
      if (type == CellType::quad4) {
        s.add(type, slave ? std::vector<local_index>{a, b, cc, d}
                          : std::vector<local_index>{a, d, cc, b});
      } else if (type == CellType::tri3) {
        s.add(type, slave ? std::vector<local_index>{a, b, cc} : std::vector<local_index>{a, d, b});
        s.add(type,
              slave ? std::vector<local_index>{a, cc, d} : std::vector<local_index>{b, d, cc});
      } else if (type == CellType::tri6) {
        const local_index ab = id(I + 1, J), bc = id(I + 2, J + 1), ac = id(I + 1, J + 1),
                          cd = id(I + 1, J + 2), da = id(I, J + 1);
        if (slave) {
          s.add(type, {a, b, cc, ab, bc, ac});
          s.add(type, {a, cc, d, ac, cd, da});
        } else {
          s.add(type, {a, d, cc, da, cd, ac});
          s.add(type, {a, cc, b, ac, bc, ab});
        }
      } else {
        const local_index ab = id(I + 1, J), bc = id(I + 2, J + 1), cd = id(I + 1, J + 2),
                          da = id(I, J + 1);
        s.add(type, slave ? std::vector<local_index>{a, b, cc, d, ab, bc, cd, da}
                          : std::vector<local_index>{a, d, cc, b, da, cd, bc, ab});
      }
    }
  return s;
}

struct Case {
  std::string name;
  bool linear = true;
  int n_slave = 0;
  long n_pairs = 0; ///< overlapping pairs
  double candidates_per_facet = 0;
  double value_us = 0, pair_us = 0, facet_us = 0;
  double allocations_per_pair = 0;
};

template <int Dim> Eigen::Matrix<double, Dim, 1> facet_center(const mortar::Facet<Dim>& f) {
  return f.x.leftCols(f.n_nodes).rowwise().mean();
}

template <int Dim>
Case run_case(const std::string& name, const Surface& slave_surface, const Surface& master_surface,
              mortar::Multiplier multiplier, int repeat) {
  Case r;
  r.name = name;
  const mortar::FacetSet slave = slave_surface.facets(), master = master_surface.facets();
  r.linear = seam::fem::order(slave.types[0]) == 1;
  r.n_slave = slave.n_facets();
  mortar::MortarOptions options;
  options.multiplier = multiplier;

  // Slave facets prepared as the interface assembly does (averaged normals, dual basis).
  const std::vector<double> normals = mortar::averaged_nodal_normals(slave);
  std::vector<mortar::SlaveFacet<Dim>> slaves(static_cast<std::size_t>(slave.n_facets()));
  for (local_index f = 0; f < slave.n_facets(); ++f) {
    auto& sf = slaves[static_cast<std::size_t>(f)];
    sf.facet = mortar::gather_facet<Dim>(slave, f);
    const auto nodes = slave.facet_nodes(f);
    for (int i = 0; i < sf.facet.n_nodes; ++i)
      for (int a = 0; a < Dim; ++a)
        sf.normals(a, i) = normals[static_cast<std::size_t>(nodes[i]) * Dim + a];
    sf.basis = mortar::make_slave_basis(sf.facet, multiplier);
  }
  std::vector<mortar::Facet<Dim>> masters;
  for (local_index f = 0; f < master.n_facets(); ++f)
    masters.push_back(mortar::gather_facet<Dim>(master, f));

  // Overlapping pairs, grouped by slave facet.
  std::vector<std::vector<local_index>> candidates(slaves.size());
  std::vector<std::pair<local_index, local_index>> pairs;
  for (local_index s = 0; s < slave.n_facets(); ++s) {
    for (local_index m = 0; m < master.n_facets(); ++m) {
      const auto& sf = slaves[static_cast<std::size_t>(s)];
      const auto& mf = masters[static_cast<std::size_t>(m)];
      if ((facet_center(sf.facet) - facet_center(mf)).norm() > 2.0) continue;
      if (mortar::integrate_pair(sf, mf, options.pair).n_cells == 0) continue;
      candidates[static_cast<std::size_t>(s)].push_back(m);
      pairs.emplace_back(s, m);
    }
  }
  r.n_pairs = static_cast<long>(pairs.size());
  if (pairs.empty()) throw std::runtime_error(name + ": no overlapping pairs");
  r.candidates_per_facet = double(pairs.size()) / double(slaves.size());

  double sink = 0.0;
  r.value_us = 1e6 / double(pairs.size()) * best_seconds(repeat, [&] {
                 for (const auto& [s, m] : pairs)
                   sink +=
                       mortar::integrate_pair(slaves[static_cast<std::size_t>(s)],
                                              masters[static_cast<std::size_t>(m)], options.pair)
                           .area;
               });
  mortar::PairLinearization lin;
  const auto pair_pass = [&] {
    for (const auto& [s, m] : pairs) {
      mortar::linearize_pair(slaves[static_cast<std::size_t>(s)],
                             masters[static_cast<std::size_t>(m)], options.pair, lin);
      sink += lin.values.area;
    }
  };
  pair_pass();
  const auto before = seam::bench::AllocationCount::now();
  pair_pass();
  const auto allocations = seam::bench::AllocationCount::now() - before;
  r.allocations_per_pair =
      double(std::max(allocations.operator_new, allocations.malloc)) / double(pairs.size());
  r.pair_us = 1e6 / double(pairs.size()) * best_seconds(repeat, pair_pass);

  const mortar::NodeFacets adjacency = mortar::node_facets(slave);
  mortar::SlaveFacetLinearization facet_lin;
  r.facet_us = 1e6 / double(slaves.size()) * best_seconds(repeat, [&] {
                 for (local_index s = 0; s < slave.n_facets(); ++s) {
                   mortar::linearize_slave_facet(slave, master, adjacency, s,
                                                 candidates[static_cast<std::size_t>(s)], options,
                                                 facet_lin);
                   sink += facet_lin.area;
                 }
               });
  if (!(sink > 0.0)) throw std::runtime_error(name + ": nothing integrated");
  return r;
}

void help() {
  std::printf(
      "usage: seam-bench linearization [--repeat R] [--standard] [--cases c1,c2,...]\n"
      "  Slave grid against a turned (0.3 rad), shifted master grid of similar size on a\n"
      "  curved surface; cases line2, line3 (2D), tri3, quad4, tri6, quad8 (3D), default\n"
      "  all. Over the overlapping pairs, CPU microseconds of one core (best of R, default\n"
      "  3): (a) integrate_pair, (b) linearize_pair per pair, ratio (b)/(a), and\n"
      "  (c) linearize_slave_facet per slave facet against its overlapping masters.\n"
      "  --standard uses standard instead of dual multipliers.\n"
      "  Goal: (b) <= 40 us per linear 3D pair, <= 5 us per line2 pair.\n");
}

int run_linearization(int argc, char** argv) {
  int repeat = 3;
  auto multiplier = mortar::Multiplier::dual;
  std::vector<std::string> cases{"line2", "line3", "tri3", "quad4", "tri6", "quad8"};
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) throw std::invalid_argument("missing value after " + a);
      return argv[++i];
    };
    if (a == "--repeat") {
      repeat = std::max(1, std::atoi(value()));
    } else if (a == "--standard") {
      multiplier = mortar::Multiplier::standard;
    } else if (a == "--cases") {
      cases.clear();
      for (std::string list = value(); !list.empty();) {
        const auto comma = list.find(',');
        cases.push_back(list.substr(0, comma));
        list = comma == std::string::npos ? "" : list.substr(comma + 1);
      }
    } else if (a == "--help" || a == "-h") {
      help();
      return 0;
    } else {
      throw std::invalid_argument("unknown option " + a);
    }
  }

  std::vector<Case> results;
  for (const std::string& c : cases) {
    const std::string name = c + "-" + c;
    if (c == "line2" || c == "line3") {
      const CellType type = c == "line2" ? CellType::line2 : CellType::line3;
      const Surface s = surface_2d(
          type, 16, 1.0 / 16, 0.0, [](double x) { return bump(x, 0.5); }, true);
      const Surface m = surface_2d(
          type, 15, 1.1 / 15, -0.04, [](double x) { return bump(x, 0.5) + 0.005; }, false);
      results.push_back(run_case<2>(name, s, m, multiplier, repeat));
    } else {
      CellType type;
      if (c == "tri3")
        type = CellType::tri3;
      else if (c == "quad4")
        type = CellType::quad4;
      else if (c == "tri6")
        type = CellType::tri6;
      else if (c == "quad8")
        type = CellType::quad8;
      else
        throw std::invalid_argument("unknown case " + c);
      const Surface s = surface_3d(type, 6, 1.0 / 6, 0.0, 0.0, 0.0, true);
      const Surface m = surface_3d(type, 7, 1.5 / 7, 0.3, -0.25, 0.005, false);
      results.push_back(run_case<3>(name, s, m, multiplier, repeat));
    }
  }

  std::printf("seam-bench linearization: %s multipliers, CPU time of one core, best of %d\n",
              multiplier == mortar::Multiplier::dual ? "dual" : "standard", repeat);
  std::printf("  %-12s %6s %6s %8s | %9s %11s %7s | %11s %9s\n", "case", "slave", "pairs",
              "cand/fct", "(a) us/pr", "(b) us/pair", "(b)/(a)", "(c) us/fct", "alloc/pr");
  for (const Case& r : results) {
    std::printf("  %-12s %6d %6ld %8.2f | %9.2f %11.2f %7.1f | %11.2f %9.2g\n", r.name.c_str(),
                r.n_slave, r.n_pairs, r.candidates_per_facet, r.value_us, r.pair_us,
                r.pair_us / r.value_us, r.facet_us, r.allocations_per_pair);
  }
  std::printf("  (a) integrate_pair, (b) linearize_pair (values and derivatives), (c) "
              "linearize_slave_facet\n  per slave facet over its overlapping masters "
              "(normals chained in); alloc/pr: heap\n  allocations per linearize_pair call "
              "once warm.\n");
  return 0;
}

const seam::bench::Register registered{
    "linearization", "linearized mortar kernel: us per pair and per slave facet vs value path",
    &run_linearization};

} // namespace
