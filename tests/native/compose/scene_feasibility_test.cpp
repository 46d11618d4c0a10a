// Existence proofs for the two sample scenes whose answer crosses an opening
// (docs/scenes.md, "plates, webs and a scene with no answer"): a part built by
// hand in the grammar, with the project's own validity and shell FEM at the
// default mesh, is valid and within the limits. If a scene change (or a rule
// change) makes these fail, the scene may have no answer at all and the
// solver's "no valid part" would mean nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "sheetgen/compose/candidate.hpp"
#include "sheetgen/compose/stiffening_lip.hpp"
#include "sheetgen/discovery/feeler.hpp"
#include "sheetgen/env/environment.hpp"
#include "sheetgen/part/realisation.hpp"
#include "sheetgen/part/validity.hpp"
#include "../common/single_force.hpp"

namespace sheetgen {
namespace {

double deg(double d) { return d * M_PI / 180.0; }

struct WebDesign {
  double depth;             // m, webs hung from the base's +-y edges
  double frame_x;           // m, the frame's plane (normal -x)
  int frame_area, floor_area;
  double floor_x0, floor_x1;  // m, the legs' extent along x (inside the floor rivet strip)
};

// A leg from the lower side edge of web `front` (side 0: the box's -y side)
// down to the floor (z = 0) over x0..x1 (as far as the web reaches), kinked
// by the grammar's smallest bend so that it leans away from the box, with a
// flange on floor_area.
void add_leg(Part& part, int front, int side, double x0, double x1, int floor_area, const Problem& p) {
  const double kink = p.manufacturing.min_bend_angle;
  const RealisedPart rp = realise(part);
  const auto& c = rp.tabs[front].corners;
  const int lower = c[1].z() + c[2].z() < c[3].z() + c[0].z() ? kStartSideEdge : kEndSideEdge;
  const Vec3 a = c[lower], b = c[(lower + 1) % 4];
  const double len = (b - a).norm();
  const double u0 = (x0 - a.x()) / (b.x() - a.x()), u1 = (x1 - a.x()) / (b.x() - a.x());
  // Within the web: a leg cannot leave its parent edge.
  const double lo = std::max(0.0, std::min(u0, u1)), hi = std::min(1.0, std::max(u0, u1));
  const int leg = part.add_tab(front, lower, TabParameters{lo * len, (hi - lo) * len, a.z(), 0, 0, side == 0 ? kink : -kink});
  if (attach_flange(part, leg, RivetPlane{floor_area, Vec3(0.3, 0, 0), Vec3(0, 0, 1)}, SheetSpec::from(p)) < 0)
    ADD_FAILURE() << "no floor flange on side " << side;
}

// Per side of the box: a web down from the base's side edge, a web on its front
// vertical edge (kinked inwards by the grammar's smallest bend,
// min_bend_angle) to the frame with a flange, and a leg from that web's lower
// edge (kinked as much) to the floor (z = 0) with a flange.
Part web_part(const Problem& p, const WebDesign& d) {
  const SheetSpec spec = SheetSpec::from(p);
  const double kink = p.manufacturing.min_bend_angle;
  Part part = make_base_part(p.loads[0], 0, p.material.thickness);
  const RealisedPart rb = realise(part);
  const double edge = (rb.tabs[0].corners[1] - rb.tabs[0].corners[0]).norm();  // the +-y edges run along x
  const double cut = 0.011;  // m, the front web stays clear of the base's bend zone at the top
  for (int side = 0; side < 2; ++side) {
    // Base edge 0 (-y) runs +x, so its web's front (+x) vertical edge is the end side (3, from the
    // bottom); edge 2 (+y) runs -x, so the front edge is the start side (1, from the top).
    const int web = part.add_tab(0, side == 0 ? 0 : 2, TabParameters{0, edge, d.depth, 0, 0, deg(-90)});
    const int front = part.add_tab(web, side == 0 ? kEndSideEdge : kStartSideEdge,
                                   TabParameters{side == 0 ? 0.0 : cut, d.depth - cut, 0.3, 0, 0, -kink});
    if (attach_flange(part, front, RivetPlane{d.frame_area, Vec3(d.frame_x, 0, 0.2), Vec3(-1, 0, 0)}, spec) < 0)
      ADD_FAILURE() << "no frame flange on side " << side;
    add_leg(part, front, side, d.floor_x0, d.floor_x1, d.floor_area, p);
  }
  return part;
}

Candidate evaluate(const Problem& p, const Environment& env, const Part& part) {
  Candidate c;
  c.part = part;
  return evaluate_part(p, env, 0, c, 0.0);
}

void expect_feasible(const std::string& scene, const WebDesign& d, double max_ratio_with_lips) {
  // The hand-built webs answer the one 9 g downward case the scenes were
  // drawn for (docs/scenes.md "boxed_in and bulkhead_hole"); under the
  // envelope's sideways cases they are far too soft (docs/scenes.md).
  Problem p = test::single_force(
      load_problem(std::string(SHEETGEN_SOURCE_DIR) + "/sample_scenes/" + scene + "/problem.json"));
  // The question here is structural: is there a part stiff enough? These
  // webs are hats whose legs meet the ram of the standard press brake
  // (docs/manufacturing.md "Press brake"), so the press-brake check is off.
  p.manufacturing.press_brake_required = false;
  const Environment env(p);
  const Part part = web_part(p, d);
  const ValidityReport v = check_validity(part, realise(part), env);
  ASSERT_TRUE(v.valid()) << scene << ": " << v.summary();
  const Candidate plain = evaluate(p, env, part);
  ASSERT_TRUE(plain.geometry_ok) << plain.message;
  ASSERT_TRUE(plain.analysed) << plain.fem_error;
  const LipResult lr = add_stiffening_lips(part, env, p);
  const Candidate lipped = evaluate(p, env, lr.part);
  ASSERT_TRUE(lipped.geometry_ok) << lipped.message;
  ASSERT_TRUE(lipped.analysed) << lipped.fem_error;
  std::printf("[%s] hand-built webs: C %.4g J, with %d lips %.4g J, limit %.4g J, MS %.3g\n", scene.c_str(),
              plain.fem.compliance, lr.lips, lipped.fem.compliance, lipped.fem.compliance_limit, lipped.fem.margin_of_safety);
  EXPECT_TRUE(lipped.valid());
  EXPECT_LE(lipped.fem.compliance, max_ratio_with_lips * lipped.fem.compliance_limit);
  EXPECT_LT(lipped.fem.compliance, plain.fem.compliance);  // lips on the webs' free edges stiffen them
}

// The webs pass straight through the 180 x 100 mm slot; 56 mm is what the
// equipment 60 mm below the base leaves. Measured 0.1122 J of 0.1766 J (0.64).
TEST(SceneFeasibility, BoxedInHasAHandBuiltPart) { expect_feasible("boxed_in", {0.056, 0.45, 1, 0, 0.155, 0.385}, 0.75); }

// Webs 76 mm deep through the 160 mm lightening hole. Measured 0.1525 J of 0.1766 J (0.86).
TEST(SceneFeasibility, BulkheadHoleHasAHandBuiltPart) { expect_feasible("bulkhead_hole", {0.076, 0.36, 0, 1, 0.26, 0.34}, 0.95); }

// Under the FAR 25.561 envelope the webs above are far too soft sideways
// (docs/scenes.md "Under the envelope"): each is a plate across its thickness
// to a sideways force. This part adds a member that takes that force in its own
// plane: the base continued through the opening to the frame (a plate kinked by
// the smallest bend), with a flange. Each web continues from its front vertical
// edge, kinked outwards to stay clear of the plate, and stands on a leg to the
// floor; the pair takes the twisting moment of the sideways force and the
// vertical forces. The plate comes from the search's first pass, the webs from
// its web pass, which is why the web pass composes both (docs/discovery.md
// "Plates beside webs").
struct PlateWebDesign {
  double depth;           // m, webs hung from the base's +-y edges
  double front_length;    // m, of the webs continuing them through the opening
  double plate_margin;    // m, the plate's root stops this far short of each end of the base's front edge
  double plate_theta3;    // rad, the plate's bend off the base (+: up)
  double frame_x;         // m, the frame's plane (normal -x)
  int frame_area, floor_area;
  double floor_x0, floor_x1;  // m, the legs' extent along x (inside the floor rivet area)
};

Part plate_web_part(const Problem& p, const PlateWebDesign& d) {
  const SheetSpec spec = SheetSpec::from(p);
  const double kink = p.manufacturing.min_bend_angle;
  Part part = make_base_part(p.loads[0], 0, p.material.thickness);
  const RealisedPart rb = realise(part);
  const auto& base = rb.tabs[0].corners;
  const double along = (base[1] - base[0]).norm(), across = (base[2] - base[1]).norm();
  // Base edge 1 is the front (+x) edge, the one facing the opening.
  const int plate = part.add_tab(0, 1, TabParameters{d.plate_margin, across - 2 * d.plate_margin, 0.3, 0, 0, d.plate_theta3});
  if (attach_flange(part, plate, RivetPlane{d.frame_area, Vec3(d.frame_x, 0, 0.2), Vec3(-1, 0, 0)}, spec) < 0)
    ADD_FAILURE() << "no frame flange on the plate";
  const double cut = 0.011;  // m, as in web_part
  for (int side = 0; side < 2; ++side) {
    const int web = part.add_tab(0, side == 0 ? 0 : 2, TabParameters{0, along, d.depth, 0, 0, deg(-90)});
    const int front = part.add_tab(web, side == 0 ? kEndSideEdge : kStartSideEdge,
                                   TabParameters{side == 0 ? 0.0 : cut, d.depth - cut, d.front_length, 0, 0, kink});
    add_leg(part, front, side, d.floor_x0, d.floor_x1, d.floor_area, p);
  }
  return part;
}

// The scene's own problem (its envelope, 30 Hz floor and buckling factor):
// the hand-built part with its stiffening lips is valid. Returns the lipped
// candidate for the scene's own expectations.
Candidate expect_feasible_under_envelope(const std::string& scene, const PlateWebDesign& d) {
  Problem p = load_problem(std::string(SHEETGEN_SOURCE_DIR) + "/sample_scenes/" + scene + "/problem.json");
  // Structural question, as above: the legs meet the ram of the standard press brake.
  p.manufacturing.press_brake_required = false;
  const Environment env(p);
  const Part part = plate_web_part(p, d);
  const ValidityReport v = check_validity(part, realise(part), env);
  EXPECT_TRUE(v.valid()) << scene << ": " << v.summary();
  const Candidate lipped = evaluate(p, env, add_stiffening_lips(part, env, p).part);
  EXPECT_TRUE(lipped.geometry_ok) << lipped.message;
  EXPECT_TRUE(lipped.analysed) << lipped.fem_error;
  const EnvelopeResult& e = lipped.fem.envelope;
  EXPECT_EQ(e.cases.size(), 6u);  // FAR 25.561: forward, rearward, left, right, down, up
  for (const CaseResult& c : e.cases)
    std::printf("[%s] plate and webs, %-14s C/C_max %.3f, MS %.3g\n", scene.c_str(), c.name.c_str(),
                c.compliance / c.compliance_limit, c.margin_of_safety);
  std::printf("[%s] plate and webs: buckling factor %.3g, f1 %.2f Hz\n", scene.c_str(), e.buckling_factor,
              e.frequencies_hz.empty() ? 0.0 : e.frequencies_hz.front());
  EXPECT_TRUE(e.eigen_checked);
  EXPECT_TRUE(lipped.valid()) << scene;
  return lipped;
}

// The plate passes the 100 mm slot at the base's height, the webs under it;
// the legs stand on the floor strip from just outside the baffle.
TEST(SceneFeasibility, BoxedInHasAHandBuiltPartUnderTheEnvelope) {
  const Candidate c = expect_feasible_under_envelope("boxed_in", {0.056, 0.33, 0.004, deg(-5), 0.45, 1, 0, 0.155, 0.385});
  // Sideways the plate and the webs share the load: well within the limit.
  EXPECT_LT(c.fem.envelope.cases[c.fem.envelope.governing_stiffness].compliance /
                c.fem.envelope.cases[c.fem.envelope.governing_stiffness].compliance_limit, 0.5);
}

// Through the 160 mm lightening hole; the legs span the floor patch behind
// the bulkhead. The first frequency is what binds here, just above the floor.
TEST(SceneFeasibility, BulkheadHoleHasAHandBuiltPartUnderTheEnvelope) {
  expect_feasible_under_envelope("bulkhead_hole", {0.076, 0.255, 0.002, deg(-5), 0.36, 0, 1, 0.255, 0.345});
}

}  // namespace
}  // namespace sheetgen
