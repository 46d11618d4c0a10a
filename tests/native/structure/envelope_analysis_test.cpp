// A part over its load's envelope (docs/fem.md "Envelope analysis"): every
// case agrees with the single-case analysis of the same force, the governing
// cases are the extremes, and the box mass enters the frequencies.
#include "sheetgen/structure/envelope_analysis.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "hat_bracket.hpp"
#include "sheetgen/core/load_cases.hpp"
#include "sheetgen/fem/buckling.hpp"
#include "sheetgen/structure/part_model.hpp"

namespace sheetgen {
namespace {

// The hat bracket's box with 4 kg and the FAR 25.561 envelope (x forward, z up)
// after its design case.
Problem envelope_problem() {
  Problem p = test::bracket_problem();
  Load& l = p.loads[0];
  l.mass = 4.0;
  l.center_of_mass = l.center;
  l.inertia = uniform_box_inertia(4.0, l.size, l.rotation);
  l.cases = {LoadCase{"design", l.force, l.moment, {}}};
  InertiaEnvelope env;
  env.factors = far25_561_factors();
  for (const InertiaFactor& f : env.factors) l.cases.push_back(inertia_case(env, f, 4.0));
  return p;
}

TEST(EnvelopeAnalysis, EveryCaseEqualsTheSingleCaseAnalysisOfItsForce) {
  const Problem p = envelope_problem();
  const Part part = test::hat_part(p);
  const PlateGeometry g = plate_geometry(part, realise(part));
  const EnvelopeResult env = analyse_part_envelope(p, 0, g);
  ASSERT_EQ(env.cases.size(), 7u);
  for (size_t k = 0; k < env.cases.size(); ++k) {
    Problem one = p;
    one.loads[0].cases = {p.loads[0].cases[k]};
    one.loads[0].force = p.loads[0].cases[k].force;
    one.loads[0].moment = p.loads[0].cases[k].moment;
    const StructuralResult s = analyse_part(one, 0, g);
    const CaseResult& c = env.cases[k];
    EXPECT_EQ(c.name, p.loads[0].cases[k].name);
    EXPECT_NEAR(c.compliance / s.compliance, 1.0, 1e-9) << c.name;
    EXPECT_NEAR(c.margin_of_safety, s.margin_of_safety, 1e-9 * std::abs(s.margin_of_safety)) << c.name;
    EXPECT_NEAR(c.deflection_along_force, s.deflection_along_force, 1e-12) << c.name;
    EXPECT_TRUE(c.buckling_checked);
  }
  // The governing cases are the extremes over the cases.
  for (const CaseResult& c : env.cases) {
    EXPECT_LE(c.compliance / c.compliance_limit, env.worst_compliance_ratio());
    EXPECT_GE(c.margin_of_safety, env.lowest_margin_of_safety());
    EXPECT_GE(c.buckling_factor, env.buckling_factor);
  }
  EXPECT_EQ(env.buckling_factor, env.cases[env.governing_buckling].buckling_factor);
  ASSERT_EQ(env.frequencies_hz.size(), 3u);
  EXPECT_GT(env.frequencies_hz[0], 0.0);
  EXPECT_DOUBLE_EQ(env.box_mass, 4.0);
}

// Opposite cases (left and right, forward and rearward, down and up) share
// one eigen solve (docs/fem.md "Envelope analysis"); every case's buckling
// factor equals its own analyse_buckling to 1e-7 (both Lanczos runs converge
// to a relative residual of 1e-9).
TEST(EnvelopeAnalysis, OppositeCasesBuckleAsTheirOwnSolves) {
  const Problem p = envelope_problem();
  const Part part = test::hat_part(p);
  const PlateGeometry g = plate_geometry(part, realise(part));
  const EnvelopeResult env = analyse_part_envelope(p, 0, g);
  const PartModelOptions mo;
  const PartModel pm = build_part_model(p, 0, g, mo);
  const ShellSolveOptions so = part_solve_options(p, mo.element);
  ShellSolver solver;
  const std::vector<ShellResult> statics = solver.solve_cases(pm.model, so);
  ASSERT_EQ(statics.size(), env.cases.size());
  int finite = 0;
  for (size_t k = 0; k < statics.size(); ++k) {
    const double own = analyse_buckling(solver, pm.model, statics[k], so).factor();
    if (std::isinf(own)) {
      EXPECT_TRUE(std::isinf(env.cases[k].buckling_factor)) << env.cases[k].name;
      continue;
    }
    ++finite;
    EXPECT_NEAR(env.cases[k].buckling_factor / own, 1.0, 1e-7) << env.cases[k].name;
  }
  EXPECT_GE(finite, 6);  // the six inertia cases all compress some of the hat
}

// A force at a centre of mass off the centroid is the same force plus its
// moment r x F at the centroid.
TEST(EnvelopeAnalysis, OffCentreMassAddsTheMomentOfItsForce) {
  Problem p = envelope_problem();
  Load& l = p.loads[0];
  const Vec3 r(0.02, -0.01, 0.03);
  l.center_of_mass = l.center + r;
  const Part part = test::hat_part(p);
  const PlateGeometry g = plate_geometry(part, realise(part));
  EnvelopeOptions quick;
  quick.buckling = false;
  quick.frequencies = 0;
  const EnvelopeResult env = analyse_part_envelope(p, 0, g, {}, quick);
  for (size_t k = 0; k < env.cases.size(); ++k) {
    Problem one = test::bracket_problem();
    one.loads[0].force = l.cases[k].force;
    one.loads[0].moment = l.cases[k].moment + r.cross(l.cases[k].force);
    EXPECT_NEAR(env.cases[k].compliance / analyse_part(one, 0, g).compliance, 1.0, 1e-9) << env.cases[k].name;
  }
}

// A part passes the eigen checks only with the model's reserve above the
// floors (Requirements::buckling_model_reserve): its own factor and f1 put the
// floors just inside and just outside that reserve.
TEST(EnvelopeAnalysis, EigenChecksHoldThePartToTheFloorsTimesTheModelReserve) {
  Problem p = envelope_problem();
  p.requirements.eigen_checks = true;
  const Part part = test::hat_part(p);
  const PlateGeometry g = plate_geometry(part, realise(part));
  const EnvelopeResult free = analyse_part_envelope(p, 0, g);
  ASSERT_TRUE(std::isfinite(free.buckling_factor));
  ASSERT_FALSE(free.frequencies_hz.empty());
  const double lambda = free.buckling_factor, f1 = free.frequencies_hz.front();
  const Requirements& req = p.requirements;
  ASSERT_GT(req.buckling_model_reserve, 1.0);
  ASSERT_GT(req.frequency_model_reserve, 1.0);
  // Floors that the part meets, by a half and by one and a half times the reserve.
  const double b_half = 1.0 + 0.5 * (req.buckling_model_reserve - 1.0), f_half = 1.0 + 0.5 * (req.frequency_model_reserve - 1.0);
  const double b_over = 1.0 + 1.5 * (req.buckling_model_reserve - 1.0), f_over = 1.0 + 1.5 * (req.frequency_model_reserve - 1.0);
  auto judged = [&](double buckling_floor, double frequency_floor) {
    Problem q = p;
    q.requirements.min_buckling_factor = buckling_floor;
    q.requirements.min_frequency_hz = frequency_floor;
    return analyse_part_envelope(q, 0, g);
  };
  const EnvelopeResult inside = judged(lambda / b_half, f1 / f_half);
  EXPECT_NEAR(inside.buckling_factor, lambda, 1e-9 * lambda);
  EXPECT_FALSE(inside.stable_enough);
  EXPECT_FALSE(inside.frequency_ok);
  const EnvelopeResult outside = judged(lambda / b_over, f1 / f_over);
  EXPECT_TRUE(outside.stable_enough);
  EXPECT_TRUE(outside.frequency_ok);
}

}  // namespace
}  // namespace sheetgen
