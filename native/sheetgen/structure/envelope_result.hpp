#pragma once
// What the envelope analysis of a part reports (envelope_analysis.hpp): per
// load case the static checks and its buckling factor, and over the cases the
// governing case of each check and the natural frequencies.
#include <limits>
#include <string>
#include <vector>

#include "sheetgen/core/problem.hpp"
#include "sheetgen/fem/shell_model.hpp"

namespace sheetgen {

struct CaseResult {
  std::string name;
  Vec3 force = Vec3::Zero();       // N, world
  double compliance = 0;           // J, f^T u
  double compliance_limit = 0;     // J, this case's (requirements and its own max_deflection)
  double deflection = 0;           // m, |translation| of the load centroid
  double deflection_along_force = 0;  // m, u . F/|F|
  double max_von_mises = 0;        // Pa, by the stress rule
  double margin_of_safety = 0;     // -
  bool stiff_enough = false;       // compliance <= compliance_limit
  bool strong_enough = false;      // MS >= required
  // -, lowest buckling load factor (+inf when the case compresses nothing, or
  // when buckling was not asked for: see buckling_checked).
  double buckling_factor = std::numeric_limits<double>::infinity();
  bool buckling_checked = false;
};

struct EnvelopeResult {
  std::vector<CaseResult> cases;
  // Index into cases of the case that governs each check: the largest C/C_max,
  // the lowest MS, the lowest buckling factor (-1: none).
  int governing_stiffness = -1, governing_strength = -1, governing_buckling = -1;
  double buckling_factor = std::numeric_limits<double>::infinity();  // -, min over the cases
  std::vector<double> frequencies_hz;                                 // ascending
  double box_mass = 0, sheet_mass = 0;                                // kg
  std::vector<Vector6d> buckling_mode, vibration_mode;               // #N, when kept
  int elements = 0, dofs = 0;
  double static_seconds = 0, buckling_seconds = 0, vibration_seconds = 0, seconds = 0;

  // The worst C/C_max and lowest MS over the cases.
  double worst_compliance_ratio() const;
  double lowest_margin_of_safety() const;
  // Whether the eigen checks ran (they may be skipped after a failed static case).
  bool eigen_checked = false;
  // Against the problem's requirements (true when not checked or not required):
  // the lowest buckling factor >= design_buckling_factor(), f1 >=
  // design_frequency_hz() (the floors with the model's reserve).
  bool stable_enough = true;
  bool frequency_ok = true;
};

}  // namespace sheetgen
