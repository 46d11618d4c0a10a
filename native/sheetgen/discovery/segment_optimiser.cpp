#include "sheetgen/discovery/segment_optimiser.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <string>

#include "sheetgen/env/environment.hpp"
#include "sheetgen/part/flat_pattern.hpp"
#include "sheetgen/part/validity.hpp"

namespace sheetgen {

double SegmentWork::length() const {
  double s = 0;
  for (int i = first; i < flange; ++i) s += part.tabs[i].params.l;
  return s;
}

double SegmentWork::area() const {
  double s = 0;
  for (int i = first; i <= flange; ++i) s += part.tabs[i].params.w * part.tabs[i].params.l;
  return s;
}

bool segment_valid(const SegmentWork& work, const Environment& env, const SheetSpec& spec) {
  const RealisedPart rp = realise(work.part);
  return check_validity(work.part, rp, spec, env).valid() && unfolds_cleanly(work.part, spec);
}

namespace {

// The free variables of the contraction: (tab, 0 = l / 1 = theta3).
struct Var {
  int tab;
  int kind;
};

std::vector<Var> contraction_vars(const SegmentWork& w) {
  std::vector<Var> v;
  const int last = w.flange - 1;
  for (int i = w.first; i <= last; ++i) {
    if (i < last) v.push_back({i, 0});
    if (!is_flat_extension(w.part.tabs[i].params)) v.push_back({i, 1});  // a flat extension stays flat
  }
  return v;
}

// Sets the variables and re-attaches; false when a limit or the attachment fails.
bool apply_vars(SegmentWork& w, const std::vector<Var>& vars, const std::vector<double>& q, const SheetSpec& spec) {
  const Manufacturing& m = spec.manufacturing;
  for (size_t k = 0; k < vars.size(); ++k) {
    TabParameters& p = w.part.tabs[vars[k].tab].params;
    if (vars[k].kind == 0) {
      if (q[k] < m.min_tab_length || q[k] > m.max_tab_length) return false;
      p.l = q[k];
    } else {
      const double a = std::abs(q[k]);
      if (a < m.min_bend_angle || a > m.max_bend_angle) return false;
      p.theta3 = q[k];
    }
  }
  const double prev = w.part.tabs[w.flange].params.theta3;
  return attach_flange(w.part, w.flange - 1, w.plane, spec, w.flange, prev) == w.flange;
}

std::vector<double> read_vars(const SegmentWork& w, const std::vector<Var>& vars) {
  std::vector<double> q(vars.size());
  for (size_t k = 0; k < vars.size(); ++k) {
    const TabParameters& p = w.part.tabs[vars[k].tab].params;
    q[k] = vars[k].kind == 0 ? p.l : p.theta3;
  }
  return q;
}

}  // namespace

ContractResult contract_segment(SegmentWork& work, const Environment& env, const SheetSpec& spec,
                                const ContractOptions& o) {
  ContractResult r;
  r.length_before = r.length_after = work.length();
  const std::vector<Var> vars = contraction_vars(work);
  std::vector<double> scale(vars.size());
  for (size_t k = 0; k < vars.size(); ++k) scale[k] = vars[k].kind == 0 ? 1.0 : o.angle_scale;
  double step = o.step;
  double energy = work.length();
  // A raw state that does not unfold (reliefs, flat overlaps) may still contract; widening can repair it.
  const bool check_unfold = o.check_unfold && segment_valid(work, env, spec);
  int attempts = 0;
  while (attempts < o.max_steps && step >= o.min_step) {
    ++attempts;
    const std::vector<double> q = read_vars(work, vars);
    // Gradient of the summed length through the attachment, in scaled variables.
    std::vector<double> g(vars.size(), 0.0);
    double gnorm = 0;
    for (size_t k = 0; k < vars.size(); ++k) {
      SegmentWork probe = work;
      std::vector<double> qp = q;
      const double h = o.finite_difference / scale[k];
      // step towards the interior of the limits so the probe is evaluable
      const double dir = (vars[k].kind == 0 || q[k] > 0) ? -1.0 : 1.0;
      qp[k] += dir * h;
      if (!apply_vars(probe, vars, qp, spec)) continue;
      g[k] = (probe.length() - energy) / (dir * o.finite_difference);  // per scaled unit
      gnorm = std::max(gnorm, std::abs(g[k]));
    }
    if (gnorm < 1e-9) { r.converged = true; break; }
    bool accepted = false;
    while (step >= o.min_step) {
      std::vector<double> qn = q;
      for (size_t k = 0; k < vars.size(); ++k) qn[k] -= step * g[k] / gnorm / scale[k];
      SegmentWork next = work;
      if (apply_vars(next, vars, qn, spec)) {
        const double e = next.length();
        if (e < energy - 1e-9) {
          const bool ok = check_unfold ? segment_valid(next, env, spec)
                                       : check_validity(next.part, realise(next.part), spec, env).valid();
          if (ok) {
            work = std::move(next);
            energy = e;
            accepted = true;
            break;
          }
        }
      }
      step *= 0.5;
    }
    if (!accepted) { r.converged = true; break; }
    ++r.steps;
    r.lengths.push_back(energy);
    if (o.record_states) r.states.push_back(work.part);
    step = std::min(std::max(o.step, o.max_step), step * 1.5);
  }
  r.length_after = work.length();
  return r;
}

namespace {

// Whether a shortcut may replace the segment. Shortcuts of a raw state that
// does not unfold need only be valid in 3D (widening may repair the unfold).
struct Acceptance {
  const Environment& env;
  const SheetSpec& spec;
  bool check_unfold;
  bool operator()(const SegmentWork& w) const {
    return check_unfold ? segment_valid(w, env, spec) : check_validity(w.part, realise(w.part), spec, env).valid();
  }
};

// theta3 samples: both signs on [min, max] bend angle (and 0 where flat extensions are allowed).
std::vector<double> bend_samples(const Manufacturing& m, int samples) {
  std::vector<double> bends;
  const int nb = std::max(2, samples);
  for (int k = 0; k < nb; ++k) {
    const double a = m.min_bend_angle + (m.max_bend_angle - m.min_bend_angle) * (k + 0.5) / nb;
    bends.push_back(a);
    bends.push_back(-a);
  }
  if (m.flat_extensions) bends.push_back(0.0);
  return bends;
}

// theta2 samples on [-skew/2, skew/2].
std::vector<double> skew_samples(const Manufacturing& m, int samples) {
  std::vector<double> skews;
  const int ns = std::max(1, samples);
  for (int k = 0; k < ns; ++k) skews.push_back(ns == 1 ? 0.0 : -0.5 * m.max_skew + m.max_skew * k / (ns - 1));
  return skews;
}

// One re-aim: tab k gets (theta2, theta3) and is aimed at the plane; when
// pre_theta3 is a number the tab before it (k's parent) first gets (pre_theta3, pre_l).
struct ReAim {
  double length;  // m, of the segment re-aimed this way
  double theta2, theta3, pre_theta3, pre_l;
  int solution;   // which of attach_flange's two solutions
};

bool build_reaim(const SegmentWork& cut, int k, const ReAim& op, const SheetSpec& spec, SegmentWork& out) {
  out = cut;
  if (k > cut.first) {
    TabParameters& q = out.part.tabs[k - 1].params;
    q.theta3 = op.pre_theta3;
    q.l = op.pre_l;
  }
  TabParameters& p = out.part.tabs[k].params;
  p.theta2 = op.theta2;
  p.theta3 = op.theta3;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  return attach_flange(out.part, k, out.plane, spec, out.flange, nan, op.solution == 1) == out.flange;
}

// The segment truncated after tab k, the flange hung on k's far edge.
SegmentWork truncated_after(const SegmentWork& work, int k) {
  SegmentWork cut;
  cut.plane = work.plane;
  cut.first = work.first;
  cut.part.load = work.part.load;
  cut.part.base = work.part.base;
  cut.part.tabs.assign(work.part.tabs.begin(), work.part.tabs.begin() + k + 1);
  Tab fl = work.part.tabs[work.flange];
  fl.parent = k;
  fl.parent_edge = kFarEdge;
  cut.part.tabs.push_back(fl);
  cut.flange = k + 1;
  return cut;
}

// The values each re-aim variable of tab k (and of its parent inside the segment) is tried at.
struct ReAimSamples {
  std::vector<double> theta2, theta3, pre_theta3, pre_l;
};

ReAimSamples reaim_samples(const SegmentWork& cut, int k, const std::vector<double>& bends, const std::vector<double>& skews,
                           const Manufacturing& m) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const TabParameters orig = cut.part.tabs[k].params;
  ReAimSamples s{{orig.theta2}, bends, {nan}, {nan}};
  s.theta3.push_back(orig.theta3);
  if (k == cut.first) {
    s.theta2.insert(s.theta2.end(), skews.begin(), skews.end());
  } else {
    const TabParameters& q = cut.part.tabs[k - 1].params;
    s.pre_theta3 = bends;
    s.pre_theta3.push_back(q.theta3);
    s.pre_l = {q.l};
    for (double f : {0.25, 0.5, 0.75}) s.pre_l.push_back(std::max(m.min_tab_length, f * q.l));
    if (q.l < m.max_tab_length) s.pre_l.push_back(std::min(m.max_tab_length, std::max(1.5 * q.l, m.min_tab_length)));
  }
  return s;
}

// Every re-aim that attaches and is shorter than best_length, shortest first
// (`prefix`: m, the kept tabs before k - 1).
std::vector<ReAim> candidate_reaims(const SegmentWork& cut, int k, const ReAimSamples& s, double prefix, double best_length,
                                    const SheetSpec& spec) {
  std::vector<ReAim> options;
  SegmentWork trial;
  for (double a : s.pre_theta3)
    for (double pl : s.pre_l)
      for (double t2 : s.theta2)
        for (double t3 : s.theta3)
          for (int sol = 0; sol < 2; ++sol) {
            ReAim op{0, t2, t3, a, pl, sol};
            if (!build_reaim(cut, k, op, spec, trial)) continue;
            op.length = prefix + trial.part.tabs[k].params.l + (k > cut.first ? pl : 0.0);
            if (op.length < best_length) options.push_back(op);
          }
  std::stable_sort(options.begin(), options.end(), [](const ReAim& a, const ReAim& b) { return a.length < b.length; });
  return options;
}

struct Shortcut {
  SegmentWork work;
  double length = 0;  // m
};

// The first acceptable candidate is the shortest: they come sorted. At most
// max_checks full validity checks.
std::optional<Shortcut> first_acceptable(const SegmentWork& cut, int k, const std::vector<ReAim>& options, double best_length,
                                         const Acceptance& acceptable, const SheetSpec& spec, int max_checks) {
  int checks = 0;
  SegmentWork trial;
  for (const ReAim& op : options) {
    if (checks >= max_checks || op.length >= best_length) break;
    build_reaim(cut, k, op, spec, trial);
    ++checks;
    if (!acceptable(trial)) continue;
    return Shortcut{trial, op.length};
  }
  return std::nullopt;
}

}  // namespace

