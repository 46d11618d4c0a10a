#pragma once
// Flat pattern (docs/architecture.md "Manufacturing plan"; docs/manufacturing.md has the
// figures). Every tab is unfolded about its sharp bend line into its parent's
// plane and then moved away from the parent, perpendicular to the bend line, by
// the bend length change dL = BA - 2 SB (BA = |theta| (R + K t),
// SB = tan(|theta|/2) (R + t/2)); it is trimmed at (or, for dL > 0, extended to)
// its parent's edge line along its own side lines. Coordinates are the base
// tab's (x_axis, y_axis), m, seen from the sheet's top side.
#include <string>
#include <vector>

#include "sheetgen/part/validity.hpp"

namespace sheetgen {

struct FlatBend {
  int tab = -1;               // the tab this bend folds (its parent is fixed)
  int parent = -1;
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();  // centre line of the bend zone, m (a: root-start side)
  Vec2 root_a = Vec2::Zero(), root_b = Vec2::Zero();  // J0, J1: where the tab's flat piece meets the parent's edge
  Vec2 outward = Vec2::Zero();  // unit, from the parent towards the tab, perpendicular to the bend line
  double angle = 0;           // rad, signed theta3
  BendDirection direction = BendDirection::Up;  // Up: the tab folds towards the viewer of the flat pattern (top side)
  double length = 0;          // m, along the bend line (= w)
  double inside_radius = 0;   // m, R
  double allowance = 0;       // m, BA
  double setback = 0;         // m, SB
  double length_change = 0;   // m, dL = BA - 2 SB
  double centre_offset = 0;   // m, BA/2 - SB: centre line position from the parent's edge line along `outward`
};

// A relief notch cut into a parent next to the end of a bend zone.
struct FlatRelief {
  int parent = -1;            // the tab it is cut into
  int tab = -1;               // the bent tab it frees (for a notch shared by two siblings: the first)
  int other_tab = -1;         // second sibling for a shared notch, else -1
  std::vector<Vec2> polygon;  // rectangle, counter-clockwise, m
  double width = 0, depth = 0;  // m
};

struct FlatPiece {
  int tab = -1;
  int parent = -1;            // the parent tab (-1 for the base)
  std::vector<Vec2> polygon;  // the tab's own flat region, counter-clockwise, m (tab: [J1, J0, F0', F1'])
  std::vector<Vec2> sharp;    // the tab's mid-surface polygon laid flat and shifted by dL, untrimmed ([P1', P0', F0', F1'])
  // Rigid map of the tab's local frame into the flat: q = origin + x * x_axis + (y + dL) * y_axis.
  Vec2 origin = Vec2::Zero(), x_axis = Vec2::UnitX(), y_axis = Vec2::UnitY();
  double shift = 0;           // m, dL of this tab's bend (0 for the base)
};

struct FlatPatternOptions {
  double relief_width = 0;     // m, 0 = t (the narrowest slot, docs/manufacturing.md "Reliefs")
  double corner_tolerance = 1e-7;  // m, a bend ending this close to its parent edge's end needs no relief
};

struct FlatPattern {
  ValidityReason status = ValidityReason::Ok;  // Ok, FlatJunctionOutsideEdge, ReliefDoesNotFit, BendZonesOverlap, FlatPatternOverlap
  std::string message;
  int tab = -1;                          // tab at fault when not ok
  BaseTab frame;                         // flat coordinates are this frame's (the base tab's)
  std::vector<Vec2> outline;             // the one cut contour, counter-clockwise, m; relief notches included
  std::vector<int> outline_tab;          // per outline edge i (outline[i] -> outline[i+1]): tab whose boundary it is
  std::vector<FlatPiece> pieces;         // per tab, same indices as Part::tabs
  std::vector<FlatBend> bends;           // one per bent tab, in tab order (flat extensions have none)
  std::vector<FlatRelief> reliefs;
  bool ok() const { return status == ValidityReason::Ok; }
  double area() const;                   // m^2, of the outline
  double relief_area() const;            // m^2
};

// Unfolds the part. The geometry is filled as far as it can be built even when
// status is not Ok. Does not look for overlaps (check_flat_pattern does).
FlatPattern unfold(const Part& part, const SheetSpec& spec, const FlatPatternOptions& options = {});

// Overlap of the flat pattern: non-adjacent outline edges must keep the kerf
// (Manufacturing::kerf) apart. Reports FlatPatternOverlap with both tabs.
ValidityReport check_flat_pattern(const FlatPattern& flat, const SheetSpec& spec, const ValidityOptions& options = {});

// The part unfolds (status Ok) and its flat pattern has no overlap: the yes/no
// the search asks of every changed part.
bool unfolds_cleanly(const Part& part, const SheetSpec& spec);

// Where a piece of the flat pattern lies on the bent part: the rigid motion
// (rotation, then translation; m) that folds the flat plane, seen from the top
// side (z up), onto the tab's plane with z along its top normal. Bend zones
// are not rigid; for them see docs/cad.md.
struct FlatPieceTransform {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Vec3 translation = Vec3::Zero();  // m
  Vec3 apply(const Vec2& q, double z = 0) const { return rotation * Vec3(q.x(), q.y(), z) + translation; }
};

// Per piece (same indices as pieces), from the flat pattern's own data only:
// undo dL, rotate about the sharp line by theta3 about -e, compose down the tree.
std::vector<FlatPieceTransform> fold_transforms(const FlatPattern& flat);

// Folds the flat pattern back using only its own data (pieces' sharp polygons,
// bend lines, angles, dL): per tab, world corners of the mid-surface polygon in
// the order of RealisedTab::corners. A consistency check of the plan.
std::vector<std::vector<Vec3>> fold_flat_pattern(const FlatPattern& flat);

// The area the convention predicts: sum of 3-D tab areas + sum of w * dL over
// bends - relief area (m^2).
double predicted_flat_area(const Part& part, const RealisedPart& realised, const FlatPattern& flat, const SheetSpec& spec);

}  // namespace sheetgen
