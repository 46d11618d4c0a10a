#pragma once
// The bracket FEM model and its linear static solve (docs/architecture.md "FEM",
// docs/fem.md): flat-shell triangles (shell_element.hpp) on one conforming
// mesh, supports, rigid links eliminated master-slave (u = T u_hat), nodal
// loads; outputs compliance, load deflection, fibre von Mises stresses and the
// margin of safety.
//
// Composition solves hundreds of candidates per load, so the solve is a
// stateful ShellSolver that keeps the sparse symbolic factorisation and reuses
// it while the stiffness sparsity pattern repeats; solve_shell() is the
// one-off form.
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sheetgen/core/problem.hpp"
#include "sheetgen/core/triangle_mesh.hpp"
#include "sheetgen/fem/shell_element.hpp"

namespace sheetgen {

using Vector6d = Eigen::Matrix<double, 6, 1>;

enum ShellDof : int { kUx = 0, kUy = 1, kUz = 2, kRx = 3, kRy = 4, kRz = 5 };

// Prescribed zero displacement of some DOFs of one node.
struct NodeSupport {
  int node = -1;
  std::array<bool, 6> fixed{{true, true, true, true, true, true}};  // by ShellDof; default: clamped
};

// A rigid 6-DOF link: every slave follows the master rigidly,
//   u_s = u_m + theta_m x (x_s - x_m),  theta_s = theta_m.
// Used for the rigid load box (master = an extra node at the box centroid,
// slaves = the base-tab nodes under it) and for self-rivets (a master node and
// the node of the other sheet at the same rivet).
struct RigidLink {
  int master = -1;
  std::vector<int> slaves;
};

struct NodalLoad {
  int node = -1;
  Vec3 force = Vec3::Zero();   // N, world frame
  Vec3 moment = Vec3::Zero();  // N m, world frame
};

// One load case: its own nodal loads on the common model. Every case of a
// model is solved on one factorisation (ShellSolver::solve_cases).
struct ShellLoadCase {
  std::string name;
  std::vector<NodalLoad> loads;
};

// A rigid body's inertia lumped at a node (the load box on its master node):
// mass at the centre of mass `node + offset`, inertia tensor about that centre.
// Enters the mass matrix of the frequency analysis only.
struct PointMass {
  int node = -1;
  double mass = 0;                                    // kg, > 0
  Vec3 offset = Vec3::Zero();                         // m, centre of mass - node position (world)
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  // kg m^2, about the centre of mass, world frame
};

struct ShellModel {
  std::vector<Vec3> nodes;                     // #N, m
  std::vector<std::array<int, 3>> triangles;   // #E by 3 node indices; the vertex order sets the "top" side
  Material material;                           // E, nu, thickness, Fty are used
  std::vector<NodeSupport> supports;
  std::vector<RigidLink> rigid_links;
  std::vector<NodalLoad> loads;                // the single case of solve()
  // The load cases of solve_cases() and of the CalculiX deck's static steps;
  // empty: `loads` is the one case, named "design" (see cases()).
  std::vector<ShellLoadCase> load_cases;
  std::vector<PointMass> point_masses;         // rigid masses of the frequency analysis
  // The node whose translation is reported as the load deflection (the load
  // box master); -1: the loaded node with the largest translation.
  int load_node = -1;

