// sheetgen command line: batch runs without Blender (docs/architecture.md "Interfaces").
#include <CLI/CLI.hpp>
#include <Eigen/Eigenvalues>

#include <chrono>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>

#include "sheetgen/core/input_error.hpp"
#include "sheetgen/core/malloc_settings.hpp"
#include "sheetgen/core/problem.hpp"
#include "sheetgen/core/sheet_gauges.hpp"
#include "sheetgen/env/environment.hpp"
#include "sheetgen/fem/ccx_export.hpp"
#include "sheetgen/fem/fem_error.hpp"
#include "sheetgen/pipeline/generate.hpp"
#include "sheetgen/pipeline/output_files.hpp"
#include "sheetgen/structure/envelope_analysis.hpp"
#include "sheetgen/structure/part_model.hpp"

#include <atomic>
#include <optional>
#include <csignal>
#include <filesystem>
#include <thread>
#include <unistd.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace {

using sheetgen::Vec3;

std::string fmt_vec(const Vec3& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "[%.4g, %.4g, %.4g]", v.x(), v.y(), v.z());
  return buf;
}

// A load's mass properties and, unless it is today's single "design" case, every case.
void print_mass_and_cases(const sheetgen::Load& l) {
  if (l.mass) {
    const Eigen::Vector3d principal = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(l.inertia, Eigen::EigenvaluesOnly).eigenvalues();
    std::printf("  %-20s mass %.4g kg  centre of mass %s m  principal inertia %s kg*m^2\n", "", *l.mass,
                fmt_vec(l.center_of_mass).c_str(), fmt_vec(principal).c_str());
  }
  if (l.cases.size() == 1 && l.cases[0].name == "design") return;
  for (const auto& c : l.cases) {
    char limit[48] = "";
    if (c.max_deflection) std::snprintf(limit, sizeof limit, "  max deflection %.4g mm", *c.max_deflection * 1e3);
    std::printf("  %-20s case %-16s force %s N (|F| %.4g N)  moment %s N*m%s\n", "", c.name.c_str(), fmt_vec(c.force).c_str(),
                c.force.norm(), fmt_vec(c.moment).c_str(), limit);
  }
}

// The inertia envelope (problem-level load_cases) and the buckling and frequency floors.
void print_envelope_and_requirements(const sheetgen::Problem& p) {
  if (const auto& e = p.load_cases) {
    std::printf("load cases: %s%zu factors on every load with a mass; forward %s  left %s  up %s\n",
                e->preset.empty() ? "" : (e->preset + ", ").c_str(), e->factors.size(), fmt_vec(e->forward).c_str(),
                fmt_vec(e->left()).c_str(), fmt_vec(e->up).c_str());
  }
  const auto& r = p.requirements;
  char freq[48] = "none";
  if (r.min_frequency_hz) std::snprintf(freq, sizeof freq, "%.4g Hz", *r.min_frequency_hz);
  // An old one-force file is not checked for buckling or frequency
  // (Requirements::eigen_checks); printing a floor for it would mislead.
  if (r.eigen_checks)
    std::printf("requirements: safety factor %.4g, min MS %.4g, min buckling factor %.4g, min frequency %s\n", r.safety_factor,
                r.min_margin_of_safety, r.min_buckling_factor, freq);
  else
    std::printf("requirements: safety factor %.4g, min MS %.4g; buckling and frequency not checked (one force per load, "
                "no floor named)\n", r.safety_factor, r.min_margin_of_safety);
}

