// Eq. 1, Eq. 2 and the MH acceptance on hand-built parts with hand-computed values.
#include <gtest/gtest.h>

#include <cmath>

#include "sheetgen/discovery/target.hpp"
#include "sheetgen/env/environment.hpp"
#include "../common/scene_fixture.hpp"
#include "../common/sheet_fixture.hpp"

namespace sheetgen {
namespace {

using namespace testing_scenes;
using fixtures::kDeg;

// Two horizontal rivet areas far below the base (z = 0): RA0 at z = -0.3 m,
// RA1 at z = -0.5 m, both 0.45 x 0.45 m, so the nearest point of anything above
// them is straight below.
Problem two_floors() {
  Problem p = base_problem();
  add_rivet_mesh(p, "floor30", quad(Vec3(-0.2, -0.2, -0.3), Vec3(0.45, 0, 0), Vec3(0, 0.45, 0)));
  add_rivet_mesh(p, "floor50", quad(Vec3(-0.2, -0.2, -0.5), Vec3(0.45, 0, 0), Vec3(0, 0.45, 0)));
  return p;
}

// Base plus one feeler bent straight down from edge 0, length l: its three free
// edges reach down to z = -l.
Part down_feeler(const Problem& p, double l) {
  Part part = make_base_part(p.loads[0], 0, 1.6e-3);
  part.add_tab(0, 0, {0.01, 0.016, l, 0, 0, -90 * kDeg});
  return part;  // tag -1: a feeler
}

TEST(Target, PopularityFactors) {
  // counts {1, 3}: sum 4, (1 - 1/5)^3 = 0.512, (1 - 3/5)^3 = 0.064
  const auto p = popularity_factors({1, 3}, 3.0);
  EXPECT_NEAR(p[0], 0.512, 1e-15);
  EXPECT_NEAR(p[1], 0.064, 1e-15);
}

TEST(Target, Eq1OnHandBuiltPart) {
  const Problem problem = two_floors();
  const Environment env(problem);
  const Part part = down_feeler(problem, 0.1);
  const RealisedPart rp = realise(part);
  TargetOptions o;  // alpha 1, beta 3, unit 0.1 m
  // The 3 free edges each come down to z = -0.1: 0.2 m = 2 units from RA0, 0.4 m = 4 units from RA1.
  const double d0 = edge_rivet_distance(env, 0, rp.tabs[1].corners[2], rp.tabs[1].corners[3]);
  EXPECT_NEAR(d0, 0.2, 1e-6);
  const double f_fresh = eq1_likelihood(part, rp, env, {0, 0}, o);
  EXPECT_NEAR(f_fresh, 3 * (std::exp(-2.0) + std::exp(-4.0)), 1e-5);
  const double f_pop = eq1_likelihood(part, rp, env, {1, 3}, o);
  EXPECT_NEAR(f_pop, 3 * (0.512 * std::exp(-2.0) + 0.064 * std::exp(-4.0)), 1e-5);
  // A frozen tab (tag >= 0) does not count: the sum is empty.
  Part frozen = part;
  frozen.tabs[1].tag = 0;
  EXPECT_EQ(eq1_likelihood(frozen, rp, env, {0, 0}, o), o.empty_likelihood);
}

TEST(Target, Eq2OnHandBuiltEdge) {
  const Problem problem = two_floors();
  const Environment env(problem);
  const Part part = down_feeler(problem, 0.1);
  const RealisedPart rp = realise(part);
  // Base edge 0 lies at z = 0: 3 and 5 units from the floors.
  const Vec3 a = rp.tabs[0].corners[0], b = rp.tabs[0].corners[1];
  const std::vector<double> d = {edge_rivet_distance(env, 0, a, b), edge_rivet_distance(env, 1, a, b)};
  EXPECT_NEAR(d[0], 0.3, 1e-6);
  EXPECT_NEAR(d[1], 0.5, 1e-6);
  TargetOptions o;
  const auto pop = popularity_factors({1, 3}, 3.0);  // (1 - 1/5)^3 = 0.512, (1 - 3/5)^3 = 0.064
  // never selected: se = 1, every reading gives 0.512 e^-3 + 0.064 e^-5 = 0.0259222
  const double w0 = eq2_edge_weight(d, pop, 0, 9, o);
  EXPECT_NEAR(w0, 0.512 * std::exp(-3.0) + 0.064 * std::exp(-5.0), 1e-6);
  EXPECT_NEAR(w0, 0.0259222, 1e-6);
  // selected twice in 9 steps: se = 1 - 2 / 10 = 0.8
  // default (Divide): 0.512 e^(-3/0.8) + 0.064 e^(-5/0.8) = 0.512 e^-3.75 + 0.064 e^-6.25 = 0.0121646 < w0
  EXPECT_EQ(o.se_reading, TargetOptions::SeReading::Divide);
  const double w = eq2_edge_weight(d, pop, 2, 9, o);
  EXPECT_NEAR(w, 0.512 * std::exp(-3.75) + 0.064 * std::exp(-6.25), 1e-6);
  EXPECT_NEAR(w, 0.0121646, 1e-6);
  EXPECT_LT(w, w0);  // prefers fewer selected edges
  // as printed: 0.512 e^(-3 * 0.8) + 0.064 e^(-5 * 0.8) > w0 (a chosen edge gains weight)
  o.se_reading = TargetOptions::SeReading::Printed;
  EXPECT_NEAR(eq2_edge_weight(d, pop, 2, 9, o), 0.512 * std::exp(-3.0 * 0.8) + 0.064 * std::exp(-5.0 * 0.8), 1e-6);
  EXPECT_NEAR(eq2_edge_weight(d, pop, 0, 9, o), w0, 1e-12);
  // se as a factor: 0.8 * w0 = 0.0207378
  o.se_reading = TargetOptions::SeReading::Multiply;
  EXPECT_NEAR(eq2_edge_weight(d, pop, 2, 9, o), 0.0207378, 1e-6);
  // 1 + 2/10 = 1.2 in the exponent: 0.512 e^-3.6 + 0.064 e^-6 = 0.0141484
  o.se_reading = TargetOptions::SeReading::Plus;
  EXPECT_NEAR(eq2_edge_weight(d, pop, 2, 9, o), 0.0141484, 1e-6);
}

TEST(Target, MetropolisHastingsRatioOnTwoStates) {
  const Problem problem = two_floors();
  const Environment env(problem);
  TargetOptions o;
  // x: the feeler reaches z = -0.1 (edges 2 and 4 units away); x': z = -0.2 (1 and 3 units).
  const Part x = down_feeler(problem, 0.1), xp = down_feeler(problem, 0.2);
  const double f = eq1_likelihood(x, realise(x), env, {0, 0}, o);
  const double fp = eq1_likelihood(xp, realise(xp), env, {0, 0}, o);
  EXPECT_NEAR(fp / f, std::exp(1.0), 1e-5);  // every term gains a factor e
  // Diffuse move x -> x' (one feeler in each: q = 1 both ways): uphill is always accepted,
  EXPECT_DOUBLE_EQ(mh_acceptance(f, fp, 1.0, 1.0), 1.0);
  // downhill with probability f(x) / f(x') = 1/e.
  EXPECT_NEAR(mh_acceptance(fp, f, 1.0, 1.0), std::exp(-1.0), 1e-5);
  // A jump chosen with probability 0.25 whose reverse has probability 0.05:
  // min(1, e^-1 * 0.05 / 0.25) = 0.2 e^-1.
  EXPECT_NEAR(mh_acceptance(fp, f, 0.25, 0.05), 0.2 * std::exp(-1.0), 1e-6);
  // An impossible reverse move is never accepted.
  EXPECT_EQ(mh_acceptance(f, fp, 0.5, 0.0), 0.0);
}

}  // namespace
}  // namespace sheetgen
