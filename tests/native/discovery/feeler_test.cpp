// The feeler prior with flat extensions (docs/grammar.md "Flat extensions",
// docs/discovery.md "Feelers"): flat feelers come only when the manufacturing
// settings allow them, at the prior's share, and switching them off leaves the
// random stream of a free-angle run exactly as it was.
#include <gtest/gtest.h>

#include <cmath>

#include "../common/sheet_fixture.hpp"
#include "sheetgen/discovery/feeler.hpp"

namespace sheetgen {
namespace {

using fixtures::kDeg;

// Right-angle limits as `--right-angles` sets them (generate.cpp).
SheetSpec right_angle_sheet(bool flat_extensions) {
  SheetSpec s = fixtures::aluminium_sheet_1_6mm();
  s.manufacturing.min_bend_angle = 89.5 * kDeg;
  s.manufacturing.max_bend_angle = 90.5 * kDeg;
  s.manufacturing.max_skew = 1e-3;
  s.manufacturing.flat_extensions = flat_extensions;
  return s;
}

TEST(FeelerPrior, FlatFeelersAtTheirShareOnlyWhenAllowed) {
  const int n = 20000;
  for (bool allowed : {false, true}) {
    const SheetSpec spec = right_angle_sheet(allowed);
    const FeelerPrior prior = resolve_prior(FeelerPrior{}, spec);
    ChainRng rng(ChainRng::seed_for(7, 0));
    int flat = 0;
    for (int i = 0; i < n; ++i) {
      const auto p = sample_feeler_parameters(prior, spec, 0.1, rng);
      ASSERT_TRUE(p.has_value());
      if (is_flat_extension(*p)) {
        ++flat;
      } else {
        EXPECT_GE(std::abs(p->theta3), 89.5 * kDeg);
        EXPECT_LE(std::abs(p->theta3), 90.5 * kDeg);
      }
    }
    const double share = static_cast<double>(flat) / n;
    std::printf("flat extensions %s: %d of %d feelers flat (%.4f)\n", allowed ? "on" : "off", flat, n, share);
    if (!allowed) {
      EXPECT_EQ(flat, 0);
    } else {
      // Binomial(n, 0.25): sigma = sqrt(0.25 * 0.75 / n) = 0.0031; 5 sigma either side.
      EXPECT_NEAR(share, prior.flat_probability, 5 * std::sqrt(0.25 * 0.75 / n));
    }
  }
}

// With flat extensions off a feeler takes exactly the five draws it took before
// they existed (d, theta1, theta2, |theta3|, sign): replayed by hand from the
// same seed, so free-angle runs stay byte-identical.
TEST(FeelerPrior, OffLeavesTheRandomStreamAlone) {
  const SheetSpec spec = fixtures::aluminium_sheet_1_6mm();
  const FeelerPrior prior = resolve_prior(FeelerPrior{}, spec);
  const double L = 0.2, w = spec.manufacturing.min_tab_width;
  ChainRng rng(ChainRng::seed_for(3, 1)), replay(ChainRng::seed_for(3, 1));
  for (int i = 0; i < 1000; ++i) {
    const auto p = sample_feeler_parameters(prior, spec, L, rng);
    ASSERT_TRUE(p.has_value());
    const double d = replay.uniform(0.0, L - w);
    const double t1 = replay.uniform(-prior.max_skew, prior.max_skew);
    const double t2 = replay.uniform(-prior.max_skew, prior.max_skew);
    const double mag = replay.uniform(prior.min_bend_angle, prior.max_bend_angle);
    const double t3 = replay.uniform() < 0.5 ? -mag : mag;
    ASSERT_EQ(p->d, d);
    ASSERT_EQ(p->theta1, t1);
    ASSERT_EQ(p->theta2, t2);
    ASSERT_EQ(p->theta3, t3);
  }
}

}  // namespace
}  // namespace sheetgen