void print_summary(const sheetgen::Problem& p) {
  std::printf("problem %s\n", p.source.c_str());
  std::printf("meshes: %zu (%d triangles)\n", p.meshes.size(), p.triangle_count());
  for (const auto& m : p.meshes)
    std::printf("  %-20s %8zu triangles %8zu vertices  %s%s\n", m.name.c_str(), m.mesh.triangles.size(), m.mesh.vertices.size(),
                m.source.c_str(), m.mesh.is_closed() ? "  (closed)" : "  (open)");
  std::printf("rivet areas: %zu\n", p.rivet_areas.size());
  for (const auto& r : p.rivet_areas)
    std::printf("  %-20s on %-16s %5zu faces  %.6f m^2\n", r.name.c_str(), p.meshes[r.mesh].name.c_str(), r.faces.size(), r.area_m2);
  std::printf("loads: %zu\n", p.loads.size());
  for (const auto& l : p.loads) {
    std::printf("  %-20s centre %s m  size %s m  force %s N  moment %s N*m\n", l.name.c_str(), fmt_vec(l.center).c_str(),
                fmt_vec(l.size).c_str(), fmt_vec(l.force).c_str(), fmt_vec(l.moment).c_str());
    print_mass_and_cases(l);
  }
  print_envelope_and_requirements(p);
  const auto b = p.bounds();
  std::printf("bounding box: min %s m  max %s m  (diagonal %.4g m)\n", fmt_vec(b.min).c_str(), fmt_vec(b.max).c_str(), b.diagonal());
  std::printf("sheet: t = %.4g mm, E = %.4g GPa, Fty = %.4g MPa; bend radius %.4g mm, K %.3g, min flange %.4g mm\n",
              p.material.thickness * 1e3, p.material.youngs_modulus * 1e-9, p.material.yield_strength * 1e-6,
              p.manufacturing.bend_radius * 1e3, p.manufacturing.k_factor, p.manufacturing.min_flange * 1e3);
}

// The environment queries a search will ask, on every load: how far its base is
// from each rivet area and from obstacles, and what a ray from it meets.
void print_queries(const sheetgen::Problem& p, const sheetgen::EnvironmentOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  sheetgen::Environment env(p, options);
  const double build = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("environment: voxel %.4g mm, built in %.3f s, distance fields %.1f MiB\n", env.voxel_size() * 1e3, build,
              static_cast<double>(env.field_memory_bytes()) / (1024.0 * 1024.0));
  const double t = p.material.thickness;
  for (size_t li = 0; li < p.loads.size(); ++li) {
    const auto& l = p.loads[li];
    const auto face = l.bottom_face();
    const Vec3 base = 0.25 * (face[0] + face[1] + face[2] + face[3]);
    const Vec3 down = l.rotation * Vec3(0, 0, -1);
    const Vec3 mid = base + 0.5 * t * down;  // mid-surface of a base tab under the box
    std::printf("load %s: base-tab centre %s m, clearance to other obstacles %.4g mm\n", l.name.c_str(), fmt_vec(mid).c_str(),
                env.clearance(mid, sheetgen::AllowedContacts{{}, {static_cast<int>(li)}}) * 1e3);
    for (int r = 0; r < env.rivet_area_count(); ++r)
      std::printf("  distance to rivet area %-16s %.4g m\n", p.rivet_areas[r].name.c_str(), env.rivet_area_distance(r, mid));
    const Vec3 dirs[6] = {Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitY(), Vec3::UnitZ(), -Vec3::UnitZ()};
    const char* names[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};
    for (int k = 0; k < 6; ++k) {
      // Start just outside the box so the ray does not report the box itself.
      const Vec3 o = l.center + (0.5 * l.size.cwiseAbs().maxCoeff() * 1.75 + t) * dirs[k];
      auto hit = env.cast_ray(o, dirs[k], 100.0);
      if (!hit) {
        std::printf("  ray %s: no hit\n", names[k]);
        continue;
      }
      std::string what = hit->load >= 0 ? "load " + p.loads[hit->load].name : "mesh " + p.meshes[hit->mesh].name;
      if (hit->rivet_area >= 0) what += " (rivet area " + p.rivet_areas[hit->rivet_area].name + ")";
      std::printf("  ray %s: hits %s face %d at %.4g m\n", names[k], what.c_str(), hit->face, hit->distance);
    }
  }
}

