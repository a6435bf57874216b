// seam-bench mortar: throughput of mortar integration (issue 3). A slave grid and a rotated,
// shifted, finer master grid on the same curved surface (3D: quad4, tri3, quad8; 2D: line2,
// line3); candidate pairs from seam::search::InterfaceSearch; then
//   (a) the element-pair kernel integrate_pair alone over all candidates, with the heap
//       allocations it makes counted (the goal is zero), and
//   (b) the full pass assemble_mortar_operators (normals, dual coefficients, kernel, triplet
//       assembly and compress),
// each for dual and standard multipliers. Goal: 1e6 linear element pairs per second per core
// for (a).
//
// seam-bench mortar-share is in mortar_share_bench.cpp.
#include "allocation_counter.hpp"
#include "registry.hpp"
#include "surface.hpp"

#include "seam/la/petsc.hpp"
#include "seam/meshtying/tied_interface.hpp"
#include "seam/mortar/interface.hpp"
#include "seam/mortar/normals.hpp"
#include "seam/problem/assembly.hpp"
#include "seam/problem/discretization.hpp"
#include "seam/problem/tying_constraint.hpp"
#include "seam/search/interface_search.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using seam::local_index;
using seam::fem::CellType;
namespace mortar = seam::mortar;
namespace search = seam::search;

/// CPU seconds of this thread (as in the search benchmark: on a shared machine CPU time is what
/// the code costs).
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

struct Timing {
  double best = 1e300; ///< fastest run, CPU seconds
  int runs = 0;
};

/// Best of up to `repeat` runs of f; once 3 CPU seconds are spent no further run starts, which
/// keeps the slow quadratic cases short.
template <class F> Timing best_seconds(int repeat, F&& f) {
  Timing t;
  double spent = 0.0;
  while (t.runs < repeat && (t.runs == 0 || spent < 3.0)) {
    const double t0 = cpu_seconds();
    f();
    const double dt = cpu_seconds() - t0;
    t.best = std::min(t.best, dt);
    spent += dt;
    ++t.runs;
  }
  return t;
}

using seam::bench::Surface;
using seam::bench::surface_2d;

// The shared interface: a bump of height `amplitude` over the unit square / interval.
double height(double amplitude, double x, double y) {
  return amplitude * std::sin(std::numbers::pi * x) * std::sin(std::numbers::pi * y);
}

