# The core library's sources, in one list: native/sheetgen/core/CMakeLists.txt
# builds sheetgen_core from it and tests/fuzz/ builds an instrumented copy from
# it, so a new core file cannot be missing from the fuzzers' link.
set(SHEETGEN_CORE_SOURCES
  input_error.cpp
  atomic_file.cpp
  malloc_settings.cpp
  triangle_mesh.cpp
  mesh_io.cpp
  geometry.cpp
  polygon_geometry.cpp
  json_reader.cpp
  load_cases.cpp
  cost_model.cpp
  press_brake_tooling.cpp
  sheet_gauges.cpp
  stopwatch.cpp
  problem.cpp
)
