// libFuzzer target: the problem reader, parse_problem(), on arbitrary bytes.
// Contract (docs/problem-format.md, docs/code-style.md point 7): any input either loads or
// throws sheetgen::InputError whose message is one line naming the file; no
// other exception, no crash, no hang, no memory blow-up. Mesh files named by
// the problem are looked up in mesh_dir/ (wall.obj, tri.ply, box_le.ply, box_be.ply).
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <string>

#include "sheetgen/core/input_error.hpp"
#include "sheetgen/core/problem.hpp"

namespace {

[[noreturn]] void contract_broken(const char* what, const std::string& detail) {
  std::fprintf(stderr, "fuzz_problem_json: contract broken: %s: %s\n", what, detail.c_str());
  std::abort();
}

// Touch everything a loaded problem promises, so a bad invariant shows up here
// rather than deep in the environment or the search.
void check_loaded(const sheetgen::Problem& p) {
  if (p.meshes.empty() || p.rivet_areas.empty() || p.loads.empty()) contract_broken("loaded", "empty section");
  for (const auto& m : p.meshes) {
    if (m.mesh.vertices.empty() || m.mesh.triangles.empty()) contract_broken("mesh", m.name);
    for (const auto& t : m.mesh.triangles)
      for (int k = 0; k < 3; ++k)
        if (t[k] < 0 || t[k] >= static_cast<int>(m.mesh.vertices.size())) contract_broken("triangle index", m.name);
    (void)m.mesh.is_closed();
  }
  for (const auto& ra : p.rivet_areas) {
    if (ra.mesh < 0 || ra.mesh >= static_cast<int>(p.meshes.size())) contract_broken("rivet mesh", ra.name);
    for (int f : ra.faces)
      if (f < 0 || f >= static_cast<int>(p.meshes[ra.mesh].mesh.triangles.size())) contract_broken("rivet face", ra.name);
    if (!(ra.area_m2 > 0)) contract_broken("rivet area", ra.name);
  }
  for (const auto& l : p.loads) {
    if (!l.center.allFinite() || !l.force.allFinite() || !l.moment.allFinite()) contract_broken("load", l.name);
    if (!(l.size.array() > 0).all()) contract_broken("load size", l.name);
    if (std::abs(l.rotation.norm() - 1.0) > 1e-9) contract_broken("load rotation not unit", l.name);
    (void)l.box_mesh();
    (void)l.signed_distance(l.center);
    (void)p.requirements.compliance_limit(l.force.norm());
  }
  (void)p.bounds().diagonal();
  (void)p.triangle_count();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const sheetgen::Problem p = sheetgen::parse_problem(text, "fuzz.json", SHEETGEN_FUZZ_MESH_DIR);
    check_loaded(p);
  } catch (const sheetgen::InputError& e) {
    const std::string msg = e.what();
    if (msg.rfind("fuzz.json", 0) != 0) contract_broken("message does not start with the file", msg);
    if (msg.find('\n') != std::string::npos || msg.find('\r') != std::string::npos)
      contract_broken("message is not one line", msg);
  }
  // Anything else (std::bad_alloc, nlohmann::json::exception, std::out_of_range,
  // std::filesystem_error ...) escapes and libFuzzer reports it as a crash.
  return 0;
}