// `sheetgen export-ccx RESULT.json --load NAME --out DECK.inp`: the FEM model of
// one load's part as a CalculiX deck: every load case as a static step, a
// *BUCKLE step for one case (`--buckle`) and a *FREQUENCY step (`--modes`)
// (docs/fem.md "CalculiX export"). result.json names its problem file
// ("problem", relative to result.json), which supplies the load box and material.
// `--element-size MM` meshes at that size instead of the default (refinement
// studies against CalculiX); `--solve` also solves the same model with our FEM
// and prints its compliance and load deflection, so both solvers see one mesh.
struct ExportCcxArgs {
  std::string result, load, out;
  double element_size_mm = 0;  // mm; <= 0: default_element_size (docs/fem.md)
  bool solve = false;
  std::string displacements;  // with --solve: CSV of our displacements by deck node id (m)
  std::string element_type = "S4";  // CalculiX element: S4 (split triangles), S8R (the same with mid-side nodes) or S6 (our triangles, quadratic)
  bool kirchhoff = false;           // with --solve: our DKT (no transverse shear) instead of DKMT, for studies
  std::string buckle;               // load case of the *BUCKLE step (name or index); "": the first case; "none": no step
  int modes = 3;                    // eigenfrequencies the *FREQUENCY step asks for; 0: no step
};

namespace fs = std::filesystem;

// A sheetgen-result/1 document.
nlohmann::json read_result_json(const std::string& result_path) {
  std::ifstream in(fs::u8path(result_path), std::ios::binary);
  if (!in) throw sheetgen::InputError(result_path, "", "cannot be opened");
  std::stringstream ss;
  ss << in.rdbuf();
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(ss.str());
  } catch (const nlohmann::json::parse_error& e) {
    throw sheetgen::InputError(result_path, "", std::string("is not valid JSON (") + e.what() + ")");
  }
  if (!doc.is_object() || doc.value("format", "") != "sheetgen-result/1")
    throw sheetgen::InputError(result_path, "format", "expected \"sheetgen-result/1\"");
  return doc;
}

// The problem file the result solves ("problem", relative to result.json).
sheetgen::Problem problem_of(const nlohmann::json& doc, const std::string& result_path) {
  if (!doc.contains("problem") || !doc["problem"].is_string())
    throw sheetgen::InputError(result_path, "problem", "required field is missing (the problem file this result solves)");
  fs::path problem_path = fs::u8path(doc["problem"].get<std::string>());
  if (problem_path.is_relative()) problem_path = fs::u8path(result_path).parent_path() / problem_path;
  return sheetgen::load_problem(problem_path.u8string());
}

int load_index_of(const sheetgen::Problem& problem, const std::string& load_name, const std::string& result_path) {
  int load_index = -1;
  for (size_t i = 0; i < problem.loads.size(); ++i)
    if (problem.loads[i].name == load_name) load_index = static_cast<int>(i);
  if (load_index < 0) throw sheetgen::InputError(result_path, "--load", "the problem has no load named '" + load_name + "'");
  return load_index;
}

// The load's valid part in the result.
const nlohmann::json& part_of(const nlohmann::json& doc, const std::string& load_name, const std::string& result_path) {
  const nlohmann::json* part = nullptr;
  if (doc.contains("parts") && doc["parts"].is_array())
    for (const auto& pj : doc["parts"])
      if (pj.is_object() && pj.value("load", "") == load_name) part = &pj;
  if (!part) throw sheetgen::InputError(result_path, "parts", "no part for load '" + load_name + "'");
  if (part->value("status", "ok") != "ok" || !part->contains("tabs"))
    throw sheetgen::InputError(result_path, "parts[load=" + load_name + "]", "has no valid part to export");
  return *part;
}

// The deck's options from the command line: the buckling case by name or
// index (the first by default), the number of modes.
sheetgen::CcxExportOptions deck_options(const sheetgen::ShellModel& model, const ExportCcxArgs& a) {
  sheetgen::CcxExportOptions o;
  o.element_type = a.element_type;
  if (a.buckle != "none") o.buckle_case = a.buckle.empty() ? 0 : sheetgen::find_load_case(model, a.buckle);
  o.frequency_modes = a.modes;
  return o;
}