/// n x n cells of size h, rotated by `angle` about (0.5, 0.5) and lifted onto the bump. The
/// lattice starts at `origin` in the rotated frame and has a node every h / order, so that
/// quad8 finds its mid-side nodes (lattice cell centres stay unused). Only cells whose centre
/// lies within `margin` of the unit square are kept. Slave facets (`slave`) turn
/// counter-clockwise seen from +z, so their normal points up; master facets turn the other way
/// and face the slave. tri3 splits the cells along one diagonal on the slave and the other on
/// the master.
Surface surface_3d(CellType type, int n, double h, double angle, double origin, double margin,
                   double amplitude, bool slave) {
  Surface s;
  s.dim = 3;
  const int order = type == CellType::quad8 ? 2 : 1;
  const int n_lattice = order * n + 1;
  const double c = std::cos(angle), sn = std::sin(angle);
  const auto place = [&](double u, double v) {
    const double du = u - 0.5, dv = v - 0.5;
    return std::array<double, 2>{0.5 + c * du - sn * dv, 0.5 + sn * du + c * dv};
  };
  for (int j = 0; j < n_lattice; ++j)
    for (int i = 0; i < n_lattice; ++i) {
      const auto [x, y] = place(origin + i * h / order, origin + j * h / order);
      s.coords.insert(s.coords.end(), {x, y, height(amplitude, x, y)});
    }
  const auto id = [n_lattice](int i, int j) { return static_cast<local_index>(j * n_lattice + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const auto [xc, yc] = place(origin + (i + 0.5) * h, origin + (j + 0.5) * h);
      if (xc < -margin || xc > 1 + margin || yc < -margin || yc > 1 + margin) continue;
      const int I = order * i, J = order * j;
      const local_index a = id(I, J), b = id(I + order, J), cc = id(I + order, J + order),
                        d = id(I, J + order);
      if (type == CellType::quad4) {
        if (slave)
          s.add(type, {a, b, cc, d});
        else
          s.add(type, {a, d, cc, b});
      } else if (type == CellType::tri3) {
        if (slave) {
          s.add(type, {a, b, cc});
          s.add(type, {a, cc, d});
        } else {
          s.add(type, {a, d, b});
          s.add(type, {b, d, cc});
        }
      } else { // quad8: corners, then the mid-side nodes of edges 0-1, 1-2, 2-3, 3-0
        const local_index ab = id(I + 1, J), bc = id(I + 2, J + 1), cd = id(I + 1, J + 2),
                          da = id(I, J + 1);
        if (slave)
          s.add(type, {a, b, cc, d, ab, bc, cd, da});
        else
          s.add(type, {a, d, cc, b, da, cd, bc, ab});
      }
    }
  return s;
}

struct Interface {
  Surface slave, master;
  std::vector<mortar::CandidatePair> candidates; // grouped by slave facet
};

// Master spacing and placement relative to the slave: finer, rotated (3D), shifted.
constexpr double master_ratio = 0.77;
constexpr double master_angle = 0.3;

Interface make_interface(CellType type, int n, double amplitude) {
  Interface in;
  const double h = 1.0 / n, hm = master_ratio * h;
  if (type == CellType::line2 || type == CellType::line3) {
    const int nm = static_cast<int>(std::ceil((1.0 + 2.0 * hm) / hm));
    const auto curve = [amplitude](double x) { return height(amplitude, x, 0.5); };
    in.slave = surface_2d(type, n, h, 0.0, curve, true);
    in.master = surface_2d(type, nm, hm, -0.63 * hm, curve, false);
  } else {
    // The rotated master lattice must cover the unit square: half its diagonal is 0.71.
    const int nm = static_cast<int>(std::ceil(1.5 / hm)) + 1;
    in.slave = surface_3d(type, n, h, 0.0, 0.0, 0.0, amplitude, true);
    in.master = surface_3d(type, nm, hm, master_angle, -0.25 + 0.37 * hm, hm, amplitude, false);
  }
  search::InterfaceSearch finder(in.slave.view(), in.master.view());
  const auto& pairs = finder.find_pairs();
  in.candidates.reserve(pairs.size());
  for (const auto& p : pairs) in.candidates.push_back({p.slave, p.master});
  std::sort(in.candidates.begin(), in.candidates.end(), [](const auto& a, const auto& b) {
    return a.slave != b.slave ? a.slave < b.slave : a.master < b.master;
  });
  return in;
}

/// Slave grid size giving about `target` candidate pairs, from the candidates per slave facet
/// of a small trial interface.
int grid_size_for(CellType type, long target, double amplitude) {
  const bool is_2d = type == CellType::line2 || type == CellType::line3;
  const int trial = is_2d ? 200 : 16;
  const Interface in = make_interface(type, trial, amplitude);
  const double per_facet = double(in.candidates.size()) / double(in.slave.types.size());
  const double facets_per_cell = type == CellType::tri3 ? 2.0 : 1.0;
  const double cells = double(target) / per_facet / facets_per_cell;
  return std::max(2, static_cast<int>(std::lround(is_2d ? cells : std::sqrt(cells))));
}

struct Result {
  std::string name;
  mortar::Multiplier multiplier{};
  bool linear = true;
  long n_slave = 0, n_master = 0, n_candidates = 0, n_overlapping = 0, n_cells = 0;
  long n_projection_failures = 0;
  double kernel_s = 0, prepare_s = 0, assembly_s = 0;
  int kernel_runs = 1;
  seam::bench::AllocationCount kernel_allocations, assembly_allocations;
  double area_ratio = 0; ///< sum of D over the slave surface area (1 up to discretization)
  double row_sum_error = 0;

  double kernel_rate() const { return double(n_candidates) / kernel_s; }
  double overlap_rate() const { return double(n_overlapping) / kernel_s; }
  double assembly_rate() const { return double(n_candidates) / assembly_s; }
  double allocations_per_pair() const {
    return double(std::max(kernel_allocations.operator_new, kernel_allocations.malloc)) /
           (double(n_candidates) * kernel_runs);
  }
};

/// Surface area of the slave facets, by Gauss quadrature on each facet (the reference for
/// sum_jk D_jk, which integrates 1 over the clip cells).
template <int Dim> double slave_measure(const mortar::FacetSet& set) {
  double total = 0.0;
  for (local_index f = 0; f < set.n_facets(); ++f) {
    const auto facet = mortar::gather_facet<Dim>(set, f);
    const auto rule = seam::fem::quadrature(facet.type, 10);
    for (int q = 0; q < rule.n_points; ++q) {
      const auto p = mortar::evaluate(facet, rule.points.data() + q * (Dim - 1));
      total += rule.weights[static_cast<std::size_t>(q)] * mortar::scaled_normal<Dim>(p.dx).norm();
    }
  }
  return total;
}

template <int Dim>
Result run_case(const std::string& name, const Interface& in, mortar::Multiplier multiplier,
                int repeat) {
  Result r;
  r.name = name;
  r.multiplier = multiplier;
  const mortar::FacetSet slave = in.slave.facets(), master = in.master.facets();
  r.linear = seam::fem::order(slave.types[0]) == 1;
  r.n_slave = slave.n_facets();
  r.n_master = master.n_facets();
  r.n_candidates = static_cast<long>(in.candidates.size());

  // Inputs of the kernel, prepared once per facet as the interface assembly does.
  const std::vector<double> normals = mortar::averaged_nodal_normals(slave);
  std::vector<mortar::SlaveFacet<Dim>> slaves(static_cast<std::size_t>(slave.n_facets()));
  r.prepare_s = best_seconds(repeat, [&] {
                  for (local_index f = 0; f < slave.n_facets(); ++f) {
                    auto& sf = slaves[static_cast<std::size_t>(f)];
                    sf.facet = mortar::gather_facet<Dim>(slave, f);
                    const auto nodes = slave.facet_nodes(f);
                    for (int i = 0; i < sf.facet.n_nodes; ++i)
                      for (int a = 0; a < Dim; ++a)
                        sf.normals(a, i) = normals[static_cast<std::size_t>(nodes[i]) * Dim + a];
                    sf.basis = mortar::make_slave_basis(sf.facet, multiplier);
                  }
                }).best;
  std::vector<mortar::Facet<Dim>> masters;
  masters.reserve(static_cast<std::size_t>(master.n_facets()));
  for (local_index f = 0; f < master.n_facets(); ++f)
    masters.push_back(mortar::gather_facet<Dim>(master, f));

  // (a) the kernel alone. A warm-up on the first candidates fills the caches (and seam::fem's
  // quadrature rule cache); the timed passes count the heap allocations.
  long overlapping = 0, cells = 0, failures = 0;
  double checksum = 0.0;
  const auto kernel_pass = [&](std::size_t n) {
    overlapping = cells = failures = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const mortar::CandidatePair p = in.candidates[i];
      const mortar::PairContribution c = mortar::integrate_pair(
          slaves[static_cast<std::size_t>(p.slave)], masters[static_cast<std::size_t>(p.master)]);
      overlapping += c.n_cells > 0;
      cells += c.n_cells;
      failures += c.n_projection_failures;
      checksum += c.area;
    }
  };
  kernel_pass(std::min<std::size_t>(in.candidates.size(), 2000));
  const auto before = seam::bench::AllocationCount::now();
  const Timing kernel = best_seconds(repeat, [&] { kernel_pass(in.candidates.size()); });
  r.kernel_allocations = seam::bench::AllocationCount::now() - before;
  r.kernel_s = kernel.best;
  r.kernel_runs = kernel.runs;
  r.n_overlapping = overlapping;
  r.n_cells = cells;
  r.n_projection_failures = failures;
  if (!(checksum > 0.0)) throw std::runtime_error(name + ": no overlap integrated");

  // (b) the full pass.
  mortar::MortarOptions options;
  options.multiplier = multiplier;
  mortar::MortarOperators ops;
  const auto before_assembly = seam::bench::AllocationCount::now();
  ops = mortar::assemble_mortar_operators(slave, master, in.candidates, options);
  r.assembly_allocations = seam::bench::AllocationCount::now() - before_assembly;
  r.assembly_s = best_seconds(repeat, [&] {
                   ops = mortar::assemble_mortar_operators(slave, master, in.candidates, options);
                 }).best;

  // Sanity of what was timed: sum_jk D_jk is the integrated area, and sum_k D_jk = sum_l M_jl.
  std::vector<double> row_sum(static_cast<std::size_t>(slave.n_nodes()), 0.0);
  double total_d = 0.0;
  for (const auto& t : ops.D) {
    row_sum[static_cast<std::size_t>(t.row)] += t.value;
    total_d += t.value;
  }
  for (const auto& t : ops.M) row_sum[static_cast<std::size_t>(t.row)] -= t.value;
  for (const double e : row_sum) r.row_sum_error = std::max(r.row_sum_error, std::abs(e));
  r.area_ratio = total_d / slave_measure<Dim>(slave);
  return r;
}

