#include "sheetgen/pipeline/part_drawing.hpp"

#include <cmath>
#include <filesystem>
#include <limits>

#include "sheetgen/core/input_error.hpp"
#include "sheetgen/core/sheet_gauges.hpp"

namespace sheetgen {
namespace {

using nlohmann::json;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

[[noreturn]] void bad(const std::string& field, const std::string& what) { throw InputError("result.json", field, what); }

// A required field of `j` (an object), named in errors as prefix.key.
const json& need(const json& j, const std::string& key, const std::string& prefix) {
  if (!j.is_object() || !j.contains(key) || j.at(key).is_null()) bad(prefix + "." + key, "is missing");
  return j.at(key);
}

double number(const json& j, const std::string& key, const std::string& prefix) {
  const json& v = need(j, key, prefix);
  if (!v.is_number()) bad(prefix + "." + key, "is not a number");
  return v.get<double>();
}

// A number that may be null or absent: NaN then.
double number_or_nan(const json& j, const std::string& key) {
  return j.is_object() && j.contains(key) && j.at(key).is_number() ? j.at(key).get<double>() : kNaN;
}

SheetPoint point2(const json& v, const std::string& field) {
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number()) bad(field, "is not an [x, y] pair");
  return {v[0].get<double>(), v[1].get<double>()};
}

SheetPoint3 point3(const json& v, const std::string& field) {
  if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
    bad(field, "is not an [x, y, z] triple");
  return {v[0].get<double>(), v[1].get<double>(), v[2].get<double>()};
}

SheetMaterial material(const Material& m) {
  const Material d;  // the project's default sheet (docs/architecture.md "Units and defaults")
  SheetMaterial s;
  const bool is_default = m.youngs_modulus == d.youngs_modulus && m.poisson_ratio == d.poisson_ratio &&
                          m.density == d.density && m.yield_strength == d.yield_strength &&
                          m.ultimate_strength == d.ultimate_strength;
  s.name = is_default ? "Al 2024-T3 sheet" : "";
  s.thickness = m.thickness;
  s.density = m.density;
  s.youngs_modulus = m.youngs_modulus;
  s.yield_strength = m.yield_strength;
  s.ultimate_strength = m.ultimate_strength;
  return s;
}

void read_bends(const json& flat, DrawingSheetPart& d) {
  const json& bends = need(flat, "bends", "flat_pattern");
  for (size_t i = 0; i < bends.size(); ++i) {
    const std::string f = "flat_pattern.bends[" + std::to_string(i) + "]";
    const json& b = bends[i];
    SheetBend s;
    s.number = static_cast<int>(number(b, "number", f));
    s.tab = static_cast<int>(number(b, "tab", f));
    s.a = point2(need(b, "a", f), f + ".a");
    s.b = point2(need(b, "b", f), f + ".b");
    s.angle = std::abs(number(b, "angle", f));
    s.up = need(b, "direction", f) == "up";
    s.inside_radius = number(b, "inside_radius", f);
    s.length = number(b, "length", f);
    s.allowance = number(b, "allowance", f);
    d.bends.push_back(s);
  }
}

void read_holes(const json& flat, DrawingSheetPart& d) {
  if (!flat.contains("holes")) return;  // a result written before the holes were
  const json& holes = flat.at("holes");
  for (size_t i = 0; i < holes.size(); ++i) {
    const std::string f = "flat_pattern.holes[" + std::to_string(i) + "]";
    SheetHole h;
    h.label = need(holes[i], "label", f).get<std::string>();
    h.self_rivet = need(holes[i], "kind", f) == "self";
    h.tab = static_cast<int>(number(holes[i], "tab", f));
    h.other_tab = static_cast<int>(number(holes[i], "other_tab", f));
    h.centre = point2(need(holes[i], "centre", f), f + ".centre");
    h.diameter = number(holes[i], "diameter", f);
    h.after_bend = static_cast<int>(number(holes[i], "after_bend", f));
    d.holes.push_back(h);
  }
}

void read_geometry(const json& e, DrawingSheetPart& d) {
  const json& flat = need(e, "flat_pattern", "part");
  const json& loops = need(flat, "outline", "flat_pattern");
  if (!loops.is_array() || loops.empty() || !loops[0].is_array()) bad("flat_pattern.outline", "has no contour");
  for (size_t i = 0; i < loops[0].size(); ++i)
    d.outline.push_back(point2(loops[0][i], "flat_pattern.outline[0][" + std::to_string(i) + "]"));
  read_bends(flat, d);
  read_holes(flat, d);
  const json& tabs = need(e, "tabs", "part");
  for (size_t i = 0; i < tabs.size(); ++i) {
    const std::string f = "tabs[" + std::to_string(i) + "].corners";
    std::vector<SheetPoint3> poly;
    for (const json& c : need(tabs[i], "corners", "tabs[" + std::to_string(i) + "]")) poly.push_back(point3(c, f));
    d.tabs.push_back(poly);
  }
}

// The case of an envelope named by governing.<check>, or null.
const json* governing_case(const json& env, const std::string& check) {
  if (!env.contains("governing") || !env["governing"].contains(check) || !env["governing"][check].is_string())
    return nullptr;
  for (const json& c : env.at("cases"))
    if (c.value("name", "") == env["governing"][check].get<std::string>()) return &c;
  return nullptr;
}

void read_eigen_checks(const json& env, SheetChecks& c) {
  c.eigen_checked = env.value("eigen_checked", false);
  if (c.eigen_checked) {
    const double b = number_or_nan(env, "buckling_factor");
    c.buckling_factor = std::isnan(b) ? std::numeric_limits<double>::infinity() : b;  // null: nothing compresses
    if (const json* g = governing_case(env, "buckling")) c.buckling_case = g->value("name", "");
  }
  if (env.contains("frequencies_hz") && !env["frequencies_hz"].empty() && env["frequencies_hz"][0].is_number())
    c.frequency_hz = env["frequencies_hz"][0].get<double>();
  if (env.contains("required") && env["required"].value("checked", false)) {
    c.min_buckling_factor = number_or_nan(env["required"], "min_buckling_factor");
    c.min_frequency_hz = number_or_nan(env["required"], "min_frequency_hz");
  }
}

// The governing checks: from the envelope when the entry has one, else the
// part's own compliance and MS (a result written before load cases).
SheetChecks checks(const json& e, const Problem& problem) {
  SheetChecks c;
  c.compliance = number_or_nan(e, "compliance");
  c.compliance_limit = number_or_nan(e, "compliance_limit");
  c.margin_of_safety = number_or_nan(e, "margin_of_safety");
  c.min_margin_of_safety = problem.requirements.min_margin_of_safety;
  c.safety_factor = problem.requirements.safety_factor;
  if (!e.contains("envelope") || !e["envelope"].is_object()) return c;
  const json& env = e["envelope"];
  if (const json* s = governing_case(env, "stiffness")) {
    c.stiffness_case = s->value("name", "");
    c.compliance = number_or_nan(*s, "compliance");
    c.compliance_limit = number_or_nan(*s, "compliance_limit");
  }
  if (const json* s = governing_case(env, "strength")) {
    c.strength_case = s->value("name", "");
    c.margin_of_safety = number_or_nan(*s, "margin_of_safety");
  }
  read_eigen_checks(env, c);
  return c;
}

}  // namespace

