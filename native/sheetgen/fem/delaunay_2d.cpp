#include "sheetgen/fem/delaunay_2d.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

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

// Insertion order: a snake over a coarse grid of the points' bounding box
// (about 4 points a cell, alternate rows reversed), so that each point is
// found by a short walk from the one before. CGAL's spatial sort (a Hilbert
// order) does the same job but took 10 % of the mesher's time.
std::vector<int> snake_order(const std::vector<Vec2>& points) {
  Vec2 lo = points[0], hi = points[0];
  for (const Vec2& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double size = std::max((hi - lo).maxCoeff(), 1e-300);
  const int cells = std::max(1, static_cast<int>(std::sqrt(points.size() / 4.0)));
  std::vector<long long> key(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const int cy = std::min(cells - 1, static_cast<int>((points[i].y() - lo.y()) / size * cells));
    int cx = std::min(cells - 1, static_cast<int>((points[i].x() - lo.x()) / size * cells));
    if (cy % 2) cx = cells - 1 - cx;
    key[i] = static_cast<long long>(cy) * cells + cx;
  }
  std::vector<int> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key[a] < key[b]; });
  return order;
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
  Cdt cdt;
  std::vector<Cdt::Vertex_handle> vertex(points.size());
  Cdt::Face_handle hint;
  for (int i : snake_order(points)) {
    const size_t before = cdt.number_of_vertices();
    const Cdt::Vertex_handle v = cdt.insert(Kernel::Point_2(points[i].x(), points[i].y()), hint);
    if (cdt.number_of_vertices() == before)  // CGAL returned the vertex already there
      throw FemError("point " + std::to_string(std::max(i, v->info())),
                     "duplicates point " + std::to_string(std::min(i, v->info())));
    v->info() = i;
    vertex[i] = v;
    hint = v->face();
  }
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