const char* multiplier_name(mortar::Multiplier m) {
  return m == mortar::Multiplier::dual ? "dual" : "std";
}

void help() {
  std::printf(
      "usage: seam-bench mortar [--pairs N] [--repeat R] [--flat] [--cases c1,c2,...] [--json]\n"
      "  Slave grid against a finer (x0.77), rotated (0.3 rad in 3D) and shifted master grid on\n"
      "  the bump z = 0.1 sin(pi x) sin(pi y) (2D: y = 0.1 sin(pi x)); --flat sets it to zero.\n"
      "  Cases: quad4, tri3, quad8 (3D), line2, line3 (2D); default all. N (default 1e5) is the\n"
      "  approximate number of candidate pairs from seam::search::InterfaceSearch per case.\n"
      "  Times, best of R runs (default 3; no further run once 3 s are spent), in CPU seconds\n"
      "  of one core:\n"
      "    (a) integrate_pair alone over all candidates (slave facets prepared beforehand),\n"
      "        heap allocations counted (operator new%s);\n"
      "    (b) assemble_mortar_operators: normals, dual coefficients, kernel, triplets,\n"
      "        compress.\n"
      "  Goal: >= 1e6 linear element pairs per second per core for (a), zero allocations.\n"
      "  Exit code 1 if the kernel allocates or a back-projection fails.\n"
      "  --json prints one JSON object as the last line.\n",
      seam::bench::counts_malloc ? " and malloc" : "");
}

