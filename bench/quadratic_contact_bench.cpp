// seam-bench quadratic_contact: CPU per pair of the energy-momentum contact kernel of quadratic
// 3D facets (gap_blocks_3d.cpp, docs/contact_dynamics.md "Quadratic 3D faces"): the weighted
// gaps of one slave/master pair with their gradients and Hessians in the 81 variables, by the
// kernel gap_blocks_3d runs (packed Hessians over the seeded variables) and by the forward
// kernel on Hyper<81> it replaced, on the curved pairs of detail::curved_pair (quad9, quad8,
// tri6 on both sides, and quad9 against tri6), with the largest difference of the two; and the
// gradient path (Dual<81>) that residual evaluations run.
//   seam-bench quadratic_contact [repeat] [packed]   (packed: the new kernel alone, for perf)
#include "registry.hpp"

#include "seam/contact/quadratic_pair_kernel.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <string>
#include <vector>

namespace {

using seam::fem::CellType;
namespace detail = seam::contact::detail;

double cpu_now() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

struct Result {
  std::vector<double> gap, gradient, hessian;
};

/// Best of `repeat` CPU seconds of one evaluation.
double time_kernel(const detail::QuadraticPair& pair, detail::QuadraticKernel kernel, int repeat,
                   Result& r) {
  double best = 1e300;
  for (int i = 0; i < repeat; ++i) {
    const double t0 = cpu_now();
    detail::quadratic_pair_derivatives(pair, seam::mortar::PairOptions{}, kernel, r.gap, r.gradient,
                                       r.hessian);
    best = std::min(best, cpu_now() - t0);
  }
  return best;
}

double largest_difference(const std::vector<double>& a, const std::vector<double>& b,
                          double& scale) {
  double d = 0.0;
  scale = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    d = std::max(d, std::abs(a[i] - b[i]));
    scale = std::max(scale, std::abs(b[i]));
  }
  return d;
}

int run(int argc, char** argv) {
  const int repeat = argc > 1 ? std::max(1, std::stoi(argv[1])) : 3;
  const bool packed_only = argc > 2 && std::string(argv[2]) == "packed";
  struct Case {
    const char* name;
    CellType slave, master;
  };
  const Case cases[] = {{"quad9/quad9", CellType::quad9, CellType::quad9},
                        {"quad8/quad8", CellType::quad8, CellType::quad8},
                        {"tri6/tri6", CellType::tri6, CellType::tri6},
                        {"quad9/tri6", CellType::quad9, CellType::tri6}};
  std::printf("%-12s %12s %12s %8s %12s %12s %12s\n", "pair", "forward ms", "packed ms", "ratio",
              "|dH|/|H|", "|dg'|/|g'|", "gradient ms");
  for (const auto& c : cases) {
    const auto pair = detail::curved_pair(c.slave, c.master, 1);
    Result forward, packed, gradient;
    const double tp = time_kernel(pair, detail::QuadraticKernel::packed, repeat, packed);
    const double tg = time_kernel(pair, detail::QuadraticKernel::gradient, repeat, gradient);
    if (packed_only) {
      std::printf("%-12s %12s %12.2f %8s %12s %12s %12.2f\n", c.name, "-", 1e3 * tp, "-", "-", "-",
                  1e3 * tg);
      continue;
    }
    const double tf = time_kernel(pair, detail::QuadraticKernel::forward, repeat, forward);
    double hs = 0.0, gs = 0.0;
    const double dh = largest_difference(packed.hessian, forward.hessian, hs);
    const double dg = largest_difference(packed.gradient, forward.gradient, gs);
    std::printf("%-12s %12.2f %12.2f %8.2f %12.2e %12.2e %12.2f\n", c.name, 1e3 * tf, 1e3 * tp,
                tf / tp, dh / std::max(hs, 1e-300), dg / std::max(gs, 1e-300), 1e3 * tg);
  }
  return 0;
}

const seam::bench::Register reg{"quadratic_contact",
                                "CPU per pair of the quadratic 3D contact kernel's Hessian", &run};

} // namespace
