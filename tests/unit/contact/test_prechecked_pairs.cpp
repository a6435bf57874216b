// The 2D centre-normal pre-check of a contact pair (n_s . n_m < -0.1) is decided once per step
// attempt (ContactInterface::keep_prechecked_pairs): a pair that passed it at one configuration
// is integrated at the next ones even where its facets have turned past the threshold. Without
// that the pair's whole share of the weighted gaps drops out where the facets' angle crosses
// 95.7 degrees, and Newton's iterates of the 200 rings of examples/rings alternated across it
// (t = 0.77, a period-2 cycle; docs/contact_dynamics.md, "Pre-check kept within a step").
//
// Here a spike of the master side (its node at x = 0.6 moved to (0.4 + d, 0.2)) pierces a flat
// slave side: the master facet from the spike's tip down to x = 0.4 has n_s . n_m =
// -d / sqrt(0.04 + d^2), -0.1 at d = d0 = 0.02 / sqrt(0.99).
#include "two_blocks_2d.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace seam::contact {
namespace {

const double d0 = 0.02 / std::sqrt(0.99);

class PrecheckedPairs : public ::testing::Test {
protected:
  void SetUp() override {
    mesh = two_blocks_2d::mesh("prechecked_pairs");
    config = two_blocks_2d::contact();
    for (std::size_t i = 0; i * 2 < mesh.x.size(); ++i)
      if (std::abs(mesh.x[i * 2] - 0.6) < 1e-9 && std::abs(mesh.x[i * 2 + 1]) < 1e-9) tip = i;
  }
  /// The master node at (0.6, 0) moved to (0.4 + d, 0.2).
  std::vector<double> spike(double d) const {
    std::vector<double> u(mesh.x.size(), 0.0);
    u[tip * 2] = 0.4 + d - 0.6;
    u[tip * 2 + 1] = 0.2;
    return u;
  }
  /// g~ summed over the gap blocks at the spike d (the interface updated there).
  std::vector<double> gaps(ContactInterface& itf, double d) const {
    return two_blocks_2d::gaps(itf, spike(d));
  }
  static double largest_difference(const std::vector<double>& a, const std::vector<double>& b) {
    double worst = 0.0;
    for (std::size_t j = 0; j < a.size(); ++j) worst = std::max(worst, std::abs(a[j] - b[j]));
    return worst;
  }
  mesh::Mesh mesh;
  io::Interface config;
  std::size_t tip = 0;
};

TEST_F(PrecheckedPairs, KeptPairIsContinuousAcrossTheThreshold) {
  const double eps = 1e-7;
  ContactInterface fresh(config, mesh);
  const auto passing = gaps(fresh, d0 + eps);
  const auto dropped = gaps(fresh, d0 - eps); // decided at that configuration: the pair drops
  const double jump = largest_difference(passing, dropped);

  ContactInterface itf(config, mesh);
  gaps(itf, d0 + eps);
  itf.keep_prechecked_pairs();
  EXPECT_FALSE(itf.prechecked_pairs().empty());
  const auto kept = gaps(itf, d0 - eps);
  const double change = largest_difference(passing, kept);
  std::printf("  g~ across n_s . n_m = -0.1 (+-1e-7 of the spike): jump %.3e decided at each "
              "configuration, change %.3e with the pair kept\n",
              jump, change);
  EXPECT_GT(jump, 1e-4);          // the pair's share: the spike is 0.2 deep
  EXPECT_LT(change, 1e-3 * jump); // continuous: a change of O(2e-7) over the 2e-7 of the move

  // The mortar integration (D_jj, g~) takes the kept pair too: g~ equals the blocks' sum.
  NodalValues values;
  itf.evaluate(values);
  EXPECT_LT(largest_difference(values.gap, kept), 1e-10 * jump);

  // A new step attempt decides anew.
  itf.forget_prechecked_pairs();
  EXPECT_TRUE(itf.prechecked_pairs().empty());
  EXPECT_LT(largest_difference(gaps(itf, d0 - eps), dropped), 1e-15);
}

} // namespace
} // namespace seam::contact
