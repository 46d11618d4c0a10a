#pragma once
// A part's structural model (docs/architecture.md "FEM"): its tabs meshed as one
// conforming shell, rivet flanges clamped at their rivets, the load box rigid
// and bonded to the base tab (master node at the box centroid carrying the
// force and moment), self-rivets as rigid ties. Also the one-call analysis the
// composition step uses, and the CalculiX deck of the same model.
#include <optional>
#include <string>
#include <vector>

#include "sheetgen/core/problem.hpp"
#include "sheetgen/fem/plate_mesher.hpp"
#include "sheetgen/fem/shell_model.hpp"
#include "sheetgen/part/part.hpp"
#include "sheetgen/part/realisation.hpp"
#include "sheetgen/structure/envelope_result.hpp"

namespace sheetgen {

// The geometry the FEM needs, independent of how it was produced (a Part in
// memory, or the tabs[] of a result.json): planar convex polygons, m, with the
// rivet area each one is riveted to (-1 = none) and the edge rivets line up along.
struct PlateGeometry {
  std::vector<std::vector<Vec3>> polygons;
  std::vector<int> rivet_area;  // per polygon
  std::vector<int> rivet_edge;  // per polygon: edge i (vertex i -> i+1) rivets run along
  // The bends, so rivets stay on flat sheet (docs/fem.md "Rivets"): per polygon
  // its parent polygon (-1: none) and |theta3| of the bend between them (rad;
  // 0: a flat extension, no bend). A bent polygon's first edge (corner 0 -> 1)
  // is its root on the parent's edge. Empty: no bends known.
  std::vector<int> parent;
  std::vector<double> bend_angle;
};

// A self-rivet: two points (one on each sheet, m) that are tied rigidly.
struct SelfRivetTie {
  int polygon_a = -1, polygon_b = -1;
  Vec3 point_a = Vec3::Zero(), point_b = Vec3::Zero();
};

struct PartModelOptions {
  double element_size = 0;                // m; <= 0: default_element_size (docs/fem.md)
  std::vector<SelfRivetTie> self_rivets;  // tied after meshing
  ShellElementOptions element;            // DKMT (transverse shear) by default
  // analyse_part(): buckling of every case and the first three frequencies
  // too, when every static case passes. They decide stable_enough and
  // frequency_ok only where the problem asks (Requirements::eigen_checks).
  bool eigen_checks = false;
};

struct PartModel {
  ShellModel model;
  PlateMesh mesh;                     // mesh.element_polygon: element -> polygon
  int load_index = -1;                // the problem's load this part holds
  int load_node = -1;                 // the rigid box's master (centroid) node
  std::vector<Vec3> rivets;           // m, rivet centres on flanges
  std::vector<int> rivet_polygon;     // per rivet, the flange polygon
};

// Tabs of a realised part as plate geometry; a rivet flange's rivets run along its far edge.
// parent and bend_angle from the tab tree (flat extensions are no bends).
PlateGeometry plate_geometry(const Part& part, const RealisedPart& realised);

// Where polygon k's sheet is not flat, as convex polygons in its plane (m):
// its root's bend zone (the setback deep along the whole root) and, per bent
// child, the child's bend zone on k's edge with the relief notches beside it
// (bend_zone_depth deep, t beyond each end). Rivets keep the edge distance
// from them. Empty when the geometry has no bends.
std::vector<std::vector<Vec3>> bend_keep_out(const PlateGeometry& geometry, int k, const SheetSpec& sheet);

// Throws FemError (a sentence naming the cause) when the model cannot be built:
// no rivet flange (nothing holds the part: a mechanism), no base-tab node under
// the load box, a flange too small for one rivet, zero thickness.
PartModel build_part_model(const Problem& problem, int load_index, const PlateGeometry& geometry,
                           const PartModelOptions& options = {});

// How many rivets build_part_model() sets on the geometry's flanges (the same
// layout, without a mesh): what the part's cost counts before its FEM. Throws
// FemError like build_part_model() when a flange holds no rivet or there is
// no flange.
int flange_rivet_count(const Problem& problem, const PlateGeometry& geometry);

// A part's answer to its load: over every case of the load (one for a
// one-force load), the numbers of the case that governs each check.
struct StructuralResult {
  // Of the stiffness-governing case (largest C / C_max):
  double compliance = 0;        // J, f^T u
  double deflection = 0;        // m, |translation| of the load centroid
  // m, the load centroid's translation along the force, u . F/|F|: what a
  // max_deflection requirement bounds (C = F . u when there is no moment). A
  // part may swing sideways more than this without breaking the requirement.
  double deflection_along_force = 0;
  double compliance_limit = 0;  // J, from the requirements
  // Of the strength-governing case (lowest MS):
  double max_von_mises = 0;     // Pa, by the stress rule of docs/fem.md
  double margin_of_safety = 0;  // -, Fty / (SF sigma) - 1
  bool stiff_enough = false;    // every case: compliance <= its limit
  bool strong_enough = false;   // every case: MS >= required
  // The buckling and frequency checks (eigen_checks in the options): true
  // when they pass, are not required, or were not run.
  bool stable_enough = true;
  bool frequency_ok = true;
  EnvelopeResult envelope;      // every case, governing cases, buckling factor, frequencies
  int elements = 0;
  int dofs = 0;                 // reduced unknowns
  int rivets = 0;
  double seconds = 0;           // build + solve

  bool passes() const { return stiff_enough && strong_enough && stable_enough && frequency_ok; }
};

// The solve options analyse_part() uses for this problem: its safety factor,
// its bend radius as the stress rule's clearance at fold ends, `element`.
ShellSolveOptions part_solve_options(const Problem& problem, const ShellElementOptions& element = {});

// Builds and solves. `solver` (optional) keeps symbolic factorisations between
// calls (composition solves many similar parts); one solver per thread.
StructuralResult analyse_part(const Problem& problem, int load_index, const PlateGeometry& geometry,
                              const PartModelOptions& options = {}, ShellSolver* solver = nullptr);

// The tabs[] of a sheetgen-result/1 part (corners, rivet_area; parent,
// parent_edge and parameters.theta3 for the bends when present) as plate geometry.
// Throws InputError naming `source` and the field when the JSON is malformed.
PlateGeometry plate_geometry_from_json(const std::string& json_tabs_text, const std::string& source);

// The self_rivets[] of a sheetgen-result/1 part: per tie the two tab indices
// and one point on each sheet (m), so a re-analysis (export-ccx) ties what the
// solver tied. Empty when the part has none. Throws InputError naming
// `source` and the field when an entry is malformed.
std::vector<SelfRivetTie> self_rivet_ties_from_json(const std::string& json_part_text, const std::string& source);

// The thickness_m of a sheetgen-result/1 part (the sheet it is made of, m; a
// thicker gauge when the problem's gave the load none), or nullopt when the
// part does not say (older files). Throws InputError naming `source` and the
// field when it is not a positive number.
std::optional<double> sheet_thickness_from_json(const std::string& json_part_text, const std::string& source);

}  // namespace sheetgen
