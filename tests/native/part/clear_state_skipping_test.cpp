// The bend sweeps and the press-brake strokes skip the states in which a pair
// is provably clear and move the turning tabs instead of realising the part
// (BendSequenceOptions / ToolSet::skip_clear_states). Their answers must be
// those of checking every state, each realised anew: the same order, the same
// sweeps, the same collision and the same tools and messages, on parts that
// collide, that the press cannot make and that it can.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "sheetgen/part/bend_sequence.hpp"
#include "sheetgen/part/clear_states.hpp"
#include "sheetgen/part/press_brake.hpp"
#include "../common/sheet_fixture.hpp"

namespace sheetgen {
namespace {

using fixtures::kDeg;
using fixtures::spec;

// A 60 x 40 mm base and 2 to 6 tabs, each on a free edge of the base or of an
// earlier tab, 16-45 mm long, bent +-20..150 deg: a mix of parts whose bends
// collide with each other, with the tools, and do not.
Part random_part(std::mt19937& rng) {
  Part p = make_base_part({Vec3(0, 0, 0), Vec3(0.06, 0, 0), Vec3(0.06, 0.04, 0), Vec3(0, 0.04, 0)}, Vec3::UnitZ());
  std::uniform_real_distribution<double> u(0, 1);
  const int tabs = 2 + static_cast<int>(u(rng) * 5);
  for (int i = 0; i < tabs; ++i) {
    for (int attempt = 0; attempt < 10; ++attempt) {
      const int parent = static_cast<int>(u(rng) * p.size());
      const int edge = parent == 0 ? static_cast<int>(u(rng) * 4) : 1 + static_cast<int>(u(rng) * 3);
      if (!p.is_free_edge(parent, edge)) continue;
      const double sign = u(rng) < 0.5 ? -1 : 1;
      const double angle = sign * (20 + 130 * u(rng)) * kDeg;
      try {
        p.add_tab(parent, edge, {0.002, 0.016 + 0.01 * u(rng), 0.016 + 0.029 * u(rng), 0, 0, angle});
        break;
      } catch (const std::invalid_argument&) {
      }
    }
  }
  return p;
}

void expect_same_collision(const BendCollision& a, const BendCollision& b) {
  EXPECT_EQ(a.bend_tab, b.bend_tab);
  EXPECT_EQ(a.tab_a, b.tab_a);
  EXPECT_EQ(a.tab_b, b.tab_b);
  EXPECT_DOUBLE_EQ(a.fraction, b.fraction);
  EXPECT_DOUBLE_EQ(a.angle, b.angle);
  EXPECT_NEAR(a.distance, b.distance, 1e-12);  // m: the moved corners equal the realised ones to rounding
}

// The skip itself: margin / motion per state, rounded down and kept back a
// part per million, at most the stroke; nothing when it gives no number.
TEST(ClearStateSkipping, StatesClearAheadAreTheMarginOverTheMotion) {
  EXPECT_EQ(clear_states(5e-3, 1e-3, 10), 4);    // 4.999995 states
  EXPECT_EQ(clear_states(5.1e-3, 1e-3, 10), 5);
  EXPECT_EQ(clear_states(1e-3, 1e-3, 10), 0);    // exactly one state's motion: not skipped
  EXPECT_EQ(clear_states(1.0, 1e-3, 10), 10);    // capped at the stroke
  EXPECT_EQ(clear_states(1e-3, 0.0, 10), 10);    // a tab on the bend line does not move
  EXPECT_EQ(clear_states(0.0, 0.0, 10), 0);      // 0 / 0
}

TEST(ClearStateSkipping, BendSequencesAreThoseOfCheckingEveryState) {
  std::mt19937 rng(20261207);
  BendSequenceOptions every, skip;
  every.skip_clear_states = false;
  int planned = 0, failed = 0;
  for (int n = 0; n < 60; ++n) {
    const Part part = random_part(rng);
    const BendSequenceResult a = plan_bend_sequence(part, spec(), every);
    const BendSequenceResult b = plan_bend_sequence(part, spec(), skip);
    SCOPED_TRACE("part " + std::to_string(n) + ": " + a.message);
    EXPECT_EQ(a.ok(), b.ok());
    EXPECT_EQ(a.order, b.order);
    EXPECT_EQ(a.sweeps, b.sweeps);
    EXPECT_EQ(a.message, b.message);
    expect_same_collision(a.collision, b.collision);
    (a.ok() ? planned : failed) += 1;
  }
  // Both outcomes are exercised.
  EXPECT_GE(planned, 10);
  EXPECT_GE(failed, 5);
}

TEST(ClearStateSkipping, PressBrakeChoicesAreThoseOfCheckingEveryState) {
  std::mt19937 rng(7);
  ToolSet every = standard_tool_set(spec().thickness), skip = every;
  every.skip_clear_states = false;
  int made = 0, not_made = 0, hits = 0;
  for (int n = 0; n < 60; ++n) {
    const Part part = random_part(rng);
    // Each bend with the others flat, and each with the others bent.
    for (const bool others_bent : {false, true})
      for (int k = 1; k < part.size(); ++k) {
        std::vector<double> angles(part.size(), 0.0);
        if (others_bent)
          for (int i = 1; i < part.size(); ++i)
            if (i != k) angles[i] = part.tabs[i].params.theta3;
        const BendToolChoice a = choose_bend_tools(part, k, angles, spec(), every);
        const BendToolChoice b = choose_bend_tools(part, k, angles, spec(), skip);
        SCOPED_TRACE("part " + std::to_string(n) + ", bend " + std::to_string(k) + ": " + a.reason);
        EXPECT_EQ(a.ok, b.ok);
        EXPECT_EQ(a.tooling.punch, b.tooling.punch);
        EXPECT_EQ(a.tooling.die, b.tooling.die);
        EXPECT_EQ(a.tooling.flipped, b.tooling.flipped);
        EXPECT_EQ(a.reason, b.reason);
        (a.ok ? made : not_made) += 1;
        hits += a.reason.find(" hits the ") != std::string::npos;
      }
  }
  // Bends made, bends not made, and among these collisions along the stroke.
  EXPECT_GE(made, 20);
  EXPECT_GE(not_made, 20);
  EXPECT_GE(hits, 10);
}

}  // namespace
}  // namespace sheetgen
