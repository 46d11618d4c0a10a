#pragma once
// The one exception type of the FEM area. A model that cannot be solved (no
// support, a mechanism, a patch connected to nothing, a bad number) throws it
// with one sentence naming the cause, so composition can reject the candidate
// and the CLI can print it. The FEM never returns NaN in place of an error.
#include <stdexcept>
#include <string>

namespace sheetgen {

class FemError : public std::runtime_error {
 public:
  // field: what is wrong, e.g. "material.thickness" or "node 17";
  // problem: why, e.g. "must be > 0 (got -1e-3 m)".
  FemError(const std::string& field, const std::string& problem)
      : std::runtime_error("FEM model: " + field + ": " + problem), field_(field), problem_(problem) {}

  const std::string& field() const { return field_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string field_, problem_;
};

}  // namespace sheetgen