  int add_node(const Vec3& p);  // returns its index
  void clamp(int node);         // all six DOFs fixed
  void add_load(int node, const Vec3& force, const Vec3& moment = Vec3::Zero());
  // Lumps a uniform traction (Pa = N/m^2, world frame) over the given elements
  // (all when empty) to their nodes, a third of each element's share per node.
  // Exact for the resultant; the consistent and lumped vectors differ only in
  // rotations, which DKT/OPT do not load under a constant traction.
  // load_cases, or `loads` as one case named "design" when there are none.
  std::vector<ShellLoadCase> cases() const;
  void add_surface_traction(const Vec3& traction, const std::vector<int>& elements = {});
};

// Both are kept because which is faster depends on the BLAS: with Debian's
// reference BLAS (this project's machines) Eigen's simplicial LDL^T beats
// CHOLMOD's BLAS-bound supernodal LL^T at 5k-20k DOF (docs/fem.md
// "Benchmarks"). With OpenBLAS CHOLMOD factors faster, but the composition on
// it was not reproducible from run to run, while on the reference BLAS both
// backends give the same part (docs/fem.md "Benchmarks").
enum class ShellSolverBackend {
  kEigenSimplicialLdlt,  // default
  kCholmodSupernodal,
};

struct ShellSolveOptions {
  ShellElementOptions element;
  ShellSolverBackend backend = ShellSolverBackend::kEigenSimplicialLdlt;
  double safety_factor = 1.5;  // -, SF in MS = Fty / (SF sigma_max) - 1 (docs/architecture.md "Units and defaults")
  // Stress rule: an element is left out of the maximum when its centroid is
  // closer than (stress_exclusion_thicknesses * t + h_p) to a singular point p
  // (a node with a support, a node of a rigid link, or a re-entrant corner of
  // the outline), where h_p is the longest edge of the elements at p. The
  // radius tends to 2 t under refinement, so the maximum over the rest
  // converges (docs/fem.md).
  double stress_exclusion_thicknesses = 2.0;
  // A boundary node is a re-entrant corner when the angles of its triangles
  // add up to more than this (rad; 190 deg): the end of a fold inside its
  // parent's edge (~270 deg) or a notch in one plane. Straight boundaries
  // (180 deg, with round-off) and the ends of a fold over a whole edge
  // (90 + 90 deg) are not.
  double reentrant_corner_angle = 190.0 * M_PI / 180.0;
  // m. At a re-entrant corner the radius is (stress_exclusion_thicknesses * t
  // + max(h_p, this)): a sheet part's fold ends inside an edge have the bend
  // (inside radius R) and a bend relief there, which the sharp-fold model
  // does not have, so its field within about R of that corner is not the
  // part's. analyse_part() sets it to the bend radius; 0 keeps h_p alone.
  // It also keeps the rule from following the graded mesh at fold ends
  // (docs/fem.md "Graded fold ends").
  double reentrant_corner_clearance = 0;
  // A pivot smaller than this fraction of its diagonal entry means the model
  // is a mechanism (a rigid-body mode no support holds).
  double singular_pivot_ratio = 1e-9;
};

struct ShellResult {
  std::string case_name;                 // the load case ("design" for solve())
  std::vector<Vector6d> displacements;   // #N, (ux, uy, uz m; rx, ry, rz rad), world frame
  double compliance = 0;                 // J, f^T u
  double load_deflection = 0;            // m, |translation| of the load node
  // m, the load node's translation along the case's resultant force, u . F/|F|
  // (0 when the case has only moments).
  double deflection_along_load = 0;
  int load_node = -1;                    // the node used for load_deflection
  std::vector<double> von_mises_top;     // #E, Pa, centroid, z = +t/2
  std::vector<double> von_mises_bottom;  // #E, Pa, centroid, z = -t/2
  std::vector<bool> stress_excluded;     // #E, true where the stress rule leaves the element out
  std::vector<int> reentrant_corners;    // boundary nodes the rule treats as singular (re-entrant corners)
  double max_von_mises = 0;              // Pa, max over the elements the rule keeps
  int max_von_mises_element = -1;
  bool stress_rule_fell_back = false;    // every element was excluded; the max is over all of them
  double margin_of_safety = 0;           // -, Fty / (SF max_von_mises) - 1 (+inf when unstressed)
  int reduced_dofs = 0;                  // unknowns after supports and rigid links
  bool pattern_reused = false;           // the symbolic factorisation was reused
  double assemble_seconds = 0, factor_seconds = 0, solve_seconds = 0, stress_seconds = 0;
};

// Keeps the symbolic factorisation between solves. Not thread-safe: use one
// solver per thread.
class ShellSolver {
 public:
  ShellSolver();
  ~ShellSolver();
  ShellSolver(ShellSolver&&) noexcept;
  ShellSolver& operator=(ShellSolver&&) noexcept;

  // Throws FemError on bad input or a singular (mechanism) model.
  ShellResult solve(const ShellModel& model, const ShellSolveOptions& options = {});
  // Every case of model.cases() on one factorisation (one result per case, in
  // order). Same errors, and a case without any load is one.
  std::vector<ShellResult> solve_cases(const ShellModel& model, const ShellSolveOptions& options = {});

  // The state the fem area's eigen analyses share with the static solve
  // (buckling.hpp, vibration.hpp); opaque elsewhere.
  struct Impl;
  Impl& state() { return *impl_; }

  int symbolic_analyses() const;  // how many times the pattern was analysed

 private:
  std::unique_ptr<Impl> impl_;
};

// One-off solves (analyse the pattern every time).
ShellResult solve_shell(const ShellModel& model, const ShellSolveOptions& options = {});
std::vector<ShellResult> solve_shell_cases(const ShellModel& model, const ShellSolveOptions& options = {});

// Checks the model without solving; throws FemError naming the first problem.
void validate_shell_model(const ShellModel& model);

}  // namespace sheetgen
