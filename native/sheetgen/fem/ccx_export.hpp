#pragma once
// CalculiX (ccx 2.20) input deck of a ShellModel, the readers of its .dat
// output, and a runner - for engineers who verify elsewhere
// (`sheetgen export-ccx`) and for the validation tests (docs/fem.md "CalculiX").
//
// CalculiX's S3 locks (-21 % on the cantilever strip, docs/platform.md). The
// deck is either our triangles as quadratic S6 (a node added at each edge
// midpoint) or each triangle split into three quadrilaterals (corner, edge
// midpoint, centroid, edge midpoint) as S4, S4R or S8R; midpoints are shared by
// the two triangles of an edge, so the deck's mesh is conforming.
// Rigid links become *RIGID BODY with a REF NODE (translations) and a ROT NODE
// (whose "translations" are the rotations); supports become *BOUNDARY in the
// model section, each load case its own *STATIC step with *CLOAD. Optional
// *BUCKLE and *FREQUENCY steps come before the static ones; point masses
// become MASS elements in a rigid body (ccx 2.20 has no rotary inertia).
// Units are the model's: m, N, Pa, kg.
//
// Deck writing is in ccx_export.cpp, the .dat readers and the runner in
// ccx_results.cpp.
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include "sheetgen/fem/shell_model.hpp"

