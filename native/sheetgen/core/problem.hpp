#pragma once
// The problem a user poses ("sheetgen-problem/1", see docs/problem-format.md):
// environment meshes, rivet areas, loads, and settings with documented defaults.
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sheetgen/core/cost_model.hpp"
#include "sheetgen/core/load_cases.hpp"
#include "sheetgen/core/press_brake_tooling.hpp"
#include "sheetgen/core/triangle_mesh.hpp"

namespace sheetgen {

struct EnvironmentMesh {
  std::string name;
  TriangleMesh mesh;   // m
  std::string source;  // file it was read from, or "<inline>"
};

struct RivetAreaSpec {
  std::string name;
  int mesh = -1;           // index into Problem::meshes
  std::vector<int> faces;  // face indices of that mesh, unique, sorted
  double area_m2 = 0;      // computed on load
};

struct Load {
  std::string name;
  Vec3 center = Vec3::Zero();                              // m, box centroid (world)
  Vec3 size = Vec3::Zero();                                // m, box extents along its local x, y, z
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  // local -> world
  // The first of `cases` (kept so single-case code reads it as before): N, world
  // frame, acting at the centre of mass; N*m about it.
  Vec3 force = Vec3::Zero();
  Vec3 moment = Vec3::Zero();

  // Mass properties (docs/problem-format.md "Load cases"). The reader fills
  // center_of_mass with `center` and inertia with uniform_box_inertia() when
  // the file gives a mass but not them; without a mass inertia stays zero. A
  // Load built in code sets these and `cases` itself.
  std::optional<double> mass;                              // kg, > 0
  Vec3 center_of_mass = Vec3::Zero();                      // m, world, inside the box
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();       // kg*m^2, world frame, about center_of_mass
  // Every static case the part must hold, each separately; names unique. After
  // reading, never empty: the explicit `cases` or the `force`/`moment` case
  // "design", then (with a mass) one case per factor of Problem::load_cases.
  std::vector<LoadCase> cases;

  // The 8 world corners; index bit 0 = +x, bit 1 = +y, bit 2 = +z in the local frame.
  std::array<Vec3, 8> corners() const;
  // The 12 triangles of the box, outward facing.
  TriangleMesh box_mesh() const;
  // Signed distance from p to the box (negative inside), m.
  double signed_distance(const Vec3& p) const;
  // The bottom face (local -z) as 4 world points, counter-clockwise seen from below
  // (outward normal = local -z). The base tab lies under this face.
  std::array<Vec3, 4> bottom_face() const;
};

struct Material {  // Al 2024-T3 sheet by default (docs/architecture.md "Units and defaults")
  double youngs_modulus = 73.1e9;  // Pa
  double poisson_ratio = 0.33;     // -
  double density = 2780.0;         // kg/m^3
  double yield_strength = 345e6;   // Pa, Fty
  double ultimate_strength = 483e6;// Pa, Ftu
  double thickness = 1.6e-3;       // m (0.063 in)
  // Thicker sheets the shop stocks, m, ascending, each above `thickness`: a
  // load with no valid part at `thickness` is searched again at each in turn
  // (core/sheet_gauges.hpp). The reader's default is the standard 2024-T3
  // gauges above `thickness` for a file in the envelope format, none for one
  // with one force per load (it solves as written); empty: the problem's sheet only.
  std::vector<double> gauges;
};

struct Requirements {
  // Stiffness: C <= max_compliance (J). If the file gives max_deflection instead,
  // max_compliance = |F| * max_deflection per load. Default: max_deflection 1 mm.
  std::optional<double> max_compliance;  // J
  std::optional<double> max_deflection;  // m
  double min_margin_of_safety = 0.0;     // -, MS = Fty / (SF * sigma_vm_max) - 1
  double safety_factor = 1.5;            // -
  double clearance = 1.0e-3;             // m, gap kept beyond t/2 between mid-surface and obstacles
  // Lowest linear buckling factor over the cases (critical load / applied load),
  // -; the reader's default is safety_factor: no buckling below ultimate load.
  double min_buckling_factor = 1.5;
  std::optional<double> min_frequency_hz;  // Hz, first natural frequency floor; none by default
  // Whether the buckling and frequency checks apply: the file uses the
  // envelope format (a load's mass or cases, or load_cases) or names
  // min_buckling_factor or min_frequency_hz. A file with one force per load
  // and neither keeps the checks it was written for, so it solves as before
  // (docs/problem-format.md "Load cases").
  bool eigen_checks = false;
  // The search holds a part's buckling factor and first frequency to the
  // floors above times these, so that an independent solver agrees the part
  // meets the floors themselves: measured against CalculiX's S6 shells, our
  // buckling factor was up to 5.6 % and our f1 up to 1.7 % above theirs
  // (docs/fem.md "Model reserve on the eigen checks"). Results still report
  // the floors as the problem gives them. -
  double buckling_model_reserve = 1.06;
  double frequency_model_reserve = 1.02;

  // The floors the search holds a part to (the required ones times the reserves).
  double design_buckling_factor() const { return min_buckling_factor * buckling_model_reserve; }
  std::optional<double> design_frequency_hz() const;  // Hz, none when min_frequency_hz is none

