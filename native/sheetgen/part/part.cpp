#include "sheetgen/part/part.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

namespace sheetgen {

int Part::add_tab(int parent, int parent_edge, const TabParameters& params, int rivet_area) {
  if (parent < 0 || parent >= size())
    throw std::invalid_argument("Part::add_tab: parent " + std::to_string(parent) + " is not an existing tab (0.." +
                                std::to_string(size() - 1) + ")");
  if (!is_free_edge(parent, parent_edge))
    throw std::invalid_argument("Part::add_tab: edge " + std::to_string(parent_edge) + " of tab " + std::to_string(parent) +
                                " is not a free edge");
  Tab t;
  t.parent = parent;
  t.parent_edge = parent_edge;
  t.params = params;
  t.rivet_area = rivet_area;
  tabs.push_back(t);
  return size() - 1;
}

std::vector<int> Part::children(int i) const {
  std::vector<int> out;
  for (int j = i + 1; j < size(); ++j)
    if (tabs[j].parent == i) out.push_back(j);
  return out;
}

int Part::bend_count() const {
  int n = 0;
  for (int i = 1; i < size(); ++i) n += is_flat_extension(tabs[i].params) ? 0 : 1;
  return n;
}

int Part::depth(int i) const {
  int d = 0;
  while (i > 0 && i < size() && d <= size()) {  // bounded even for a hand-edited cyclic tree
    i = tabs[i].parent;
    ++d;
  }
  return d;
}

Part make_base_part(const std::vector<Vec3>& polygon, const Vec3& normal_in, int load_index) {
  if (polygon.size() < 3) throw std::invalid_argument("make_base_part: the base polygon needs at least 3 corners");
  const Vec3 n = normal_in.normalized();
  const Vec3 e0 = polygon[1] - polygon[0];
  if (!(e0.norm() > 0) || !(n.norm() > 0)) throw std::invalid_argument("make_base_part: degenerate base polygon");
  Part part;
  part.load = load_index;
  part.base.origin = polygon[0];
  part.base.x_axis = (e0 - e0.dot(n) * n).normalized();
  part.base.y_axis = n.cross(part.base.x_axis);
  const double scale = e0.norm();
  for (const Vec3& p : polygon) {
    const Vec3 r = p - polygon[0];
    if (std::abs(r.dot(n)) > 1e-9 * std::max(1.0, scale))
      throw std::invalid_argument("make_base_part: the base polygon is not planar");
    part.base.outline.emplace_back(r.dot(part.base.x_axis), r.dot(part.base.y_axis));
  }
  const auto& o = part.base.outline;
  const size_t m = o.size();
  for (size_t i = 0; i < m; ++i) {
    const Vec2 a = o[(i + 1) % m] - o[i], b = o[(i + 2) % m] - o[(i + 1) % m];
    if (a.x() * b.y() - a.y() * b.x() <= 0)
      throw std::invalid_argument("make_base_part: the base polygon must be strictly convex and counter-clockwise about its normal");
  }
  Tab base;
  part.tabs.push_back(base);
  return part;
}

Part make_base_part(const Load& load, int load_index, double thickness) {
  const auto bottom = load.bottom_face();  // counter-clockwise seen from below
  const Vec3 up = load.rotation * Vec3::UnitZ();
  // Corners (-x,-y), (+x,-y), (+x,+y), (-x,+y) in the load frame: counter-clockwise
  // about +z (the top side faces the load); edge 0 is the -y side, edge 1 the +x side.
  std::vector<Vec3> poly = {bottom[0], bottom[3], bottom[2], bottom[1]};
  for (Vec3& p : poly) p -= 0.5 * thickness * up;
  return make_base_part(poly, up, load_index);
}

SheetSpec SheetSpec::from(const Problem& problem) {
  SheetSpec s;
  s.thickness = problem.material.thickness;
  s.clearance = problem.requirements.clearance;
  s.manufacturing = problem.manufacturing;
  return s;
}

double bend_setback(double theta, const SheetSpec& s) {
  return std::tan(0.5 * std::abs(theta)) * (s.manufacturing.bend_radius + 0.5 * s.thickness);
}

double bend_allowance(double theta, const SheetSpec& s) {
  return std::abs(theta) * (s.manufacturing.bend_radius + s.manufacturing.k_factor * s.thickness);
}

double bend_length_change(double theta, const SheetSpec& s) { return bend_allowance(theta, s) - 2.0 * bend_setback(theta, s); }

double bend_zone_depth(double theta, const SheetSpec& s) {
  return std::max(s.manufacturing.bend_radius + s.thickness, bend_setback(theta, s) + 0.5 * s.thickness);
}

}  // namespace sheetgen