// "*BUCKLE of 'design', *FREQUENCY (3 modes, 1 rigid masses), 2 static ('design', 'side')"
std::string steps_summary(const sheetgen::ShellModel& model, const sheetgen::CcxExportOptions& o) {
  const std::vector<sheetgen::ShellLoadCase> cases = model.cases();
  std::string s;
  if (o.buckle_case >= 0) s += "*BUCKLE of '" + cases[o.buckle_case].name + "', ";
  if (o.frequency_modes > 0)
    s += "*FREQUENCY (" + std::to_string(o.frequency_modes) + " modes, " + std::to_string(model.point_masses.size()) +
         " rigid masses), ";
  s += std::to_string(cases.size()) + " static (";
  for (size_t c = 0; c < cases.size(); ++c) s += (c ? ", '" : "'") + cases[c].name + "'";
  return s + ")";
}

// Writes beside the target and renames: a failed run leaves no half-written deck.
sheetgen::CcxDeckMap write_deck(const sheetgen::PartModel& model, const ExportCcxArgs& a) {
  const fs::path out = fs::u8path(a.out);
  const fs::path tmp = out.parent_path() / (out.filename().u8string() + ".tmp");
  const sheetgen::CcxExportOptions options = deck_options(model.model, a);
  sheetgen::CcxDeckMap map;
  {
    std::ofstream deck(tmp, std::ios::binary);
    if (!deck) throw sheetgen::InputError(a.out, "--out", "cannot be written (" + std::string(std::strerror(errno)) + ")");
    try {
      map = sheetgen::write_ccx_deck(model.model, deck, options);
    } catch (...) {
      deck.close();
      std::error_code ec;
      fs::remove(tmp, ec);
      throw;
    }
    deck.flush();
    if (!deck) {
      std::error_code ec;
      fs::remove(tmp, ec);
      throw sheetgen::InputError(a.out, "--out", "write failed (disk full?)");
    }
    std::printf("wrote %s: %d nodes, %d %s elements, %zu rivets clamped, load at node %d\n", a.out.c_str(),
                map.node_count, map.element_count, a.element_type.c_str(), model.rivets.size(),
                map.ref_node.empty() ? -1 : map.ref_node.back());
    std::printf("steps: %s\n", steps_summary(model.model, options).c_str());
  }
  fs::rename(tmp, out);
  return map;
}

// Node by node against CalculiX's .dat: where the two solvers part.
void write_displacements_csv(const std::string& path, const sheetgen::PartModel& model, const sheetgen::ShellResult& r,
                             const sheetgen::CcxDeckMap& map) {
  std::ofstream csv(fs::u8path(path), std::ios::binary);
  if (!csv) throw sheetgen::InputError(path, "--displacements", "cannot be written");
  csv << "deck_node,x_m,y_m,z_m,ux_m,uy_m,uz_m\n";
  char line[256];
  for (size_t i = 0; i < r.displacements.size() && i < map.node_id.size(); ++i) {
    if (map.node_id[i] < 0) continue;
    const auto& x = model.model.nodes[i];
    const auto& u = r.displacements[i];
    std::snprintf(line, sizeof line, "%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", map.node_id[i], x.x(), x.y(), x.z(), u(0),
                  u(1), u(2));
    csv << line;
  }
}