std::string problem_label(const std::string& source) {
  const std::filesystem::path p = std::filesystem::u8path(source);
  if (p.extension() != ".json") return source;
  const std::filesystem::path folder = p.parent_path().filename();
  return folder.empty() ? p.filename().u8string() : (folder / p.filename()).u8string();
}

DrawingSheetPart drawing_sheet_part(const json& e, const Problem& scene) {
  try {
    // The sheet the part is made of: a thicker gauge when the problem's gave none (docs/pipeline.md).
    std::optional<Problem> thicker;
    const Problem& problem =
        problem_at_sheet(scene, e.contains("thickness_m") ? number(e, "thickness_m", "part") : 0.0, thicker);
    DrawingSheetPart d;
    d.part_name = need(e, "load", "part").get<std::string>();
    d.problem_name = problem_label(problem.source);
    d.status = e.value("status", "") == "ok" ? "valid part: every check met" : "NOT VALID: " + e.value("reason", "");
    read_geometry(e, d);
    d.material = material(problem.material);
    d.flat_area = number(e, "area_m2", "part");
    d.mass = number(e, "mass_kg", "part");
    d.k_factor = problem.manufacturing.k_factor;
    d.kerf = problem.manufacturing.kerf;
    d.rivet_diameter = problem.manufacturing.rivet_diameter;
    d.checks = checks(e, problem);
    return d;
  } catch (const json::exception& x) {  // a field of the wrong type
    bad("parts[" + e.value("load", std::string("?")) + "]", x.what());
  }
}

const json& drawable_part_entry(const json& doc, const std::string& load) {
  std::string names;
  if (doc.is_object() && doc.contains("parts") && doc["parts"].is_array())
    for (const json& p : doc["parts"]) {
      const std::string name = p.value("load", "");
      if (name == load) {
        if (p.value("status", "") != "ok")
          bad("parts[" + load + "]", "load '" + load + "' has no valid part, so it has no drawing (" +
                                         p.value("reason", std::string("no reason given")) + ")");
        return p;
      }
      names += (names.empty() ? "" : ", ") + name;
    }
  bad("parts", "there is no load '" + load + "' (loads: " + (names.empty() ? "none" : names) + ")");
}

DrawingSheetLayout write_part_drawing(const json& part_entry, const Problem& problem, const std::string& path,
                                      const DrawingSheetOptions& options) {
  return write_drawing_pdf(drawing_sheet_part(part_entry, problem), options, path);
}

DrawingSheetLayout write_load_drawing(const std::string& text, const std::string& load, const Problem& problem,
                                      const std::string& path, const DrawingSheetOptions& options) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& x) {
    bad("byte " + std::to_string(x.byte), "is not valid JSON");
  }
  return write_part_drawing(drawable_part_entry(doc, load), problem, path, options);
}

}  // namespace sheetgen
