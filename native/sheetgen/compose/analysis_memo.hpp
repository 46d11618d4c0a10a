#pragma once
// The FEM answers of one load's searches, kept so that no part is analysed
// twice (docs/pipeline.md "Analysis memo"). The passes of a load (plain, web
// roots, flat extensions, seed retries, and all of them again without the
// press-brake check) meet many of the same parts: a pass without the press
// check composes the same library as the pass with it, and every final check
// re-analyses the parts the previous one rejected. analyse_part() is a
// function of the problem's load, material and requirements (fixed for one
// load) and of the plate geometry and model options, which form the key, so a
// kept answer is the answer the analysis would give again, bit for bit.
#include <cstddef>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_map>

#include "sheetgen/structure/part_model.hpp"

namespace sheetgen {

// What one analysis gave: its result, or the FEM's sentence when it could not solve.
struct MemoEntry {
  StructuralResult fem;
  std::string fem_error;  // empty: fem holds the answer
};

struct MemoStats {
  size_t hits = 0, misses = 0;
};

// Thread-safe; one per load of a problem. Parts of another load, material or
// set of requirements must not share it.
class AnalysisMemo {
 public:
  // The bytes of everything analyse_part() reads that differs between parts
  // of one load: the plates (corners, rivet areas and edges, parents, bend
  // angles), the element size, the self-rivet ties, the element options and
  // whether the eigen checks run.
  static std::string key_of(const PlateGeometry& geometry, const PartModelOptions& options);

  // The kept answer for `key`, counting a hit or a miss.
  std::optional<MemoEntry> find(const std::string& key);
  void insert(const std::string& key, MemoEntry entry);
  MemoStats stats() const;

 private:
  mutable std::mutex mutex_;
  std::unordered_map<std::string, MemoEntry> entries_;
  MemoStats stats_;
};

}  // namespace sheetgen
