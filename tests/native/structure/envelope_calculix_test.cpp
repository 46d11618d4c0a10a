// The envelope analysis of three real parts against CalculiX on the decks
// export-ccx writes (docs/fem.md "Envelope analysis"): the corner sample's
// part, the avionics bay's transponder part and its gps_receiver part (one
// self-rivet), each with its box's mass (the design force / 9 g, the 9 g
// downward stand-in it was designed for) and the FAR 25.561 envelope. ccx
// runs S6 on the same triangles (quadratic shells, docs/fem.md "Which
// CalculiX reference"): buckling factor and first frequency within 5 %. The
// static cases' compliances are printed beside ccx's; they are asserted
// against the solid model (tests/python/test_envelope_solid.py, 3 %), since
// CalculiX's shells on our triangles scatter about it by more than that.
// Full tier (ccx).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "sheetgen/core/load_cases.hpp"
#include "sheetgen/fem/ccx_export.hpp"
#include "sheetgen/structure/envelope_analysis.hpp"
#include "../common/single_force.hpp"

namespace sheetgen {
namespace {

namespace fs = std::filesystem;

std::string read_fixture(const std::string& name) {
  std::ifstream in(std::string(SHEETGEN_SOURCE_DIR) + "/tests/native/structure/data/" + name + ".json");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The scene's problem with load `load` given the mass its design force (9 g
// down) stands for and the FAR 25.561 envelope after its design case (x
// forward, z up): the case set the CalculiX references were measured on.
Problem envelope_problem(const std::string& scene, const std::string& load, int& index) {
  Problem p =
      test::single_force(load_problem(std::string(SHEETGEN_SOURCE_DIR) + "/sample_scenes/" + scene + "/problem.json"));
  index = -1;
  for (size_t i = 0; i < p.loads.size(); ++i)
    if (p.loads[i].name == load) index = static_cast<int>(i);
  Load& l = p.loads.at(index);
  const double mass = l.force.norm() / (9.0 * kStandardGravity);
  l.mass = mass;
  l.center_of_mass = l.center;
  l.inertia = uniform_box_inertia(mass, l.size, l.rotation);
  InertiaEnvelope env;
  env.factors = far25_561_factors();
  for (const InertiaFactor& f : env.factors) l.cases.push_back(inertia_case(env, f, mass));
  return p;
}

// The envelope's cases that CalculiX solves: design, forward 9 g, left 3 g and
// down 6 g. The other three are -1/6, -1 and -1/2 times forward, left and
// down: in a linear model C = F^T K^-1 F, so their compliances are those
// cases' times 1/36, 1 and 1/4 exactly, in ccx as in ours (EnvelopeAnalysis
// tests check ours case by case). Each ccx step refactors, so the three
// mirrored steps would add half the run time and no information.
std::vector<LoadCase> independent_cases(const Load& l) {
  std::vector<LoadCase> kept;
  for (const LoadCase& c : l.cases)
    if (c.name == "design" || c.name == "forward 9 g" || c.name == "left 3 g" || c.name == "down 6 g") kept.push_back(c);
  return kept;
}

double lowest(const std::vector<double>& v) { return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end()); }

void compare_with_calculix(const std::string& scene, const std::string& load, const std::string& fixture) {
  int index = -1;
  Problem p = envelope_problem(scene, load, index);
  p.loads[index].cases = independent_cases(p.loads[index]);
  const std::string text = read_fixture(fixture);
  PartModelOptions mo;
  mo.self_rivets = self_rivet_ties_from_json(text, fixture);
  const PartModel pm = build_part_model(p, index, plate_geometry_from_json(text, fixture), mo);
  ShellSolver solver;
  EnvelopeOptions eo;
  eo.frequencies = 1;
  const EnvelopeResult ours = analyse_envelope(p, pm, eo, mo.element, solver);
  ASSERT_GE(ours.governing_buckling, 0);

  const fs::path dir = fs::temp_directory_path() / ("sheetgen_envelope_ccx_" + fixture);
  fs::create_directories(dir);
  CcxExportOptions co;
  co.element_type = "S6";
  co.buckle_case = ours.governing_buckling;
  // Three, not one: asked for one factor, ccx 2.20's *BUCKLE returned the
  // transponder part's second (1.398 against 0.754); its iteration needs room
  // beside the wanted eigenvalue. The lowest of the three is compared.
  co.buckling_factors = 3;
  co.frequency_modes = 1;
  const CcxEnvelope ccx = solve_envelope_with_ccx(pm.model, dir.string(), "envelope", "ccx", co);
  fs::remove_all(dir);

  ASSERT_EQ(ccx.cases.size(), ours.cases.size());
  for (size_t k = 0; k < ours.cases.size(); ++k) {
    std::printf("%s %-15s C ours %.6g J, ccx S6 %.6g J (%+.2f %%)\n", fixture.c_str(), ours.cases[k].name.c_str(),
                ours.cases[k].compliance, ccx.cases[k].compliance,
                100 * (ours.cases[k].compliance / ccx.cases[k].compliance - 1));
  }
  std::printf("%s buckling (%s) ours %.5g, ccx %.5g (%+.2f %%); f1 ours %.5g Hz, ccx %.5g Hz (%+.2f %%); ccx %.0f s\n",
              fixture.c_str(), ours.cases[ours.governing_buckling].name.c_str(), ours.buckling_factor,
              lowest(ccx.buckling_factors), 100 * (ours.buckling_factor / lowest(ccx.buckling_factors) - 1),
              ours.frequencies_hz.at(0), ccx.frequencies_hz.at(0),
              100 * (ours.frequencies_hz.at(0) / ccx.frequencies_hz.at(0) - 1), ccx.wall_seconds);
  EXPECT_NEAR(ours.buckling_factor / lowest(ccx.buckling_factors), 1.0, 0.05);
  EXPECT_NEAR(ours.frequencies_hz.at(0) / ccx.frequencies_hz.at(0), 1.0, 0.05);
}

TEST(EnvelopeCalculix, CornerPartAgreesWithCalculix) {
  compare_with_calculix("corner", "avionics_box", "corner_avionics_box");
}

TEST(EnvelopeCalculix, BayTransponderPartAgreesWithCalculix) {
  compare_with_calculix("avionics_bay", "transponder", "bay_transponder");
}

TEST(EnvelopeCalculix, SelfRivetedBayPartAgreesWithCalculix) {
  compare_with_calculix("avionics_bay", "gps_receiver", "bay_gps_receiver_self_rivet");
}

}  // namespace
}  // namespace sheetgen
