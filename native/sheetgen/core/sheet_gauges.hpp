#pragma once
// Sheet gauges: the thicker sheets a load is searched at when the problem's
// sheet gives it no valid part (docs/pipeline.md "Thicker gauges"). A designer
// whose bracket is too soft or buckles takes the same kind of bracket in the
// next gauge the shop stocks; this is that step, with the search redone at
// each gauge, because every clearance, bend radius and flange length grows
// with the thickness.
#include <optional>
#include <vector>

#include "sheetgen/core/problem.hpp"

namespace sheetgen {

// The standard 2024-T3 clad sheet gauges of AMS-QQ-A-250/4 from 0.016 to
// 0.160 in, in metres, ascending.
const std::vector<double>& standard_gauges();

// The reader's default for material.gauges: the standard gauges thicker than
// `thickness` (m), ascending. Thicker than 0.160 in a bracket is machined or
// built up, not bent from one sheet, so the list stops there.
std::vector<double> default_gauges(double thickness);

// Fills the manufacturing lengths that scale with the thickness t (m): the
// file's value where `mf.given` has one, else the default multiple of t
// (docs/problem-format.md "manufacturing").
void derive_thickness_defaults(Manufacturing& mf, double thickness);

// The same problem in another sheet of the same material: thickness t (m)
// and the lengths that scale with it derived again; everything else as it is.
Problem at_gauge(const Problem& problem, double thickness);

// `problem` at the sheet a part is made of (a LoadOutcome's thickness,
// result.json's thickness_m): the problem itself when that is its own sheet
// or unknown (<= 0), else at_gauge, kept in `storage`. No copy in the common
// case (a scene's meshes may be large), and a problem built in code, whose
// thickness-scaled lengths were set by hand, keeps them.
const Problem& problem_at_sheet(const Problem& problem, double thickness, std::optional<Problem>& storage);

}  // namespace sheetgen