// --solve: every case of the deck, the buckling factor of every case and the
// frequencies the deck asks for, by our FEM on the deck's mesh.
void print_our_envelope(const sheetgen::Problem& problem, const sheetgen::PartModel& model,
                        const sheetgen::ShellElementOptions& element, const ExportCcxArgs& a) {
  sheetgen::EnvelopeOptions eo;
  eo.frequencies = a.modes;
  sheetgen::ShellSolver solver;
  const sheetgen::EnvelopeResult env = sheetgen::analyse_envelope(problem, model, eo, element, solver);
  for (const sheetgen::CaseResult& c : env.cases)
    std::printf("ours: case %-16s compliance %.8g J (limit %.6g J), along F %.6g mm, MS %.4g, buckling factor %.6g\n",
                c.name.c_str(), c.compliance, c.compliance_limit, c.deflection_along_force * 1e3, c.margin_of_safety,
                c.buckling_factor);
  std::printf("ours: frequencies");
  for (double f : env.frequencies_hz) std::printf(" %.6g", f);
  std::printf(" Hz (box %.4g kg, sheet %.4g kg); statics %.3f s, buckling %.3f s, vibration %.3f s\n", env.box_mass,
              env.sheet_mass, env.static_seconds, env.buckling_seconds, env.vibration_seconds);
}

// --solve: the same model with our FEM, so both solvers see one mesh.
void solve_ours(const sheetgen::Problem& problem, const sheetgen::PartModel& model, const sheetgen::CcxDeckMap& map,
                const ExportCcxArgs& a) {
  sheetgen::ShellElementOptions element;
  element.transverse_shear = !a.kirchhoff;
  const sheetgen::ShellSolveOptions solve_options = sheetgen::part_solve_options(problem, element);
  const sheetgen::ShellResult r = sheetgen::solve_shell(model.model, solve_options);
  std::printf("ours: h = %.4g mm, %zu triangles, %d DOF, compliance %.8g J, deflection %.8g mm\n",
              model.mesh.element_size * 1e3, model.model.triangles.size(), r.reduced_dofs, r.compliance,
              r.load_deflection * 1e3);
  if (r.max_von_mises_element >= 0) {
    const auto& tri = model.model.triangles[r.max_von_mises_element];
    const sheetgen::Vec3 c = (model.model.nodes[tri[0]] + model.model.nodes[tri[1]] + model.model.nodes[tri[2]]) / 3.0;
    std::printf("ours: max von Mises %.6g MPa (stress rule) at element centroid (%.2f, %.2f, %.2f) mm, MS %.4g\n",
                r.max_von_mises * 1e-6, c.x() * 1e3, c.y() * 1e3, c.z() * 1e3, r.margin_of_safety);
  }
  if (!a.displacements.empty()) write_displacements_csv(a.displacements, model, r, map);
  print_our_envelope(problem, model, element, a);
}

int export_ccx(const ExportCcxArgs& a) {
  const nlohmann::json doc = read_result_json(a.result);
  const sheetgen::Problem scene = problem_of(doc, a.result);
  const int load_index = load_index_of(scene, a.load, a.result);
  const nlohmann::json& part = part_of(doc, a.load, a.result);
  // The sheet the part is made of: a thicker gauge when the problem's gave the load none (docs/pipeline.md).
  const std::optional<double> t =
      sheetgen::sheet_thickness_from_json(part.dump(), a.result + " parts[load=" + a.load + "]");
  std::optional<sheetgen::Problem> thicker;
  const sheetgen::Problem& problem = sheetgen::problem_at_sheet(scene, t.value_or(0.0), thicker);
  const sheetgen::PlateGeometry geometry = sheetgen::plate_geometry_from_json(part.dump(), a.result);
  sheetgen::PartModelOptions model_options;
  model_options.element_size = a.element_size_mm * 1e-3;
  model_options.self_rivets = sheetgen::self_rivet_ties_from_json(part.dump(), a.result);
  const sheetgen::PartModel model = sheetgen::build_part_model(problem, load_index, geometry, model_options);
  const sheetgen::CcxDeckMap map = write_deck(model, a);
  if (a.solve) solve_ours(problem, model, map, a);
  return 0;
}

// "  sheet 3.18 mm (thicker gauge 5)" for a part the problem's sheet could not
// give (docs/pipeline.md "Thicker gauges"); empty otherwise.
std::string sheet_note(const sheetgen::Problem& problem, const sheetgen::LoadOutcome& l) {
  if (!(l.thickness > problem.material.thickness)) return {};
  char s[64];
  std::snprintf(s, sizeof s, "  sheet %.3g mm (thicker gauge %d)", l.thickness * 1e3, l.gauges_tried);
  return s;
}