namespace sheetgen {

struct CcxExportOptions {
  std::string heading = "sheetgen flat-shell model";
  // "S4", "S4R", "S6" or "S8R". S6 keeps our triangles (quadratic, six
  // nodes); the others split each into 3 quads (S8R with a mid-side node per
  // quad edge). S6 is the buckling and frequency reference of the tests: it
  // keeps our mesh and meets the closed forms; compliance is checked against a
  // solid model, since every shell deck on our triangles scatters about it by
  // a few % (docs/fem.md "Which CalculiX reference").
  std::string element_type = "S4";
  // A *BUCKLE step for this case of model.cases() (index from 0); -1: none.
  // ccx scales the loads given in that step alone (no preload), so each
  // factor is a multiple of this case's loads.
  int buckle_case = -1;
  int buckling_factors = 3;  // -, how many buckling factors *BUCKLE asks for (>= 1)
  // A *FREQUENCY step asking for this many of the lowest eigenfrequencies; 0: none.
  // The sheet's mass comes from material.density (*DENSITY), the rigid masses
  // from model.point_masses.
  int frequency_modes = 0;
};

// Where the model's entities went in the deck (CalculiX ids are 1-based).
struct CcxDeckMap {
  std::vector<int> node_id;        // #N model nodes -> deck node id (-1: not written, unused by elements and links)
  std::vector<int> ref_node;       // per rigid link: its REF NODE id (translations of the master)
  std::vector<int> rot_node;       // per rigid link: its ROT NODE id (rotations of the master)
  std::vector<int> mass_ref_node;  // per point mass: the REF NODE of the rigid body that carries it
  int node_count = 0;              // deck nodes
  int element_count = 0;           // deck shell elements (per triangle: 1 S6, or 3 quads)
  int mass_element_count = 0;      // MASS elements (1 to 7 per point mass)
  int static_steps = 0;            // one per model.cases(), after the eigenvalue steps
};

// Writes the deck. Throws FemError when the model fails validate_shell_model()
// or the options do not fit it (a case index out of range, no density for
// *FREQUENCY, an inertia no body can have).
CcxDeckMap write_ccx_deck(const ShellModel& model, std::ostream& out, const CcxExportOptions& options = {});
CcxDeckMap write_ccx_deck(const ShellModel& model, const std::string& path, const CcxExportOptions& options = {});

// The index in model.cases() of the case named `name`; a name no case has but
// that is a number ("0", "1", ...) is taken as the index. Throws FemError
// naming the cases when neither matches.
int find_load_case(const ShellModel& model, const std::string& name);

// One MASS element of a rigid body's stand-in.
struct CcxLumpedMass {
  Vec3 position = Vec3::Zero();  // m, world
  double mass = 0;               // kg
};

// Point masses, rigidly tied together, with the mass, centre of mass and
// inertia tensor of `body` exactly: m/6 at c +- a_k q_k on the principal axes
// q_k of the second moment S = tr(J)/2 I - J, a_k = sqrt(3 s_k / m), and the
// mass of axes with s_k = 0 at the centre c = node_position + offset
// (docs/fem.md "Rigid masses in CalculiX"). 1, 3, 5 or 6 (+1) points. Throws
// FemError when J breaks the triangle inequality J_i <= J_j + J_k (S not
// positive semi-definite): no distribution of mass has such an inertia.
std::vector<CcxLumpedMass> lumped_rigid_mass(const PointMass& body, const Vec3& node_position);

// One "displacements (vx,vy,vz)" block of a ccx .dat file.
struct CcxDisplacementBlock {
  std::string set;        // the node set printed, as ccx writes it (upper case)
  double time = 0;        // the step time ccx prints (static step k of unit length: k)
  std::map<int, Vec3> u;  // deck node id -> translation, m
};

// What a ccx .dat holds, in file order.
struct CcxDatResults {
  std::vector<CcxDisplacementBlock> displacements;
  std::vector<double> buckling_factors;  // -, "B U C K L I N G   F A C T O R   O U T P U T", mode order
  std::vector<double> frequencies_hz;    // Hz, "E I G E N V A L U E   O U T P U T", real part in cycles/time
};

// Throws FemError when the file cannot be read.
CcxDatResults read_ccx_dat(const std::string& dat_path);

// The last "displacements (vx,vy,vz)" block of a ccx .dat file: deck node id ->
// translation, m. Throws FemError when the file has no such block.
std::map<int, Vec3> read_ccx_displacements(const std::string& dat_path);

// One static case as ccx solved it.
struct CcxCaseSolution {
  std::string name;                     // the case's name in model.cases()
  std::vector<Vector6d> displacements;  // #N, model nodes; rotations are known only at rigid-link masters (else 0)
  double compliance = 0;                // J, f^T u of this case's loads with the ccx displacements
  bool compliance_complete = true;      // false when a moment acts where ccx reports no rotation
  double load_deflection = 0;           // m, |translation| of model.load_node, else of the loaded node that moves most
};

// Everything one deck asks of ccx.
struct CcxEnvelope {
  std::vector<CcxCaseSolution> cases;    // one per model.cases(), in order
  std::vector<double> buckling_factors;  // -, multiples of the loads of options.buckle_case; empty without *BUCKLE
  std::vector<double> frequencies_hz;    // Hz, ascending; empty without *FREQUENCY
  double wall_seconds = 0;               // s, ccx run time
};

// Writes work_dir/<job>.inp with `options`, runs `ccx -i <job>` there, reads
// <job>.dat. Throws FemError when ccx cannot be run, reports an error, or its
// .dat lacks a case, the buckling factors or the frequencies the deck asks for.
CcxEnvelope solve_envelope_with_ccx(const ShellModel& model, const std::string& work_dir,
                                    const std::string& job = "sheetgen", const std::string& ccx_executable = "ccx",
                                    const CcxExportOptions& options = {});

// The first case of solve_envelope_with_ccx (the one case of a model without
// load_cases), with the run time.
struct CcxSolution {
  std::vector<Vector6d> displacements;  // #N, model nodes; rotations are known only at rigid-link masters (else 0)
  double compliance = 0;                // J, f^T u from the ccx displacements
  bool compliance_complete = true;      // false when a moment acts where ccx reports no rotation
  double load_deflection = 0;           // m, |translation| of model.load_node (as ShellResult)
  double wall_seconds = 0;              // ccx run time
};

CcxSolution solve_with_ccx(const ShellModel& model, const std::string& work_dir, const std::string& job = "sheetgen",
                           const std::string& ccx_executable = "ccx", const CcxExportOptions& options = {});

}  // namespace sheetgen
