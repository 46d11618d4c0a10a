#include "sheetgen/part/bend_sequence.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_set>
#include <utility>

#include "sheetgen/core/polygon_geometry.hpp"
#include "sheetgen/part/clear_states.hpp"

namespace sheetgen {

namespace {

class Simulator {
 public:
  Simulator(const Part& part, const SheetSpec& spec, const BendSequenceOptions& o)
      : part_(part), o_(o), need_(spec.thickness + o.gap), n_(part.size()) {
    ro_.angles.assign(n_, 0.0);
    subtree_.assign(n_, std::vector<char>(n_, 0));
    for (int i = n_ - 1; i >= 0; --i) {
      subtree_[i][i] = 1;
      for (int c : part.children(i))
        for (int k = 0; k < n_; ++k)
          if (subtree_[c][k]) subtree_[i][k] = 1;
    }
  }

  // Collision among all non-adjacent pairs in the current state.
  bool state_clear(BendCollision& hit) {
    realise_into(part_, rp_, ro_);
    for (int a = 0; a < n_; ++a)
      for (int b = a + 1; b < n_; ++b)
        if (!pair_clear(a, b, hit)) return false;
    return true;
  }

  // Sweeps bend k from 0 to its angle with the current other angles.
  //
  // Conservative advancement: only the subtree of k moves, turning about k's
  // bend line by `step` per state, so a point at distance r from that line
  // moves at most r * step. A pair found d >= need apart stays clear for the
  // next (d - need) / (r * step) states, which are not looked at (nor, when
  // every pair is clear, realised). Only states provably clear are skipped,
  // so the first collision found is the one checking every state finds.
  bool sweep(int k, BendCollision& hit) {
    const double target = part_.tabs[k].params.theta3;
    const int steps = std::max(1, static_cast<int>(std::ceil(std::abs(target) / o_.max_step)));
    const double step = std::abs(target) / steps;
    clear_until_.assign(static_cast<size_t>(n_) * n_, 0);
    radius_.clear();
    for (int s = 1; s <= steps; ++s) {
      bool realised = false;
      for (int a = 0; a < n_; ++a) {
        if (!subtree_[k][a]) continue;
        for (int b = 0; b < n_; ++b) {
          if (subtree_[k][b]) continue;
          int& until = clear_until_[a * n_ + b];
          if (until >= s) continue;
          if (!realised) {
            set_state(k, target * s / steps, s == 1);
            realised = true;
            if (radius_.empty()) set_radii(k);
          }
          double apart = 0;
          if (!pair_clear(a, b, hit, &apart)) {
            hit.bend_tab = k;
            hit.fraction = static_cast<double>(s) / steps;
            hit.angle = ro_.angles[k];
            ro_.angles[k] = 0;
            return false;
          }
          if (o_.skip_clear_states) until = s + clear_states(apart - need_, radius_[a] * step, steps);
        }
      }
    }
    ro_.angles[k] = target * steps / steps;  // where the last state left it, skipped or not
    return true;
  }

  void set_angle(int k, double a) { ro_.angles[k] = a; }

 private:
  // Whether tabs a and b are clear of each other in rp_; when they are,
  // `apart` (m) is a lower bound on their distance (infinite for pairs that
  // may touch by design).
  bool pair_clear(int a, int b, BendCollision& hit, double* apart = nullptr) const {
    double unused = 0;
    double& d = apart ? *apart : unused;
    d = std::numeric_limits<double>::infinity();
    if (part_.tabs[a].parent == b || part_.tabs[b].parent == a) return true;
    // A self-rivet pair closes onto itself at the end of its bends by design.
    if (part_.tabs[a].riveted_to == b || part_.tabs[b].riveted_to == a) return true;
    const RealisedTab& ta = rp_.tabs[a];
    const RealisedTab& tb = rp_.tabs[b];
    d = box_gap(ta.box, tb.box);
    if (d >= need_) return true;
    d = convex_polygon_distance(ta.corners, ta.normal, tb.corners, tb.normal, need_);
    if (d >= need_) return true;
    hit.tab_a = a;
    hit.tab_b = b;
    hit.distance = d;
    return false;
  }

