// The Hessian kernel of the energy-momentum contact of quadratic 3D facets (gap_blocks_3d.cpp:
// packed Hessians over the seeded variables, the back-projection's derivatives by the implicit
// function theorem, docs/contact_dynamics.md "Quadratic 3D faces") on random curved pairs:
// - its gaps, gradients and Hessians equal those of the plain forward kernel on Hyper<81> to
//   round-off (quad9, tri6 on both sides; with SEAM_FULL=1 also quad8 on both sides and quad9
//   against tri6 with the standard basis, quad4 against quad9);
// - its Hessian columns equal central differences of its own gradient, and its gradient
//   central differences of its gaps, in slave positions, slave normals and master positions;
// - the gradient path (Dual<81>, the residuals) gives the Hessian path's gaps and gradients.
#include "seam/contact/quadratic_pair_kernel.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

namespace seam::contact {
namespace {

using detail::QuadraticKernel;
using fem::CellType;
constexpr int nv = 81;

struct Derivatives {
  std::vector<double> gap, gradient, hessian;
};

Derivatives evaluate(const detail::QuadraticPair& pair, QuadraticKernel kernel) {
  Derivatives d;
  detail::quadratic_pair_derivatives(pair, mortar::PairOptions{}, kernel, d.gap, d.gradient,
                                     d.hessian);
  return d;
}

double max_abs(const std::vector<double>& a) {
  double m = 0.0;
  for (const double x : a) m = std::max(m, std::abs(x));
  return m;
}

/// Moves variable v of the pair (slave positions, slave normals, master positions) by h.
void perturb(detail::QuadraticPair& pair, int v, double h) {
  const int group = v / 27, node = v % 27 / 3, axis = v % 3;
  auto& x = group == 0 ? pair.xs : group == 1 ? pair.normals : pair.xm;
  x.at(static_cast<std::size_t>(node))[axis] += h;
}

struct Case {
  CellType slave, master;
  bool dual;
};

class QuadraticPairKernel : public ::testing::TestWithParam<Case> {};

TEST_P(QuadraticPairKernel, EqualsForwardKernel) {
  const Case c = GetParam();
  // quad8 and quad9 against tri6 under SEAM_FULL=1 only (the forward kernel takes 1 s).
  if ((c.slave == CellType::quad8 || c.slave != c.master) && std::getenv("SEAM_FULL") == nullptr)
    GTEST_SKIP() << "SEAM_FULL=1 runs this case";
  auto pair = detail::curved_pair(c.slave, c.master, 7);
  pair.dual = c.dual;
  const Derivatives packed = evaluate(pair, QuadraticKernel::packed);
  const Derivatives forward = evaluate(pair, QuadraticKernel::forward);
  ASSERT_EQ(packed.gap.size(), static_cast<std::size_t>(fem::n_nodes(c.slave)));
  ASSERT_GT(max_abs(forward.gap), 1e-3); // the facets overlap
  const double hessian_scale = max_abs(forward.hessian);
  ASSERT_GT(hessian_scale, 0.1);
  for (std::size_t j = 0; j < packed.gap.size(); ++j)
    EXPECT_NEAR(packed.gap[j], forward.gap[j], 1e-14 * max_abs(forward.gap)) << "node " << j;
  for (std::size_t i = 0; i < packed.gradient.size(); ++i)
    EXPECT_NEAR(packed.gradient[i], forward.gradient[i], 1e-13 * max_abs(forward.gradient))
        << "gradient entry " << i;
  double worst = 0.0;
  for (std::size_t i = 0; i < packed.hessian.size(); ++i)
    worst = std::max(worst, std::abs(packed.hessian[i] - forward.hessian[i]));
  EXPECT_LT(worst, 1e-12 * hessian_scale);
}

TEST_P(QuadraticPairKernel, CentralDifferences) {
  const Case c = GetParam();
  auto pair = detail::curved_pair(c.slave, c.master, 3);
  pair.dual = c.dual;
  const Derivatives d = evaluate(pair, QuadraticKernel::packed);
  const std::size_t ns = d.gap.size();
  const double gradient_scale = max_abs(d.gradient), hessian_scale = max_abs(d.hessian);
  const double h = 1e-5;
  // A slave position and a slave normal of the last node (mid-side or centre on a quadratic
  // facet), a master position.
  const int last = 3 * (fem::n_nodes(c.slave) - 1);
  for (const int v : {last + 2, 27 + last + 1, 54 + 4}) {
    auto plus = pair, minus = pair;
    perturb(plus, v, h);
    perturb(minus, v, -h);
    const Derivatives p = evaluate(plus, QuadraticKernel::packed);
    const Derivatives m = evaluate(minus, QuadraticKernel::packed);
    for (std::size_t j = 0; j < ns; ++j) {
      EXPECT_NEAR((p.gap[j] - m.gap[j]) / (2.0 * h),
                  d.gradient[j * nv + static_cast<std::size_t>(v)], 1e-7 * gradient_scale)
          << "gap " << j << " variable " << v;
      for (std::size_t w = 0; w < static_cast<std::size_t>(nv); ++w)
        EXPECT_NEAR((p.gradient[j * nv + w] - m.gradient[j * nv + w]) / (2.0 * h),
                    d.hessian[(j * nv + static_cast<std::size_t>(v)) * nv + w],
                    1e-6 * hessian_scale)
            << "gap " << j << " variables " << v << ", " << w;
    }
  }
}

TEST_P(QuadraticPairKernel, GradientPathEqualsHessianPath) {
  const Case c = GetParam();
  auto pair = detail::curved_pair(c.slave, c.master, 5);
  pair.dual = c.dual;
  const Derivatives packed = evaluate(pair, QuadraticKernel::packed);
  const Derivatives gradient = evaluate(pair, QuadraticKernel::gradient);
  ASSERT_EQ(gradient.gap.size(), packed.gap.size());
  ASSERT_GT(max_abs(packed.gap), 1e-3);
  for (std::size_t j = 0; j < packed.gap.size(); ++j)
    EXPECT_NEAR(gradient.gap[j], packed.gap[j], 1e-14 * max_abs(packed.gap)) << "node " << j;
  double worst = 0.0;
  for (std::size_t i = 0; i < packed.gradient.size(); ++i)
    worst = std::max(worst, std::abs(gradient.gradient[i] - packed.gradient[i]));
  EXPECT_LT(worst, 1e-13 * max_abs(packed.gradient));
}

INSTANTIATE_TEST_SUITE_P(Pairs, QuadraticPairKernel,
                         ::testing::Values(Case{CellType::quad9, CellType::quad9, true},
                                           Case{CellType::quad8, CellType::quad8, true},
                                           Case{CellType::tri6, CellType::tri6, true},
                                           Case{CellType::quad9, CellType::tri6, false},
                                           Case{CellType::quad4, CellType::quad9, true}));

} // namespace
} // namespace seam::contact