int run_mortar(int argc, char** argv) {
  long target = 100'000;
  int repeat = 3;
  bool json = false;
  double amplitude = 0.1;
  std::vector<std::string> cases{"quad4", "tri3", "quad8", "line2", "line3"};
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) throw std::invalid_argument("missing value after " + a);
      return argv[++i];
    };
    if (a == "--pairs")
      target = std::lround(std::atof(value()));
    else if (a == "--repeat")
      repeat = std::atoi(value());
    else if (a == "--flat")
      amplitude = 0.0;
    else if (a == "--json")
      json = true;
    else if (a == "--cases") {
      cases.clear();
      for (std::string list = value(); !list.empty();) {
        const auto comma = list.find(',');
        cases.push_back(list.substr(0, comma));
        list = comma == std::string::npos ? "" : list.substr(comma + 1);
      }
    } else if (a == "--help" || a == "-h") {
      help();
      return 0;
    } else
      throw std::invalid_argument("unknown option " + a);
  }
  if (target < 10 || target > 100'000'000 || repeat < 1)
    throw std::invalid_argument("need 10 <= --pairs <= 1e8 and --repeat >= 1");

  std::vector<Result> results;
  for (const std::string& c : cases) {
    CellType type;
    if (c == "quad4")
      type = CellType::quad4;
    else if (c == "tri3")
      type = CellType::tri3;
    else if (c == "quad8")
      type = CellType::quad8;
    else if (c == "line2")
      type = CellType::line2;
    else if (c == "line3")
      type = CellType::line3;
    else
      throw std::invalid_argument("unknown case " + c + " (quad4, tri3, quad8, line2, line3)");
    const Interface in = make_interface(type, grid_size_for(type, target, amplitude), amplitude);
    const std::string name = c + "-" + c;
    for (const auto m : {mortar::Multiplier::dual, mortar::Multiplier::standard}) {
      results.push_back(type == CellType::line2 || type == CellType::line3
                            ? run_case<2>(name, in, m, repeat)
                            : run_case<3>(name, in, m, repeat));
    }
  }

  std::printf("seam-bench mortar: %s interface, CPU time of one core, best of %d runs (fewer "
              "once a measurement\n  has taken 3 s)\n",
              amplitude == 0.0 ? "flat" : "curved", repeat);
  std::printf("  (a) integrate_pair alone; (b) assemble_mortar_operators. Mpairs/s = 1e6 "
              "candidate pairs per second\n");
  std::printf("  %-12s %-4s %7s %8s %7s %6s | %8s %8s %7s %9s %8s | %8s %9s | %6s\n", "case",
              "mult", "slave", "cand", "overlap", "cells", "(a) Mp/s", "ovl Mp/s", "ns/pair",
              "alloc/pr", "prep us", "(b) Mp/s", "b allocs", "goal");
  bool allocation_free = true;
  for (const Result& r : results) {
    const bool fine = r.allocations_per_pair() == 0.0;
    allocation_free = allocation_free && fine;
    char goal[16] = "-";
    if (r.linear) std::snprintf(goal, sizeof goal, "%.2fx", r.kernel_rate() / 1e6);
    std::printf("  %-12s %-4s %7ld %8ld %7ld %6.2f | %8.3f %8.3f %7.0f %9.3g %8.2f | %8.3f %9llu "
                "| %6s\n",
                r.name.c_str(), multiplier_name(r.multiplier), r.n_slave, r.n_candidates,
                r.n_overlapping, double(r.n_cells) / double(std::max(1L, r.n_overlapping)),
                1e-6 * r.kernel_rate(), 1e-6 * r.overlap_rate(), 1e9 * r.kernel_s / r.n_candidates,
                r.allocations_per_pair(), 1e6 * r.prepare_s / r.n_slave, 1e-6 * r.assembly_rate(),
                static_cast<unsigned long long>(
                    std::max(r.assembly_allocations.operator_new, r.assembly_allocations.malloc)),
                goal);
  }
  std::printf("  cells = integration cells (3D triangles, 2D segments) per overlapping pair; "
              "prep us = slave facet\n  preparation (gather, normals, dual coefficients) per "
              "slave facet; goal = (a) / 1e6 pairs/s\n  (linear cases). Allocations counted: "
              "operator new%s.\n",
              seam::bench::counts_malloc ? " and malloc" : " only");
  std::printf("  checks: sum D / slave area, max |sum_k D_jk - sum_l M_jl|, projection failures\n");
  for (const Result& r : results)
    std::printf("    %-12s %-4s %.8f  %.1e  %ld\n", r.name.c_str(), multiplier_name(r.multiplier),
                r.area_ratio, r.row_sum_error, r.n_projection_failures);
  long failures = 0;
  for (const Result& r : results) failures += r.n_projection_failures;
  std::printf("  kernel allocation-free: %s; projection failures: %ld\n",
              allocation_free ? "yes" : "NO", failures);

  if (json) {
    std::printf("{\"flat\": %s, \"repeat\": %d, \"cases\": [", amplitude == 0.0 ? "true" : "false",
                repeat);
    for (std::size_t i = 0; i < results.size(); ++i) {
      const Result& r = results[i];
      std::printf("%s{\"case\": \"%s\", \"multiplier\": \"%s\", \"slave_facets\": %ld, "
                  "\"master_facets\": %ld, \"candidates\": %ld, \"overlapping\": %ld, "
                  "\"cells\": %ld, \"kernel_s\": %.6g, \"kernel_pairs_per_s\": %.6g, "
                  "\"kernel_overlapping_pairs_per_s\": %.6g, \"kernel_runs\": %d, "
                  "\"kernel_allocations_per_pair\": %.6g, \"prepare_s\": %.6g, "
                  "\"assembly_s\": %.6g, "
                  "\"assembly_pairs_per_s\": %.6g, \"area_ratio\": %.12g, "
                  "\"row_sum_error\": %.3g, \"projection_failures\": %ld}",
                  i ? ", " : "", r.name.c_str(), multiplier_name(r.multiplier), r.n_slave,
                  r.n_master, r.n_candidates, r.n_overlapping, r.n_cells, r.kernel_s,
                  r.kernel_rate(), r.overlap_rate(), r.kernel_runs, r.allocations_per_pair(),
                  r.prepare_s, r.assembly_s, r.assembly_rate(), r.area_ratio, r.row_sum_error,
                  r.n_projection_failures);
    }
    std::printf("], \"allocation_free\": %s, \"projection_failures\": %ld}\n",
                allocation_free ? "true" : "false", failures);
  }
  return allocation_free && failures == 0 ? 0 : 1;
}

const seam::bench::Register registered{
    "mortar", "mortar integration: pair kernel and interface assembly throughput", &run_mortar};

} // namespace
