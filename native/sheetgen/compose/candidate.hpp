#pragma once
// One candidate of the composition (paper Sec. 5.1, docs/architecture.md
// "Composition"): a subset of the segment library, closed under parents,
// assembled into a part, checked (validity against the environment, flat
// pattern, bend sequence), scored by its cost (core/cost_model.hpp: sheet,
// bends, rivets, in m^2 of sheet) and analysed by the shell FEM.
#include <limits>
#include <string>
#include <vector>

#include "sheetgen/compose/analysis_cache.hpp"
#include "sheetgen/core/problem.hpp"
#include "sheetgen/discovery/segment_library.hpp"
#include "sheetgen/part/part.hpp"
#include "sheetgen/part/validity.hpp"
#include "sheetgen/structure/part_model.hpp"

namespace sheetgen {

class Environment;

// One evaluated subset.
struct Candidate {
  std::vector<int> segments;       // sorted ids, closed under parents
  Part part;
  bool geometry_ok = false;        // assembled part valid (tabs, clearance, self, flat, bends)
  ValidityReason reason = ValidityReason::Ok;
  std::string message;             // why not, when not
  bool analysed = false;
  StructuralResult fem;            // when analysed
  std::string fem_error;           // the FEM's sentence when it could not solve
  double area = 0;                 // m^2, flat-pattern material
  int bends = 0;
  int rivets = 0;                  // flange rivets (as the FEM lays them out) and self-rivets
  double cost = 0;                 // m^2, the composition's score: search_score() (core/cost_model.hpp)
  std::vector<SelfRivetTie> self_rivets;  // gusset rivets (paper Sec. 5.2), tied in the FEM
  bool over_cost_bound = false;    // geometry ok, but not analysed: dearer than the valid parts kept
  bool screened_out = false;       // analysed on the screening mesh only, not among the best there (fem is that result)
  bool valid() const { return geometry_ok && analysed && fem.passes(); }
};

// The default FEM element size of a part (m): fem's default_element_size of
// its realised tabs at sheet thickness `thickness` (m). The composition's
// search and screening meshes and sizing's trials are multiples of it.
double part_default_element_size(const Part& part, double thickness);

// Evaluates one subset (exposed for tests): assembly, validity, flat pattern,
// bend sequence, FEM. element_size <= 0: the default mesh. With a cache, an
// analysis the load's searches have already made is taken from it.
Candidate evaluate_candidate(const Problem& problem, const Environment& env, int load_index, const Part& base,
                             const SegmentLibrary& library, std::vector<int> segments, double element_size,
                             ShellSolver* solver = nullptr,
                             double cost_bound = std::numeric_limits<double>::infinity(),
                             AnalysisCache* cache = nullptr);

// The FEM of a candidate whose geometry passed: sets analysed and fem, or
// fem_error when the model cannot be solved. element_size <= 0: the default mesh.
void analyse_candidate(const Problem& problem, int load_index, Candidate& candidate, double element_size,
                       ShellSolver* solver = nullptr, AnalysisCache* cache = nullptr);

// Re-evaluates a candidate's own part (with its self-rivets), e.g. at the
// default mesh for the final check. A part whose cost (m^2) is at least
// cost_bound is checked but not analysed (over_cost_bound).
Candidate evaluate_part(const Problem& problem, const Environment& env, int load_index, Candidate candidate,
                        double element_size, ShellSolver* solver = nullptr,
                        double cost_bound = std::numeric_limits<double>::infinity(),
                        AnalysisCache* cache = nullptr);

}  // namespace sheetgen
