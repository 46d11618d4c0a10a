#pragma once
// Triangle-mesh readers (OBJ, ASCII and binary PLY) and an OBJ writer.
// Polygons are fan-triangulated; every failure is an InputError naming the
// file and the line (or element) at fault.
#include <string>

#include "sheetgen/core/triangle_mesh.hpp"

namespace sheetgen {

// Reads by extension (.obj / .ply, any case). `display_name` is what errors call the file.
TriangleMesh read_mesh(const std::string& path, const std::string& display_name = "");
TriangleMesh read_obj(const std::string& path, const std::string& display_name = "");
TriangleMesh read_ply(const std::string& path, const std::string& display_name = "");
// From memory (used by the readers and the fuzzers).
TriangleMesh parse_obj(const std::string& text, const std::string& display_name);
TriangleMesh parse_ply(const std::string& bytes, const std::string& display_name);

// Checks a mesh the user gave: not empty, finite vertices, indices in range.
void validate_mesh(const TriangleMesh& mesh, const std::string& file, const std::string& field);

void write_obj(const TriangleMesh& mesh, const std::string& path);

}  // namespace sheetgen
