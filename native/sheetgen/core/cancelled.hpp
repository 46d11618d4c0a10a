#pragma once
// Thrown by long builds (distance grids) when the caller's cancel flag is set;
// the pipeline turns it into a cancelled result, never an error.
#include <stdexcept>

namespace sheetgen {

struct Cancelled : std::runtime_error {
  Cancelled() : std::runtime_error("cancelled") {}
};

}  // namespace sheetgen
