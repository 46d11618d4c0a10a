#include "sheetgen/discovery/bendable.hpp"

#include "sheetgen/part/manufacturing_plan.hpp"

namespace sheetgen {

BendableResult segment_bendable(const Problem& problem, const Part& base, const SegmentLibrary& library,
                                const Segment& segment) {
  BendableResult r;
  if (!problem.manufacturing.press_brake_required) return r;
  const Part part = assemble_with(base, library, segment);
  const SheetSpec spec = SheetSpec::from(problem);
  ManufacturingPlan plan = plan_manufacturing(part, spec);
  if (!plan.ok()) {
    // Flat overlap and the bend sequence's self-collisions only get worse
    // with more tabs, like the press brake's.
    r.ok = false;
    r.message = plan.message;
    return r;
  }
  plan_press_brake(plan, part, spec, problem.manufacturing.press_brake_tools, {}, kSearchPressBrakeSweeps);
  if (!plan.press.ok) {
    r.ok = false;
    r.message = plan.press.message;
  }
  return r;
}

}  // namespace sheetgen
