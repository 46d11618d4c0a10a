#pragma once
// Structured meshes for the closed-form FEM tests: a parallelogram patch
// p0 + s u + t v split into right/left-leaning triangle pairs, with nodes
// merged across patches (so an L-bracket is two patches sharing the fold).
#include <cmath>
#include <map>
#include <tuple>
#include <vector>

#include "sheetgen/fem/shell_model.hpp"

namespace sheetgen::test {

class GridBuilder {
 public:
  explicit GridBuilder(ShellModel& model, double merge_tol = 1e-9) : model_(model), tol_(merge_tol) {}

  int node(const Vec3& p) {
    const auto k = std::make_tuple(std::llround(p.x() / tol_), std::llround(p.y() / tol_), std::llround(p.z() / tol_));
    auto it = index_.find(k);
    if (it != index_.end()) return it->second;
    const int i = model_.add_node(p);
    index_.emplace(k, i);
    return i;
  }

  // Mesh of p(s, t) for s, t in [0, 1] with ns x nt cells, two triangles per
  // cell, diagonals alternating ("union jack" free, but not all one way, so the
  // mesh has no preferred direction). Returns the node grid [i][j].
  template <class F>
  std::vector<std::vector<int>> patch(F&& p, int ns, int nt, bool alternate = true) {
    std::vector<std::vector<int>> g(ns + 1, std::vector<int>(nt + 1));
    for (int i = 0; i <= ns; ++i)
      for (int j = 0; j <= nt; ++j) g[i][j] = node(p(double(i) / ns, double(j) / nt));
    for (int i = 0; i < ns; ++i)
      for (int j = 0; j < nt; ++j) {
        const int a = g[i][j], b = g[i + 1][j], c = g[i + 1][j + 1], d = g[i][j + 1];
        if (!alternate || (i + j) % 2 == 0) {
          model_.triangles.push_back({a, b, c});
          model_.triangles.push_back({a, c, d});
        } else {
          model_.triangles.push_back({a, b, d});
          model_.triangles.push_back({b, c, d});
        }
      }
    return g;
  }

  std::vector<std::vector<int>> flat(const Vec3& p0, const Vec3& u, const Vec3& v, int ns, int nt,
                                     bool alternate = true) {
    return patch([&](double s, double t) { return Vec3(p0 + s * u + t * v); }, ns, nt, alternate);
  }

 private:
  ShellModel& model_;
  double tol_;
  std::map<std::tuple<long long, long long, long long>, int> index_;
};

}  // namespace sheetgen::test