  // rp_ with bend k at `angle`. Checking every state realises each anew;
  // otherwise only k's subtree moves, turned about k's bend line from the
  // state the sweep started in (`first`: the sweep's first state): the
  // corners realise_into gives, to rounding, at a fraction of the cost.
  void set_state(int k, double angle, bool first) {
    ro_.angles[k] = angle;
    if (!o_.skip_clear_states) {
      realise_into(part_, rp_, ro_);
      return;
    }
    if (first) {
      ro_.angles[k] = 0;
      realise_into(part_, start_, ro_);
      ro_.angles[k] = angle;
      rp_ = start_;
    }
    // The child turns by -angle about its bend line (realise_into: its
    // direction away from the line is cos * o + sin * n, o = e x n).
    const Vec3 o = start_.tabs[k].origin, e = start_.tabs[k].x_axis;
    const double c = std::cos(-angle), sn = std::sin(-angle);
    auto turn = [&](const Vec3& v) { return Vec3(c * v + sn * e.cross(v) + (1 - c) * e.dot(v) * e); };
    for (int a = 0; a < n_; ++a) {
      if (!subtree_[k][a]) continue;
      const RealisedTab& from = start_.tabs[a];
      RealisedTab& to = rp_.tabs[a];
      to.box = BoundingBox();
      for (size_t j = 0; j < from.corners.size(); ++j) to.box.extend(to.corners[j] = o + turn(from.corners[j] - o));
      to.normal = turn(from.normal);
    }
  }

  // radius_[a]: how far the farthest corner of each tab of k's subtree is from
  // k's bend line (turning about the line keeps it).
  void set_radii(int k) {
    const Vec3 o = rp_.tabs[k].origin, e = rp_.tabs[k].x_axis;
    radius_.assign(n_, 0.0);
    for (int a = 0; a < n_; ++a) {
      if (!subtree_[k][a]) continue;
      for (const Vec3& v : rp_.tabs[a].corners) {
        const Vec3 r = v - o;
        radius_[a] = std::max(radius_[a], (r - r.dot(e) * e).norm());
      }
    }
  }

