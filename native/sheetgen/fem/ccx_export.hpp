#pragma once
// CalculiX (ccx 2.20) input deck of a ShellModel, the reader of its .dat
// displacements, and a runner - for engineers who verify elsewhere
// (`sheetgen export-ccx`) and for the validation tests (docs/fem.md "CalculiX").
//
// CalculiX's S3 locks (-21 % on the cantilever strip, docs/platform.md), so each
// triangle becomes three quadrilaterals (corner, edge midpoint, centroid, edge
// midpoint); midpoints are shared by the two triangles of an edge, so the quad
// mesh is conforming. Elements are S4 (full integration, incompatible modes).
// Rigid links become *RIGID BODY with a REF NODE (translations) and a ROT NODE
// (whose "translations" are the rotations); loads become *CLOAD, supports
// *BOUNDARY. Units are the model's: m, N, Pa.
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include "sheetgen/fem/shell_model.hpp"

namespace sheetgen {

struct CcxExportOptions {
  std::string heading = "sheetgen flat-shell model";
  // "S4", "S4R" or "S8R"; triangles are split into 3 quads either way. S8R
  // (quadratic, a mid-side node per quad edge) is the reference for our
  // element's accuracy: S4 on split triangles converges slowly from below
  // (docs/fem.md "Transverse shear").
  std::string element_type = "S4";
};

// Where the model's entities went in the deck (CalculiX ids are 1-based).
struct CcxDeckMap {
  std::vector<int> node_id;   // #N model nodes -> deck node id (-1: not written, unused by elements and links)
  std::vector<int> ref_node;  // per rigid link: its REF NODE id (translations of the master)
  std::vector<int> rot_node;  // per rigid link: its ROT NODE id (rotations of the master)
  int node_count = 0;         // deck nodes
  int element_count = 0;      // deck quads (3 per triangle)
};

// Writes the deck. Throws FemError when the model fails validate_shell_model().
CcxDeckMap write_ccx_deck(const ShellModel& model, std::ostream& out, const CcxExportOptions& options = {});
CcxDeckMap write_ccx_deck(const ShellModel& model, const std::string& path, const CcxExportOptions& options = {});

// The last "displacements (vx,vy,vz)" block of a ccx .dat file: deck node id ->
// translation, m. Throws FemError when the file has no such block.
std::map<int, Vec3> read_ccx_displacements(const std::string& dat_path);

struct CcxSolution {
  std::vector<Vector6d> displacements;  // #N, model nodes; rotations are known only at rigid-link masters (else 0)
  double compliance = 0;                // J, f^T u from the ccx displacements
  bool compliance_complete = true;      // false when a moment acts where ccx reports no rotation
  double load_deflection = 0;           // m, |translation| of model.load_node (as ShellResult)
  double wall_seconds = 0;              // ccx run time
};

// Writes work_dir/<job>.inp, runs `ccx -i <job>` there, reads <job>.dat.
// Throws FemError when ccx cannot be run or reports an error.
CcxSolution solve_with_ccx(const ShellModel& model, const std::string& work_dir, const std::string& job = "sheetgen",
                           const std::string& ccx_executable = "ccx", const CcxExportOptions& options = {});

}  // namespace sheetgen
