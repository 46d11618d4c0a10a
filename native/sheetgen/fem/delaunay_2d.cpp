#include "sheetgen/fem/delaunay_2d.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <numeric>
#include <string>
#include <utility>

#include "sheetgen/fem/fem_error.hpp"

namespace sheetgen {
namespace {

// Exact predicates on double coordinates; the triangulation constructs no
// new point, so inexact constructions never come into play.
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<int, Kernel>;    // info: index into the points
using InfoFaceBase = CGAL::Triangulation_face_base_with_info_2<bool, Kernel>;  // info: inside the outline
using FaceBase = CGAL::Constrained_triangulation_face_base_2<Kernel, InfoFaceBase>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
// Crossing outline segments throw instead of getting an intersection point
// constructed (inexactly); a point exactly on a segment splits it.
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds,
                                                       CGAL::No_constraint_intersection_requiring_constructions_tag>;

void check_input(const std::vector<Vec2>& points, const std::vector<int>& outline) {
  if (outline.size() < 3) throw FemError("outline", "needs at least 3 points (got " + std::to_string(outline.size()) + ")");
  std::vector<char> seen(points.size(), 0);
  for (int i : outline) {
    if (i < 0 || i >= static_cast<int>(points.size()))
      throw FemError("outline", "index " + std::to_string(i) + " is not a point (" + std::to_string(points.size()) +
                                    " points)");
    if (seen[i]++) throw FemError("outline", "point " + std::to_string(i) + " appears twice");
  }
  for (size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite()) throw FemError("point " + std::to_string(i), "is not finite");
}

// CGAL merges equal points into one vertex; name the first pair instead.
void throw_duplicate(const std::vector<Vec2>& points) {
  std::vector<int> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  auto key = [&](int i) { return std::make_pair(points[i].x(), points[i].y()); };
  std::sort(order.begin(), order.end(), [&](int a, int b) { return key(a) < key(b) || (key(a) == key(b) && a < b); });
  for (size_t k = 1; k < order.size(); ++k)
    if (key(order[k - 1]) == key(order[k]))
      throw FemError("point " + std::to_string(order[k]), "duplicates point " + std::to_string(order[k - 1]));
}

// Marks the finite faces inside the outline: those not reachable from the
// infinite face without crossing a constrained edge.
void mark_inside(Cdt& cdt) {
  for (Cdt::Face_handle f : cdt.all_face_handles()) f->info() = true;
  std::vector<Cdt::Face_handle> stack = {cdt.infinite_face()};
  cdt.infinite_face()->info() = false;
  while (!stack.empty()) {
    const Cdt::Face_handle f = stack.back();
    stack.pop_back();
    for (int i = 0; i < 3; ++i) {
      const Cdt::Face_handle n = f->neighbor(i);
      if (!n->info() || cdt.is_constrained(Cdt::Edge(f, i))) continue;
      n->info() = false;
      stack.push_back(n);
    }
  }
}

}  // namespace

PolygonTriangulation triangulate_polygon(const std::vector<Vec2>& points, const std::vector<int>& outline) {
  check_input(points, outline);
  std::vector<std::pair<Kernel::Point_2, int>> input;
  input.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i)
    input.emplace_back(Kernel::Point_2(points[i].x(), points[i].y()), static_cast<int>(i));
  Cdt cdt;
  cdt.insert(input.begin(), input.end());  // spatially sorted insertion
  if (cdt.number_of_vertices() != points.size()) throw_duplicate(points);

  std::vector<Cdt::Vertex_handle> vertex(points.size());
  for (Cdt::Vertex_handle v : cdt.finite_vertex_handles()) vertex[v->info()] = v;
  try {
    for (size_t i = 0; i < outline.size(); ++i)
      cdt.insert_constraint(vertex[outline[i]], vertex[outline[(i + 1) % outline.size()]]);
  } catch (const Cdt::Intersection_of_constraints_exception&) {
    throw FemError("outline", "segments cross (the polygon is not simple)");
  }
  PolygonTriangulation out;
  if (cdt.dimension() < 2) {  // all points on one line: no triangle
    out.unused_points.resize(points.size());
    std::iota(out.unused_points.begin(), out.unused_points.end(), 0);
    return out;
  }
  mark_inside(cdt);
  std::vector<char> used(points.size(), 0);
  for (Cdt::Face_handle f : cdt.finite_face_handles()) {
    if (!f->info()) continue;
    const std::array<int, 3> t = {f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()};
    for (int v : t) used[v] = 1;
    out.triangles.push_back(t);
  }
  for (size_t i = 0; i < points.size(); ++i)
    if (!used[i]) out.unused_points.push_back(static_cast<int>(i));
  return out;
}

}  // namespace sheetgen
