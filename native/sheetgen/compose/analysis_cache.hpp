#pragma once
// The FEM analyses of one load, kept for the load's later searches
// (docs/pipeline.md "Analyses shared between passes"). The web pass, the seed
// retries, their pooled compositions, the right-angle pass and the press-brake
// fallback's round search the same load again, and many of their candidates
// are parts an earlier search has already analysed: a pooled composition
// starts from the segments of the searches before it. An analysis is a pure
// function of the part, its self-rivets, the mesh size and the problem's
// FEM inputs, so the earlier result is the one a new analysis would give, to
// the last bit. Thread-safe: the composition's workers share one cache.
#include <cstddef>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_map>

#include "sheetgen/core/problem.hpp"
#include "sheetgen/structure/part_model.hpp"

namespace sheetgen {

struct Candidate;

class AnalysisCache {
 public:
  // What analyse_candidate() sets: the result, or the FEM's sentence when the
  // model could not be solved (the result is then not kept: a failed analysis
  // leaves the candidate's own earlier one in place).
  struct Analysis {
    bool analysed = false;
    StructuralResult fem;
    std::string fem_error;
  };

  // The exact bytes of every input of the candidate's analysis: the load
  // (its box, force, mass and cases), the material, the requirements, the
  // thickness-scaled FEM inputs (bend radius, rivet size and spacing), the
  // mesh size, the part (base, every tab's parent, edge, parameters, rivet
  // area and self-rivet partner; not the callers' tags) and the self-rivet
  // ties. Two keys are equal only when those inputs are equal bit for bit, so
  // one cache may serve any problems; generate() keeps one per load.
  static std::string key(const Problem& problem, int load_index, const Candidate& candidate, double element_size);

  std::optional<Analysis> find(const std::string& key) const;
  void insert(const std::string& key, const Analysis& analysis);

  int hits() const;      // find() calls that returned an analysis
  std::size_t size() const;

 private:
  mutable std::mutex mutex_;
  std::unordered_map<std::string, Analysis> analyses_;
  mutable int hits_ = 0;
};

}  // namespace sheetgen