  // Compliance limit for a load with force magnitude |F| (N), J.
  double compliance_limit(double force_magnitude) const;
  // Compliance limit of one case, J: |F| * the case's own max_deflection when it
  // has one, else compliance_limit(|F|).
  double compliance_limit(const LoadCase& load_case) const;
};

// The manufacturing lengths whose defaults are multiples of the sheet
// thickness, as the problem file gave them (unset: the default), so that a
// thicker gauge derives its own (core/sheet_gauges.hpp). m.
struct ThicknessScaledInput {
  std::optional<double> bend_radius, min_flange, min_tab_width, min_tab_length;
  std::optional<double> rivet_diameter, rivet_edge_distance, rivet_pitch;
};

struct Manufacturing {  // lengths m, angles rad; defaults depend on thickness t (filled on load)
  ThicknessScaledInput given;    // what the file said of the lengths below that scale with t
  double bend_radius = 0;        // inside bend radius R; default 4 t
  double k_factor = 0.45;        // neutral-axis position as a fraction of t
  double kerf = 0.2e-3;          // gap kept between flat-pattern pieces, m
  double min_flange = 0;         // minimum rivet flange length; default 4 t + R
  double min_tab_width = 0;      // w_min, feeler width; default 10 t
  double min_tab_length = 0;     // l_min; default 2 R + 2 t (room for the bend)
  double max_tab_length = 0.5;   // l_max, m
  // |theta3| lower limit. A shop would want twice the sheet's springback,
  // 6.5 deg for 2024-T3; the default stays at the grammar's 5 deg until the
  // search finds the sample scenes' parts without (docs/cost.md "Minimum bend
  // angle").
  double min_bend_angle = 5.0 * M_PI / 180.0;
  double max_bend_angle = 135.0 * M_PI / 180.0;  // |theta3| upper limit (press brake tooling)
  double max_skew = 60.0 * M_PI / 180.0;         // |theta1|, |theta2| limit
  // A tab may also continue its parent's plane (theta3 = 0 exactly): a flat
  // extension, cut in one piece with its parent and not bent. Off in the paper's
  // grammar; on in right-angle mode, where it is how an expert widens a plate
  // (docs/grammar.md "Flat extensions").
  bool flat_extensions = false;
  double rivet_diameter = 0;     // default: 2 t rounded up to 1/32 in, at least 3.2 mm (1/8 in)
  double rivet_edge_distance = 0;// default 2 * rivet_diameter (MIL-HDBK practice)
  double rivet_pitch = 0;        // default 6 * rivet_diameter
  // The press-brake tools (part/press_brake.hpp, docs/manufacturing.md
  // "Press brake"). The answer's bend sequence is always checked on them.
  // `press_brake_required`: the search also refuses a candidate they cannot
  // bend ("prefer", the default, and "require"). `press_brake_fallback`
  // ("prefer"): a load for which no such part is found is searched again
  // without the check, and its answer says which bend the tools cannot make.
  // "report" turns both off.
  bool press_brake_required = true;
  bool press_brake_fallback = true;
  PressBrakeTooling press_brake_tools = default_press_brake_tooling();  // `press_brake_tools`

  // The expert's practice (paper Sec. 1): every bend 90 deg, no skew, and plates
  // widened by flat extensions, as an expert cuts a plate larger rather than
  // bending it (docs/grammar.md "Flat extensions"). Set as limits, so
  // sampling, optimisation and validity all obey it; +-0.5 deg and 1 mrad absorb
  // rounding in the angles that are solved for.
  void restrict_to_right_angles();
  // Whether these limits are already the right-angle ones.
  bool right_angles_only() const;
  // Whether the right-angle grammar is a strict subset of the one these limits
  // allow: 90 deg lies inside the bend limits and they are not right-angle
  // already (the right-angle pass, docs/pipeline.md "Right-angle pass").
  bool admits_right_angle_pass() const;
};

struct SearchSettings {
  int chains = 10;          // M
  int iterations = 1000;    // N per chain
  int beam_width = 8;       // B
  std::uint64_t seed = 1;
  double alpha = 1.0;       // Eq. 1
  double beta = 3.0;        // Eq. 1
  double scene_unit = 0.1;  // m; distances in Eq. 1-2 are measured in this unit (decimetres)
  int threads = 0;          // 0 = all cores
};

struct Problem {
  std::string source;  // the JSON file, or "<inline>"
  std::vector<EnvironmentMesh> meshes;
  std::vector<RivetAreaSpec> rivet_areas;
  std::vector<Load> loads;
  // The problem-level `load_cases` as read (its cases are already in every
  // massed load's `cases`); kept so outputs can say which envelope was used.
  std::optional<InertiaEnvelope> load_cases;
  Material material;
  Requirements requirements;
  Manufacturing manufacturing;
  CostModel cost;
  SearchSettings search;

  BoundingBox bounds() const;  // of meshes and load boxes
  int triangle_count() const;
};

// Reads and validates a problem file. Mesh files are resolved relative to the
// JSON's directory. Throws InputError (file, field, problem) on any bad input.
Problem load_problem(const std::string& path);
// Same from JSON text; `source` names it in errors, `base_dir` resolves mesh files.
Problem parse_problem(const std::string& json_text, const std::string& source, const std::string& base_dir);

}  // namespace sheetgen
