#pragma once
// The environments a problem's loads are searched in, one load after another
// (docs/pipeline.md "Environments"): the scene's fields are built once and
// each load's environment adds the parts made for the loads before it. A
// thicker gauge's environment is built beside it for the load that needs one.
#include <memory>
#include <vector>

#include "sheetgen/core/problem.hpp"
#include "sheetgen/env/environment.hpp"

namespace sheetgen {

struct GenerateProgress;

class LoadEnvironments {
 public:
  // `problem` (kept by reference, it must outlive this) is the problem's own
  // sheet; `progress` (optional) carries the cancel flag to every build.
  LoadEnvironments(const Problem& problem, GenerateProgress* progress);

  // The next load's environment: the current one with the parts made since
  // it was built (one small field each). nullptr when the build was cancelled.
  const Environment* next();
  // The current load's environment at the problem's sheet, built again (the
  // scene's fields, then each batch of parts as next() added them) when
  // release() dropped it. nullptr when the build was cancelled.
  const Environment* current();
  // Drops the current environment until current() or next() needs it again.
  // Its fields are the largest block of a solve's memory (docs/benchmarks.md
  // "Peak memory"): a load searched at a thicker gauge releases it before that
  // sheet's environment is built, so the two never live at once.
  void release();
  // The current load's environment built for another sheet of the problem (a
  // thicker gauge): the scene's fields at that sheet's voxel and band, then the
  // earlier parts added as next() added them, so a load searched at a gauge sees
  // what a problem written at that thickness would show it (docs/pipeline.md
  // "Thicker gauges"). nullptr when the build was cancelled.
  std::unique_ptr<Environment> at_sheet(const Problem& sheet) const;
  // A finished part: an obstacle from the next load on.
  void add_part(EnvironmentMesh part);

 private:
  EnvironmentOptions options() const;

  const Problem& problem_;
  GenerateProgress* progress_;
  std::vector<EnvironmentMesh> new_parts_;               // made since `env_` was built
  std::vector<std::vector<EnvironmentMesh>> additions_;  // the parts added so far, one batch per next()
  std::unique_ptr<Environment> env_;                     // null before the first load and after release()
};

}  // namespace sheetgen