ShortcutResult shortcut_segment(SegmentWork& work, const Environment& env, const SheetSpec& spec,
                                const ShortcutOptions& o) {
  ShortcutResult r;
  r.length_before = r.length_after = work.length();
  if (!o.enabled || work.flange != work.part.size() - 1 || work.feeler_count() < 1) return r;
  const Manufacturing& m = spec.manufacturing;
  const Acceptance acceptable{env, spec, segment_valid(work, env, spec)};
  const std::vector<double> bends = bend_samples(m, o.bend_samples);
  const std::vector<double> skews = skew_samples(m, o.skew_samples);
  SegmentWork best;
  double best_length = o.max_length_ratio * work.length();
  bool found = false;
  for (int k = work.first; k < work.flange && k <= work.first + o.max_depth; ++k) {
    const SegmentWork cut = truncated_after(work, k);
    double prefix = 0;  // lengths of the kept tabs before k - 1
    for (int i = work.first; i < k - 1; ++i) prefix += work.part.tabs[i].params.l;
    if (prefix >= best_length) break;
    const ReAimSamples samples = reaim_samples(cut, k, bends, skews, m);
    const std::vector<ReAim> options = candidate_reaims(cut, k, samples, prefix, best_length, spec);
    std::optional<Shortcut> s = first_acceptable(cut, k, options, best_length, acceptable, spec, o.max_checks);
    if (!s) continue;
    best = std::move(s->work);
    best_length = s->length;
    found = true;
  }
  if (found) {
    r.removed_tabs = work.feeler_count() - best.feeler_count();
    work = std::move(best);
  }
  r.length_after = work.length();
  return r;
}