std::atomic<bool> g_interrupted{false};
extern "C" void on_sigint(int) { g_interrupted = true; }

struct SolveArgs {
  std::string problem, out;
  std::optional<std::uint64_t> seed;
  std::optional<int> chains, iterations, beam, threads;
  bool right_angles = false;
  bool flat_extensions = false;
  bool no_self_rivet = false;
  bool no_lips = false;
  bool no_web_roots = false;
  bool no_flat_fallback = false;
  bool no_sizing = false;
  bool no_right_angle_pass = false;
  bool no_right_angle_search = false;
  int seed_retries = sheetgen::GenerateOptions{}.seed_retries;
};

// `sheetgen solve`: exit 0 = every load has a valid part, 2 = some load has
// none (result.json says why), 1 = bad input, 130 = interrupted (nothing written).
int solve(const SolveArgs& a) {
  const sheetgen::Problem problem = sheetgen::load_problem(a.problem);
  sheetgen::GenerateOptions options;
  options.chains = a.chains;
  options.iterations = a.iterations;
  options.beam_width = a.beam;
  options.threads = a.threads;
  options.seed = a.seed;
  options.right_angles = a.right_angles;
  options.flat_extensions = a.flat_extensions;
  options.compose.self_rivet = !a.no_self_rivet;
  options.compose.stiffening_lips = !a.no_lips;
  options.web_fallback = !a.no_web_roots;
  options.flat_fallback = !a.no_flat_fallback;
  options.seed_retries = a.seed_retries;
  options.sizing = !a.no_sizing;
  options.right_angle_pass = !a.no_right_angle_pass;
  options.right_angle_search = !a.no_right_angle_search;
  sheetgen::GenerateProgress progress;
  std::signal(SIGINT, on_sigint);
  std::signal(SIGTERM, on_sigint);
  sheetgen::GenerateResult result;
  std::exception_ptr failure;
  std::atomic<bool> finished{false};
  std::thread worker([&] {
    try {
      result = sheetgen::generate(problem, options, &progress);
    } catch (...) {
      failure = std::current_exception();  // reaches the caller below, not std::terminate
    }
    finished = true;
  });
  const bool tty = ::isatty(STDERR_FILENO);
  while (!finished.load()) {
    if (g_interrupted.load()) progress.cancel = true;
    if (tty) {
      const auto stage = static_cast<sheetgen::Stage>(progress.stage.load());
      const long long done = progress.discovery.iterations.load(), total = std::max(1LL, progress.discovery.total.load());
      const int width = 30;
      const int filled = stage >= sheetgen::Stage::Composition ? width : static_cast<int>(width * done / total);
      // The second and third searches of a load (web roots, flat extensions;
      // docs/pipeline.md) restart the bar; say so.
      const std::string label = std::string(sheetgen::to_string(stage)) +
                                (progress.right_angle_pass.load() ? " (right angles)"
                                 : progress.flat_pass.load()      ? " (flat)"
                                 : progress.web_roots.load()      ? " (webs)"
                                                                  : "") +
                                (progress.gauge.load() > 0 ? " (gauge " + std::to_string(progress.gauge.load()) + ")" : "");
      std::fprintf(stderr, "\r  load %d/%d [%-*s] %-18s segments %3d  evaluated %4d  best %.1f cm^2   ", progress.load.load() + 1,
                   progress.loads.load(), width, std::string(filled, '#').c_str(), label.c_str(),
                   progress.discovery.segments.load(), progress.compose.evaluated.load(), progress.compose.best_cost.load() * 1e4);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  worker.join();
  if (tty) std::fprintf(stderr, "\n");
  if (failure) std::rethrow_exception(failure);
  if (result.cancelled || g_interrupted.load()) {
    std::fprintf(stderr, "sheetgen: interrupted; nothing was written\n");
    return 130;
  }
  try {
    sheetgen::write_outputs(a.out, problem, result, a.problem);
  } catch (const std::runtime_error& e) {
    // The output folder is the user's choice: report it like bad input.
    std::fprintf(stderr, "sheetgen: %s\n", e.what());
    return 1;
  }
  for (const auto& l : result.loads) {
    if (l.ok)
      std::printf("%-20s ok  area %.1f cm^2  mass %.1f g%s  bends %d  compliance %.4g J (limit %.4g)  deflection along F %.3f mm "
                  "(|u| %.3f mm)  MS %.2f  %.1f s\n",
                  l.load.c_str(), l.part.area * 1e4, l.part.area * l.thickness * problem.material.density * 1e3,
                  sheet_note(problem, l).c_str(),
                  l.part.bends, l.part.fem.compliance, l.part.fem.compliance_limit, l.part.fem.deflection_along_force * 1e3,
                  l.part.fem.deflection * 1e3, l.part.fem.margin_of_safety, l.total_time.wall_seconds);
    else
      std::printf("%-20s no valid part: %s\n", l.load.c_str(), l.reason.c_str());
  }
  std::printf("wrote %s/result.json (%.1f s)\n", a.out.c_str(), result.seconds);
  return result.all_ok() ? 0 : 2;
}

struct CheckArgs {
  std::string problem;
  bool env = false;     // also build the environment and print its queries
  double voxel_mm = 0;  // mm, clearance field voxel; 0 = automatic
};

// `sheetgen check`: the problem's summary, with --env the environment's queries.
int check(const CheckArgs& a) {
  const sheetgen::Problem p = sheetgen::load_problem(a.problem);
  print_summary(p);
  if (a.env) {
    sheetgen::EnvironmentOptions options;
    options.voxel_size = a.voxel_mm * 1e-3;
    print_queries(p, options);
  }
  std::printf("ok\n");
  return 0;
}

CLI::App* add_check_command(CLI::App& app, CheckArgs& a) {
  auto* check = app.add_subcommand("check", "validate a problem file and print a summary");
  check->add_option("problem", a.problem, "problem JSON (sheetgen-problem/1)")->required();
  check->add_flag("--env", a.env, "also build the environment (clearance field, rays) and print queries");
  check->add_option("--voxel-mm", a.voxel_mm, "clearance field voxel size in mm (default: automatic)");
  return check;
}

CLI::App* add_solve_command(CLI::App& app, SolveArgs& a) {
  auto* solve_cmd = app.add_subcommand("solve", "design a part for every load of a problem");
  solve_cmd->add_option("problem", a.problem, "problem JSON (sheetgen-problem/1)")->required();
  solve_cmd->add_option("--out", a.out, "output folder")->required();
  solve_cmd->add_option("--seed", a.seed, "random seed");
  solve_cmd->add_option("--chains", a.chains, "MCMC chains (M)")->check(CLI::Range(1, 1024));
  solve_cmd->add_option("--iterations", a.iterations, "iterations per chain (N)")->check(CLI::Range(1, 10000000));
  solve_cmd->add_option("--beam", a.beam, "beam width of the composition (B)")->check(CLI::Range(1, 4096));
  solve_cmd->add_option("--threads", a.threads, "worker threads (0 = all cores)")->check(CLI::Range(0, 1024));
  solve_cmd->add_flag("--right-angles", a.right_angles,
                      "restrict bends to +-90 degrees (plus flat extensions) and no skew (the expert's practice)");
  solve_cmd->add_flag("--flat-extensions", a.flat_extensions,
                      "let a tab continue its parent flat (0 degrees, no bend); on with --right-angles");
  solve_cmd->add_flag("--no-self-rivet", a.no_self_rivet, "do not try self-riveting (for the ablation of paper Fig. 9)");
  solve_cmd->add_flag("--no-lips", a.no_lips, "do not try stiffening lips on the free edges (the paper's method alone)");
  solve_cmd->add_flag("--no-web-roots", a.no_web_roots,
                      "do not search a load again with web roots when the first search finds no valid part");
  solve_cmd->add_flag("--no-flat-fallback", a.no_flat_fallback,
                      "do not search a load a third time with flat extensions when no search found a valid part");
  solve_cmd->add_flag("--no-right-angle-pass", a.no_right_angle_pass,
                      "do not search each load once more in the right-angle grammar for a cheaper part");
  solve_cmd->add_flag("--no-right-angle-search", a.no_right_angle_search,
                      "do not search a load whose answer is a press-brake fallback again as a right-angle solve would");
  solve_cmd->add_flag("--no-sizing", a.no_sizing,
                      "keep each answer as the composition found it, without narrowing its tabs to its limits");
  solve_cmd->add_option("--seed-retries", a.seed_retries,
                        "searches of a load with fresh seeds after every other pass found no valid part; one whose own "
                        "segments give no part composes them with those found before it (default 2)")
      ->check(CLI::Range(0, 100));
  return solve_cmd;
}

CLI::App* add_export_ccx_command(CLI::App& app, ExportCcxArgs& a) {
  auto* ccx = app.add_subcommand("export-ccx", "write one load's part as a CalculiX input deck");
  ccx->add_option("result", a.result, "result JSON (sheetgen-result/1)")->required();
  ccx->add_option("--load", a.load, "load name")->required();
  ccx->add_option("--out", a.out, "deck to write (.inp)")->required();
  ccx->add_option("--element-size", a.element_size_mm, "element size in mm (default: the solver's, docs/fem.md)")
      ->check(CLI::Range(0.05, 1000.0));
  ccx->add_flag("--solve", a.solve, "also solve the model with sheetgen's FEM and print compliance and deflection");
  ccx->add_option("--displacements", a.displacements,
                  "with --solve: write our displacements by deck node id to this CSV (m), to compare with CalculiX's .dat");
  ccx->add_option("--element-type", a.element_type,
                  "CalculiX element: S4 (default; split triangles), S6 (our triangles, quadratic: the compliance reference, docs/fem.md) or S8R (split triangles, quadratic)")
      ->check(CLI::IsMember({"S4", "S6", "S8R"}));
  ccx->add_flag("--kirchhoff", a.kirchhoff,
                "with --solve: solve with DKT (no transverse shear) instead of the default DKMT, for studies");
  ccx->add_option("--buckle", a.buckle,
                  "load case of the *BUCKLE step: its name or index from 0 (default: the first case); none: no *BUCKLE");
  ccx->add_option("--modes", a.modes, "eigenfrequencies of the *FREQUENCY step (default 3); 0: no *FREQUENCY")
      ->check(CLI::Range(0, 1000));
  return ccx;
}

}  // namespace

int main(int argc, char** argv) {
  // The CLI owns its process: keep freed FEM buffers for the next candidate
  // (core/malloc_settings.hpp). The Python module leaves Blender's alone.
  if (const char* refused = sheetgen::apply_malloc_settings(); *refused)
    std::fprintf(stderr, "sheetgen: warning: glibc refused the allocator setting %s\n", refused);
  CLI::App app{"sheetgen: generative design of sheet-metal brackets"};
  app.require_subcommand(1);
  CheckArgs check_args;
  SolveArgs solve_args;
  ExportCcxArgs ccx_args;
  const CLI::App* check_cmd = add_check_command(app, check_args);
  const CLI::App* solve_cmd = add_solve_command(app, solve_args);
  const CLI::App* ccx_cmd = add_export_ccx_command(app, ccx_args);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 1;
  }

  try {
    if (*check_cmd) return check(check_args);
    if (*solve_cmd) return solve(solve_args);
    if (*ccx_cmd) return export_ccx(ccx_args);
  } catch (const sheetgen::InputError& e) {
    std::fprintf(stderr, "sheetgen: %s\n", e.what());
    return 1;
  } catch (const sheetgen::FemError& e) {
    std::fprintf(stderr, "sheetgen: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sheetgen: internal error: %s\n", e.what());
    return 3;
  }
  return 0;
}
