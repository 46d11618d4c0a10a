#include "sheetgen/fem/delaunay_2d.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "sheetgen/fem/fem_error.hpp"

namespace sheetgen {
namespace {

struct Tri {
  int v[3];  // counter-clockwise
  int n[3];  // neighbour across the edge opposite v[i], -1 on the outside
  bool alive;
};

double orient(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// > 0 when d lies inside the circumcircle of the counter-clockwise (a, b, c).
double incircle(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double adx = a.x() - d.x(), ady = a.y() - d.y();
  const double bdx = b.x() - d.x(), bdy = b.y() - d.y();
  const double cdx = c.x() - d.x(), cdy = c.y() - d.y();
  const double ad = adx * adx + ady * ady, bd = bdx * bdx + bdy * bdy, cd = cdx * cdx + cdy * cdy;
  return adx * (bdy * cd - bd * cdy) - ady * (bdx * cd - bd * cdx) + ad * (bdx * cdy - bdy * cdx);
}

}  // namespace

std::vector<std::array<int, 3>> delaunay_triangulation(const std::vector<Vec2>& input) {
  const int n = static_cast<int>(input.size());
  if (n < 3) return {};
  // Normalise to a unit box for conditioning.
  Vec2 lo = input[0], hi = input[0];
  for (const Vec2& p : input) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec2 centre = 0.5 * (lo + hi);
  const double scale = std::max((hi - lo).maxCoeff(), 1e-300);
  std::vector<Vec2> p(n + 3);
  for (int i = 0; i < n; ++i) p[i] = (input[i] - centre) / scale;
  // Super triangle far outside the unit box.
  p[n] = Vec2(-1e3, -1e3);
  p[n + 1] = Vec2(1e3, -1e3);
  p[n + 2] = Vec2(0, 1e3);

  // Insert in a snake order over a coarse grid so the walk from the last new
  // triangle is short.
  const int cells = std::max(1, static_cast<int>(std::sqrt(n / 4.0)));
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  auto cell_key = [&](int i) {
    const int cy = std::min(cells - 1, static_cast<int>((p[i].y() + 0.5) * cells));
    int cx = std::min(cells - 1, static_cast<int>((p[i].x() + 0.5) * cells));
    if (cy % 2) cx = cells - 1 - cx;
    return static_cast<long long>(cy) * cells + cx;
  };
  std::vector<long long> keys(n);
  for (int i = 0; i < n; ++i) keys[i] = cell_key(i);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return keys[a] < keys[b]; });

  std::vector<Tri> tris;
  tris.reserve(2 * static_cast<size_t>(n) + 8);
  tris.push_back(Tri{{n, n + 1, n + 2}, {-1, -1, -1}, true});
  std::vector<int> free_slots;
  std::vector<int> mark;  // visit stamp per triangle
  int stamp = 0;
  int last = 0;
  struct BoundaryEdge {
    int a, b, outside;
  };
  std::vector<int> cavity, stack;
  std::vector<BoundaryEdge> boundary;
  std::vector<int> created;

  for (int pi : order) {
    const Vec2& q = p[pi];
    // Walk to the triangle containing q. The edge tried first rotates with
    // the step: a walk that always tries edges in the same order can cycle
    // (it is only guaranteed to end on a Delaunay triangulation with exact
    // predicates, and ours are floating point; seen on a real part, where
    // every step had a way on and the walk came back). Should it still not
    // end, the triangle that holds q best is found by a scan of all of them.
    int t = last;
    const int max_steps = 4 * static_cast<int>(tris.size()) + 16;
    for (int steps = 0;; ++steps) {
      if (steps > max_steps) {
        double best = -std::numeric_limits<double>::infinity();
        for (int c = 0; c < static_cast<int>(tris.size()); ++c) {
          if (!tris[c].alive) continue;
          double worst = std::numeric_limits<double>::infinity();
          for (int i = 0; i < 3; ++i) worst = std::min(worst, orient(p[tris[c].v[(i + 1) % 3]], p[tris[c].v[(i + 2) % 3]], q));
          if (worst > best) best = worst, t = c;
        }
        break;
      }
      const Tri& T = tris[t];
      int next = -1;
      for (int k = 0; k < 3; ++k) {
        const int i = (k + steps) % 3;
        if (orient(p[T.v[(i + 1) % 3]], p[T.v[(i + 2) % 3]], q) < 0) {
          next = T.n[i];
          break;
        }
      }
      if (next < 0) break;
      t = next;
    }
    // Cavity: triangles whose circumcircle holds q, grown from t.
    ++stamp;
    mark.resize(tris.size(), 0);
    cavity.clear();
    boundary.clear();
    stack.assign(1, t);
    mark[t] = stamp;
    while (!stack.empty()) {
      const int c = stack.back();
      stack.pop_back();
      cavity.push_back(c);
      for (int i = 0; i < 3; ++i) {
        const int nb = tris[c].n[i];
        const int a = tris[c].v[(i + 1) % 3], b = tris[c].v[(i + 2) % 3];
        if (nb >= 0 && mark[nb] == stamp) continue;
        if (nb >= 0 && incircle(p[tris[nb].v[0]], p[tris[nb].v[1]], p[tris[nb].v[2]], q) > 0) {
          mark[nb] = stamp;
          stack.push_back(nb);
        } else {
          boundary.push_back({a, b, nb});
        }
      }
    }
    for (const BoundaryEdge& e : boundary)
      if (orient(p[e.a], p[e.b], q) <= 0)
        throw FemError("mesher", "Delaunay cavity is not star-shaped (duplicate or nearly coincident points)");
    for (int c : cavity) {
      tris[c].alive = false;
      free_slots.push_back(c);
    }
    // Fan the cavity boundary to q.
    created.clear();
    for (const BoundaryEdge& e : boundary) {
      int id;
      if (!free_slots.empty()) {
        id = free_slots.back();
        free_slots.pop_back();
      } else {
        id = static_cast<int>(tris.size());
        tris.push_back(Tri{});
      }
      tris[id] = Tri{{e.a, e.b, pi}, {-1, -1, e.outside}, true};
      // Re-point the outside neighbour by the shared edge, not by the old id:
      // a freed slot may already hold one of the new triangles.
      if (e.outside >= 0)
        for (int j = 0; j < 3; ++j)
          if (tris[e.outside].v[j] != e.a && tris[e.outside].v[j] != e.b) tris[e.outside].n[j] = id;
      created.push_back(id);
    }
    // Link the new triangles to each other: the edge (b, q) of the triangle on
    // boundary edge (a, b) is shared with the triangle on edge (b, c).
    for (int x : created)
      for (int y : created) {
        if (x == y) continue;
        if (tris[x].v[1] == tris[y].v[0]) {  // x = (a, b, q), y = (b, c, q)
          tris[x].n[0] = y;                  // opposite a: edge (b, q)
          tris[y].n[1] = x;                  // opposite b: edge (q, b)
        }
      }
    last = created.front();
    if (mark.size() < tris.size()) mark.resize(tris.size(), 0);
  }

  std::vector<std::array<int, 3>> out;
  out.reserve(2 * static_cast<size_t>(n));
  for (const Tri& T : tris)
    if (T.alive && T.v[0] < n && T.v[1] < n && T.v[2] < n) out.push_back({T.v[0], T.v[1], T.v[2]});
  return out;
}

}  // namespace sheetgen