Part remove_tab_reparent(const Part& part, int j) {
  const RealisedPart rp = realise(part);
  Part out;
  out.load = part.load;
  out.base = part.base;
  const int pj = part.tabs[j].parent;
  for (int i = 0; i < part.size(); ++i) {
    if (i == j) continue;
    Tab t = part.tabs[i];
    if (t.parent == j) {
      // keep the root start P0 where it was, on the same edge index of j's parent
      const Vec3 p0 = rp.tabs[i].origin;
      const auto& c = rp.tabs[pj].corners;
      const int e = t.parent_edge;
      const Vec3 a = c[e], b = c[(e + 1) % c.size()];
      t.parent = pj;
      t.params.d = std::max(0.0, (p0 - a).dot((b - a).normalized()));
    }
    if (t.parent > j) --t.parent;
    out.tabs.push_back(t);
  }
  return out;
}

int merge_coplanar(SegmentWork& work, const Environment& env, const SheetSpec& spec, const MergeOptions& o) {
  // 1.5 x the smallest bend, but never a real bend: in right-angle mode (min 89.5 deg) only
  // flat extensions merge.
  const double max_angle =
      o.max_angle >= 0 ? o.max_angle : std::min(1.5 * spec.manufacturing.min_bend_angle, 10.0 * M_PI / 180.0);
  int merges = 0;
  for (int j = work.first + 1; j < work.flange; ++j) {
    const Tab& tj = work.part.tabs[j];
    if (std::abs(tj.params.theta3) > max_angle || tj.parent_edge != kFarEdge) continue;
    const int i = tj.parent;
    SegmentWork next = work;
    // One tab over both: lengths add along the common direction, the far edge is j's.
    TabParameters& pi = next.part.tabs[i].params;
    pi.l += tj.params.l * std::cos(tj.params.theta3);
    pi.theta1 = tj.params.theta1;
    next.part = remove_tab_reparent(next.part, j);
    next.flange -= 1;
    const double before = work.length();
    const double prev = next.part.tabs[next.flange].params.theta3;
    if (attach_flange(next.part, next.flange - 1, next.plane, spec, next.flange, prev) != next.flange) continue;
    if (next.length() > before * (1 + o.max_length_growth)) continue;
    if (!segment_valid(next, env, spec)) continue;
    work = std::move(next);
    ++merges;
    --j;  // the tab now at j is the old j + 1
  }
  return merges;
}