  const Part& part_;
  BendSequenceOptions o_;
  double need_;
  int n_;
  RealiseOptions ro_;
  RealisedPart rp_;
  std::vector<std::vector<char>> subtree_;
  std::vector<int> clear_until_;  // per pair (a * n + b): the last state of the sweep known clear
  std::vector<double> radius_;    // m, per tab of the swept subtree (set_radii)
  RealisedPart start_;            // the part as the sweep found it (set_state)
};

std::string describe(const BendCollision& c) {
  char buf[256];
  if (c.bend_tab < 0)
    std::snprintf(buf, sizeof buf, "tabs %d and %d are %.3f mm apart in the flat sheet", c.tab_a, c.tab_b, c.distance * 1e3);
  else
    std::snprintf(buf, sizeof buf, "bending tab %d, at %.1f deg (%.0f %% of its bend) tab %d comes %.3f mm from tab %d",
                  c.bend_tab, c.angle * 180.0 / M_PI, 100.0 * c.fraction, c.tab_a, c.distance * 1e3, c.tab_b);
  return buf;
}

// `r` failed at `hit`: its message is "<what>: <the collision>".
BendSequenceResult failed(BendSequenceResult r, const BendCollision& hit, const std::string& what) {
  r.status = ValidityReason::NoBendSequence;
  r.collision = hit;
  r.message = what + ": " + describe(hit);
  return r;
}

}  // namespace

BendSequenceResult check_bend_order(const Part& part, const std::vector<int>& order, const SheetSpec& spec,
                                    const BendSequenceOptions& o) {
  const int n = part.size();
  std::vector<char> seen(n, 0);
  if (static_cast<int>(order.size()) != part.bend_count())
    throw std::invalid_argument("check_bend_order: the order must list every bent tab once");
  for (int k : order) {
    if (k <= 0 || k >= n || seen[k] || is_flat_extension(part.tabs[k].params))
      throw std::invalid_argument("check_bend_order: bad or repeated tab " + std::to_string(k));
    seen[k] = 1;
  }
  BendSequenceResult r;
  Simulator sim(part, spec, o);
  BendCollision hit;
  if (!sim.state_clear(hit)) return failed(std::move(r), hit, "the flat sheet already collides");
  for (int k : order) {
    ++r.sweeps;
    if (!sim.sweep(k, hit)) return failed(std::move(r), hit, "bend order fails");
    r.order.push_back(k);
  }
  return r;
}

BendSequenceResult plan_bend_sequence(const Part& part, const SheetSpec& spec, const BendSequenceOptions& o) {
  const int n = part.size();
  BendSequenceResult r;
  Simulator sim(part, spec, o);
  BendCollision hit;
  if (!sim.state_clear(hit)) return failed(std::move(r), hit, "no bend sequence");
  std::vector<int> candidates;
  for (int i = 1; i < n; ++i)
    if (!is_flat_extension(part.tabs[i].params)) candidates.push_back(i);  // a flat extension is not bent
  std::stable_sort(candidates.begin(), candidates.end(), [&](int a, int b) { return part.depth(a) < part.depth(b); });
  std::string mask(n, '0');
  std::unordered_set<std::string> dead;
  std::vector<int> order;
  std::vector<BendTooling> tooling;
  BendCollision deepest;
  int deepest_level = -1;
  std::string deepest_press;  // the press brake's reason, when its failure was the deepest
  std::vector<double> done(n, 0.0);
  std::function<bool()> dfs = [&]() -> bool {
    if (order.size() == candidates.size()) return true;
    if (dead.count(mask)) return false;
    for (int k : candidates) {
      if (mask[k] == '1') continue;
      if (r.sweeps >= o.max_sweeps) {
        r.exhausted = true;
        return false;
      }
      ++r.sweeps;
      BendCollision h;
      if (!sim.sweep(k, h)) {
        if (static_cast<int>(order.size()) > deepest_level) {
          deepest_level = static_cast<int>(order.size());
          deepest = h;
          deepest_press.clear();
        }
        continue;
      }
      if (o.tools) {
        const BendToolChoice tools = choose_bend_tools(part, k, done, spec, *o.tools);
        if (!tools.ok) {
          if (static_cast<int>(order.size()) > deepest_level) {
            deepest_level = static_cast<int>(order.size());
            deepest_press = tools.reason;
          }
          sim.set_angle(k, 0.0);
          continue;
        }
        tooling.push_back(tools.tooling);
      }
      done[k] = part.tabs[k].params.theta3;
      sim.set_angle(k, part.tabs[k].params.theta3);
      mask[k] = '1';
      order.push_back(k);
      if (dfs()) return true;
      order.pop_back();
      if (o.tools) tooling.pop_back();
      mask[k] = '0';
      sim.set_angle(k, 0.0);
      done[k] = 0.0;
      if (r.exhausted) return false;
    }
    dead.insert(mask);
    return false;
  };
  if (dfs()) {
    r.order = order;
    r.tooling = tooling;
    return r;
  }
  r.status = ValidityReason::NoBendSequence;
  r.collision = deepest;
  r.message = std::string(r.exhausted ? "no bend sequence found within " : "no bend sequence exists (searched ") +
              std::to_string(r.sweeps) + " sweeps" + (r.exhausted ? "" : ")") + "; deepest failure: " +
              (deepest_press.empty() ? describe(deepest) : deepest_press);
  return r;
}

}  // namespace sheetgen
