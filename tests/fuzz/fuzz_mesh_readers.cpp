// libFuzzer target: the OBJ and PLY readers, parse_obj() and parse_ply(), on
// the same arbitrary bytes, followed by validate_mesh() as load_problem does.
// Contract: a mesh or sheetgen::InputError (one line, naming the file); no
// other exception, no crash, no hang, no memory blow-up (run with
// -rss_limit_mb / -malloc_limit_mb, see scripts/fuzz.sh).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "sheetgen/core/input_error.hpp"
#include "sheetgen/core/mesh_io.hpp"

namespace {

[[noreturn]] void contract_broken(const char* what, const std::string& detail) {
  std::fprintf(stderr, "fuzz_mesh_readers: contract broken: %s: %s\n", what, detail.c_str());
  std::abort();
}

void check_message(const sheetgen::InputError& e, const char* file) {
  const std::string msg = e.what();
  if (msg.rfind(file, 0) != 0) contract_broken("message does not start with the file", msg);
  if (msg.find('\n') != std::string::npos || msg.find('\r') != std::string::npos) contract_broken("message is not one line", msg);
}

void use(const sheetgen::TriangleMesh& mesh, const char* file) {
  try {
    sheetgen::validate_mesh(mesh, file, "mesh");
  } catch (const sheetgen::InputError& e) {
    check_message(e, file);
    return;
  }
  // A valid mesh: every query the problem loader and the environment make.
  (void)sheetgen::bounding_box(mesh).diagonal();
  (void)mesh.area();
  (void)mesh.is_closed();
  for (int f = 0; f < static_cast<int>(mesh.triangles.size()); ++f) (void)mesh.face_normal(f);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    use(sheetgen::parse_obj(bytes, "fuzz.obj"), "fuzz.obj");
  } catch (const sheetgen::InputError& e) {
    check_message(e, "fuzz.obj");
  }
  try {
    use(sheetgen::parse_ply(bytes, "fuzz.ply"), "fuzz.ply");
  } catch (const sheetgen::InputError& e) {
    check_message(e, "fuzz.ply");
  }
  return 0;
}