WidenResult widen_segment(SegmentWork& work, const Environment& env, const SheetSpec& spec, const WidenOptions& o) {
  WidenResult r;
  r.area_before = work.area();
  const SegmentWork original = work;
  for (int i = work.first; i <= work.flange; ++i) {
    double step = o.initial_step;
    while (step >= o.min_step) {
      bool accepted = false;
      for (int variant = 0; variant < 3 && !accepted; ++variant) {
        SegmentWork next = work;
        const RealisedPart rp = realise(next.part);
        Tab& tab = next.part.tabs[i];
        TabParameters& p = tab.params;
        const auto& pc = rp.tabs[tab.parent].corners;
        const int e = tab.parent_edge;
        const double edge_len = (pc[(e + 1) % pc.size()] - pc[e]).norm();
        // The flat root slides by -dL tan(theta2) along the parent edge (docs/manufacturing.md).
        const double shift = -bend_length_change(p.theta3, spec) * std::tan(p.theta2);
        const double lo = std::max(0.0, -shift) + 1e-9, hi = edge_len - std::max(0.0, shift) - 1e-9;
        double d = p.d, end = p.d + p.w;
        if (variant == 0) { d -= step; end += step; }
        else if (variant == 1) end += step;
        else d -= step;
        d = std::max(d, std::min(lo, p.d));
        end = std::min(end, std::max(hi, p.d + p.w));
        if (d >= p.d - 1e-12 && end <= p.d + p.w + 1e-12) continue;  // no room on that side
        // children keep their root start in the world
        std::vector<std::pair<int, Vec3>> kids;
        for (int c = i + 1; c < next.part.size(); ++c)
          if (next.part.tabs[c].parent == i) kids.push_back({c, rp.tabs[c].origin});
        p.d = d;
        p.w = end - d;
        RealisedPart rn = realise(next.part);
        for (const auto& [c, p0] : kids) {
          const Tab& ct = next.part.tabs[c];
          const auto& cc = rn.tabs[i].corners;
          const Vec3 a = cc[ct.parent_edge], b = cc[(ct.parent_edge + 1) % cc.size()];
          next.part.tabs[c].params.d = std::max(0.0, (p0 - a).dot((b - a).normalized()));
        }
        // The last feeler carries the flange on its far edge: re-attach so the far edge stays
        // at t/2 from the rivet plane (d moves the root along an edge that need not be parallel
        // to the plane) and the flange spans the whole widened far edge (no relief needed).
        const bool carries_flange = i == work.flange - 1 && next.part.tabs[work.flange].parent == i &&
                                    next.part.tabs[work.flange].parent_edge == kFarEdge;
        if (carries_flange && o.reattach_flange) {
          const double prev = next.part.tabs[work.flange].params.theta3;
          if (attach_flange(next.part, i, next.plane, spec, work.flange, prev) != work.flange) continue;
        }
        // Only tab i changed (its children kept their roots): check what involves it, and the unfold.
        ValidityOptions vo;
        vo.only_tab = i;
        bool ok = check_validity(next.part, realise(next.part), spec, env, vo).valid();
        if (ok && carries_flange) {
          vo.only_tab = work.flange;
          ok = check_validity(next.part, realise(next.part), spec, env, vo).valid();
          vo.only_tab = i;
        }
        if (ok) ok = unfolds_cleanly(next.part, spec);
        if (ok) {
          work = std::move(next);
          accepted = true;
          ++r.steps;
        }
      }
      if (!accepted) step *= 0.5;
    }
  }
  // The per-tab checks above are incremental; the whole segment is checked once at the end.
  if (r.steps > 0 && !segment_valid(work, env, spec)) {
    work = original;
    r.steps = 0;
  }
  r.area_after = work.area();
  return r;
}

}  // namespace sheetgen
