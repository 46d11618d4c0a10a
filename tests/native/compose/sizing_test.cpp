// Sizing (docs/pipeline.md "Sizing"): a valid part with room below its
// limit is narrowed and stays valid; one at its limit is left as it is; a
// narrowed tab's children stay where they were, clipped to its new edge.
#include "sheetgen/compose/sizing.hpp"

#include <gtest/gtest.h>

#include "leg_on_floor.hpp"

#include <cmath>

#include "sheetgen/env/environment.hpp"
#include "sheetgen/part/realisation.hpp"
#include "sheetgen/structure/part_model.hpp"

namespace sheetgen {
namespace {

// The compose tests' leg (leg_on_floor.hpp) pushed 10 N along +x (the
// full-width leg has a margin of safety near 2.6), with a compliance limit:
// its compliance grows as its width falls.
using SizingFixture = testing::LegOnFloor;

SizingFixture sizing_leg(double compliance_limit) {
  SizingFixture f = testing::leg_on_floor(10.0);
  f.problem.requirements.max_compliance = compliance_limit;
  return f;
}

// The fixture's part as the pipeline hands it to sizing: checked at the default mesh.
Candidate checked_answer(const SizingFixture& f, const Environment& env) {
  Candidate c;
  c.part = f.part;
  return evaluate_part(f.problem, env, 0, c, 0.0);
}

double unlimited_compliance() {
  // The leg's own compliance at the default mesh, with no limit to speak of.
  const SizingFixture f = sizing_leg(1e9);
  return analyse_part(f.problem, 0, plate_geometry(f.part, realise(f.part))).compliance;
}

TEST(Sizing, APartWithRoomBelowItsLimitIsNarrowedAndStaysValid) {
  const double c0 = unlimited_compliance();
  // Three times the full-width leg's compliance: the leg may lose well over
  // half of its width above min_tab_width (C ~ 1 / w for a plate in bending).
  const SizingFixture f = sizing_leg(3.0 * c0);
  const Environment env(f.problem);
  const Candidate answer = checked_answer(f, env);
  ASSERT_TRUE(answer.valid()) << answer.message << answer.fem_error << " C " << answer.fem.compliance << " / "
                              << answer.fem.compliance_limit << " MS " << answer.fem.margin_of_safety;

  const SizingResult r = size_part(f.problem, env, 0, answer);
  std::printf("leg: %d trials, %d cuts, width %.1f -> %.1f mm, C %.4g -> %.4g J (limit %.4g), area %.1f -> %.1f cm^2\n",
              r.trials, r.cuts, f.part.tabs[1].params.w * 1e3, r.part.part.tabs[1].params.w * 1e3, answer.fem.compliance,
              r.part.fem.compliance, 3.0 * c0, r.area_before * 1e4, r.part.area * 1e4);
  ASSERT_GT(r.cuts, 0);
  EXPECT_FALSE(r.final_check_failed);
  EXPECT_TRUE(r.part.valid());
  EXPECT_LT(r.part.cost, answer.cost);
  EXPECT_LT(r.part.part.tabs[1].params.w, 0.6 * f.part.tabs[1].params.w);
  EXPECT_GE(r.part.part.tabs[1].params.w, f.problem.manufacturing.min_tab_width - 1e-12);
  // Independently of the sizing's own bookkeeping: the sized part analysed
  // afresh at the default mesh keeps its limit, and a narrower leg is softer.
  const StructuralResult again = analyse_part(f.problem, 0, plate_geometry(r.part.part, realise(r.part.part)));
  EXPECT_LE(again.compliance, 3.0 * c0);
  EXPECT_GT(again.compliance, c0);
}

TEST(Sizing, APartAtItsLimitIsLeftAsItIs) {
  const double c0 = unlimited_compliance();
  // 1 % of room: the smallest cut tried (an eighth of the 84 mm above
  // min_tab_width, 10.5 mm of the leg's 100 mm) costs far more than that.
  const SizingFixture f = sizing_leg(1.01 * c0);
  const Environment env(f.problem);
  const Candidate answer = checked_answer(f, env);
  ASSERT_TRUE(answer.valid()) << answer.message << answer.fem_error;
  const SizingResult r = size_part(f.problem, env, 0, answer);
  EXPECT_EQ(r.cuts, 0);
  EXPECT_GT(r.trials, 0);
  ASSERT_EQ(r.part.part.size(), f.part.size());
  for (int i = 1; i < f.part.size(); ++i) {
    EXPECT_EQ(r.part.part.tabs[i].params.d, f.part.tabs[i].params.d);
    EXPECT_EQ(r.part.part.tabs[i].params.w, f.part.tabs[i].params.w);
  }
}

TEST(Sizing, NarrowingKeepsTheChildrenInPlaceClippedToTheNewEdge) {
  const SizingFixture f = sizing_leg(1.0);
  Part part = f.part;
  const RealisedPart before = realise(part);
  // 30 mm off the leg's root start: its far edge loses the same 30 mm at the
  // start (the leg is not skewed), so the flange that spanned it starts 30 mm on.
  ASSERT_TRUE(narrow_tab(part, 1, 0.03, 0.0, f.problem.manufacturing.min_tab_width));
  const RealisedPart after = realise(part);
  EXPECT_NEAR(part.tabs[1].params.w, 0.07, 1e-12);
  EXPECT_NEAR(part.tabs[2].params.d, 0.0, 1e-12);
  EXPECT_NEAR(part.tabs[2].params.w, 0.07, 1e-12);
  // The flange's root end did not move; its root start moved 30 mm along the edge.
  EXPECT_NEAR((after.tabs[2].corners[0] - before.tabs[2].corners[0]).norm(), 0.0, 1e-12);
  EXPECT_NEAR((after.tabs[2].origin - before.tabs[2].origin).norm(), 0.03, 1e-12);
  // Only sheet is removed: every corner of the narrowed leg and of its flange
  // lies in the tab it was cut from (its plane, inside its outline), so the
  // part keeps every clearance the wider one had.
  for (int tab : {1, 2}) {
    const RealisedTab& old_tab = before.tabs[tab];
    for (const Vec3& q : after.tabs[tab].corners) {
      EXPECT_NEAR((q - old_tab.corners[0]).dot(old_tab.normal), 0.0, 1e-12);
      const size_t n = old_tab.corners.size();
      for (size_t k = 0; k < n; ++k) {
        const Vec3& a = old_tab.corners[k];
        const Vec3& b = old_tab.corners[(k + 1) % n];
        EXPECT_GE((b - a).cross(q - a).dot(old_tab.normal), -1e-12) << "tab " << tab << " edge " << k;
      }
    }
  }
  // Below min_tab_width nothing changes.
  Part again = f.part;
  EXPECT_FALSE(narrow_tab(again, 1, 0.05, 0.04, f.problem.manufacturing.min_tab_width));
}

}  // namespace
}  // namespace sheetgen
