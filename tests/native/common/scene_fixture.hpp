#pragma once
// Small scenes assembled in code for the discovery and part tests and the part bench.
#include "sheetgen/core/problem.hpp"

#include "sheet_fixture.hpp"

namespace sheetgen::testing_scenes {

inline Manufacturing manufacturing() { return fixtures::aluminium_manufacturing_1_6mm(); }  // docs/architecture.md defaults for t = 1.6 mm

// Rectangle from corner o spanned by u and v (normal u x v), two triangles.
inline TriangleMesh quad(const Vec3& o, const Vec3& u, const Vec3& v) {
  TriangleMesh m;
  m.vertices = {o, o + u, o + u + v, o + v};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

// Horizontal rectangle (x0..x1, y0..y1) m at height z m, normal +z, two triangles.
inline TriangleMesh rectangle(double x0, double x1, double y0, double y1, double z) {
  TriangleMesh m;  // corners written out rather than through quad(): x0 + (x1 - x0) need not round to x1
  m.vertices = {Vec3(x0, y0, z), Vec3(x1, y0, z), Vec3(x1, y1, z), Vec3(x0, y1, z)};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

// Load 40 x 40 x 20 mm whose base tab is the square (0,0)-(40,40) mm at z = 0.
inline Problem base_problem() {
  Problem p;
  p.source = "<test>";
  p.material.thickness = 1.6e-3;
  p.requirements.clearance = 1e-3;
  p.manufacturing = manufacturing();
  Load load;
  load.name = "box";
  load.center = Vec3(0.02, 0.02, 0.0108);
  load.size = Vec3(0.04, 0.04, 0.02);
  load.force = Vec3(0, 0, -100);
  p.loads.push_back(load);
  return p;
}

inline void add_rivet_mesh(Problem& p, const std::string& name, const TriangleMesh& m) {
  p.meshes.push_back({name, m, "<inline>"});
  RivetAreaSpec ra;
  ra.name = name;
  ra.mesh = static_cast<int>(p.meshes.size()) - 1;
  ra.faces = {0, 1};
  p.rivet_areas.push_back(ra);
}

}  // namespace sheetgen::testing_scenes
