#include "sheetgen/part/manufacturing_plan.hpp"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

namespace sheetgen {

ManufacturingPlan plan_manufacturing(const Part& part, const SheetSpec& spec, const ManufacturingPlanOptions& o) {
  ManufacturingPlan plan;
  plan.flat = unfold(part, spec, o.flat);
  plan.flat_report = check_flat_pattern(plan.flat, spec, o.validity);
  if (!plan.flat_report.valid()) {
    plan.status = plan.flat_report.first_reason();
    plan.message = plan.flat_report.summary();
    if (!o.plan_bends_when_flat_fails) return plan;
  }
  plan.sequence = plan_bend_sequence(part, spec, o.bends);
  if (!plan.sequence.ok() && plan.ok()) {
    plan.status = plan.sequence.status;
    plan.message = plan.sequence.message;
  }
  if (o.press_brake && plan.sequence.ok()) plan_press_brake(plan, part, spec, o.press_brake_tools, o.bends, o.press_brake_sweeps);
  return plan;
}

void plan_press_brake(ManufacturingPlan& plan, const Part& part, const SheetSpec& spec,
                      const PressBrakeTooling& tooling, const BendSequenceOptions& bends, int sweeps) {
  plan.tools = make_tool_set(tooling, spec.thickness);
  plan.press_checked = true;
  // The press-aware search walks the orders in the part-only search's order,
  // so when every bend of the part-only order can be made it would return
  // that same order: checking it first gives the same answer for one order's cost.
  plan.press = check_press_brake(part, plan.sequence.order, spec, plan.tools);
  if (plan.press.ok) return;
  BendSequenceOptions with_tools = bends;
  with_tools.tools = &plan.tools;
  with_tools.max_sweeps = std::min(bends.max_sweeps, sweeps);
  BendSequenceResult pressed = plan_bend_sequence(part, spec, with_tools);
  // No order found: plan.press keeps the part-only order's first failure, a
  // named bend and why, which the order the drawings show does have.
  if (!pressed.ok()) return;
  plan.press.ok = true;
  plan.press.tooling = pressed.tooling;
  plan.press.failed_tab = -1;
  plan.press.message.clear();
  plan.sequence = std::move(pressed);
}

void set_rivet_holes(ManufacturingPlan& plan, const RealisedPart& realised, const std::vector<PlacedRivet>& flange_rivets,
                     const std::vector<PlacedSelfRivet>& self_rivets, const RivetHoleOptions& options) {
  // Numbered as the drawings number the bends (write_manufacturing_files).
  const std::vector<int> order = plan.sequence.ok() ? plan.sequence.order : std::vector<int>{};
  plan.holes = rivet_holes(plan.flat, realised, flange_rivets, self_rivets, order, options);
}

std::vector<BendToolRow> bend_tool_rows(const ManufacturingPlan& plan) {
  std::vector<BendToolRow> rows;
  if (!plan.press_checked) return rows;
  for (const BendTooling& b : plan.press.tooling)
    rows.push_back({b.tab, plan.tools.punches[b.punch].name, plan.tools.dies[b.die].name, b.flipped});
  return rows;
}

void write_manufacturing_files(const std::string& dir, const RealisedPart& realised, const ManufacturingPlan& plan,
                               const DrawingOptions& drawing) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error("cannot create directory " + dir + ": " + ec.message());
  DrawingOptions d = drawing;
  if (d.bend_order.empty() && plan.sequence.ok()) d.bend_order = plan.sequence.order;
  const std::filesystem::path p(dir);
  write_text_file((p / "flat.dxf").string(), flat_pattern_dxf(plan.flat, d, plan.holes));
  write_text_file((p / "flat.svg").string(), flat_pattern_svg(plan.flat, d, plan.holes));
  write_text_file((p / "bends.csv").string(), bend_table_csv(plan.flat, d.bend_order, bend_tool_rows(plan)));
  write_text_file((p / "rivets.csv").string(), rivet_table_csv(plan.flat, plan.holes));
  write_text_file((p / "part.obj").string(), part_obj(realised));
}

}  // namespace sheetgen
