#include "sheetgen/discovery/discovery.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <cmath>
#include <map>
#include <stdexcept>
#include <unordered_map>

#include "sheetgen/discovery/bendable.hpp"
#include "sheetgen/env/environment.hpp"
#include "sheetgen/part/validity.hpp"
#include "sheetgen/part/flat_pattern.hpp"

namespace sheetgen {

const char* to_string(EdgePolicy p) {
  switch (p) {
    case EdgePolicy::Ours: return "ours";
    case EdgePolicy::GreedyNearest: return "greedy";
    case EdgePolicy::Uniform: return "uniform";
  }
  return "?";
}
const char* to_string(SegmentPolicy p) {
  switch (p) {
    case SegmentPolicy::Ours: return "ours";
    case SegmentPolicy::Greedy: return "greedy";
    case SegmentPolicy::Uniform: return "uniform";
  }
  return "?";
}

DiscoveryOptions DiscoveryOptions::from(const Problem& problem) {
  DiscoveryOptions o;
  const SearchSettings& s = problem.search;
  o.chains = s.chains;
  o.iterations = s.iterations;
  o.seed = s.seed;
  o.threads = s.threads;
  o.target.alpha = s.alpha;
  o.target.beta = s.beta;
  o.target.scene_unit = s.scene_unit;
  return o;
}

Part remove_subtrees(const Part& part, const std::vector<int>& roots) {
  std::vector<char> gone(part.size(), 0);
  for (int r : roots)
    if (r > 0 && r < part.size()) gone[r] = 1;
  std::vector<int> map(part.size(), -1);
  Part out;
  out.load = part.load;
  out.base = part.base;
  for (int i = 0; i < part.size(); ++i) {
    const int p = part.tabs[i].parent;
    if (i > 0 && gone[p]) gone[i] = 1;
    if (gone[i]) continue;
    map[i] = out.size();
    Tab t = part.tabs[i];
    if (i > 0) t.parent = map[p];
    out.tabs.push_back(t);
  }
  return out;
}

Segment make_segment(const SegmentWork& w) {
  Segment s;
  const RealisedPart rp = realise(w.part);
  for (int i = w.first; i <= w.flange; ++i) {
    Tab t = w.part.tabs[i];
    t.parent = i == w.first ? -1 : t.parent - w.first;
    t.tag = -1;
    s.tabs.push_back(t);
  }
  s.parent_edge = w.part.tabs[w.first].parent_edge;
  s.rivet_area = w.plane.rivet_area;
  s.area = w.area();
  s.length = w.length();
  s.bends = 0;
  for (const Tab& t : s.tabs) s.bends += is_flat_extension(t.params) ? 0 : 1;
  s.root_a = rp.tabs[w.first].bend_start();
  s.root_b = rp.tabs[w.first].bend_end();
  s.connect_a = rp.tabs[w.flange].bend_start();
  s.connect_b = rp.tabs[w.flange].bend_end();
  s.regularisation = regularisation_score(static_cast<int>(s.tabs.size()), s.root_b - s.root_a, s.connect_b - s.connect_a);
  return s;
}

namespace {

constexpr int kFeelerTagBase = -2;  // feeler tag = -2 - uid (frozen tabs: segment id >= 0)

struct Candidate {
  SegmentWork work;        // raw (then optimised) segment inside the chain's frozen part
  Segment segment;         // filled for the library (features, attachment)
  int feeler_tag = 0;      // tag of the path's first feeler tab (its branch is removed when admitted)
  double u = 0;            // admission draw
  bool optimised = false;
};

struct Chain {
  int index = 0;
  ChainRng rng{1};
  Part part;               // [0, frozen) base + frozen segments, then feelers
  int frozen = 1;
  RealisedPart realised;
  double f = 0;
  int steps = 0;
  int next_uid = 0;
  std::unordered_map<std::uint64_t, int> selected;          // edge key -> times selected (Eq. 2)
  struct CachedDistance {
    Vec3 a, b;
    std::vector<double> d;
  };
  std::unordered_map<std::uint64_t, CachedDistance> dist_cache;  // edge key -> distance per RA (m)
  std::vector<Candidate> found;    // connections of accepted states this round
  std::vector<Candidate> queue;    // optimised, to offer after the round
  DiscoveryStats stats;
};

struct Context {
  const Problem& problem;
  const Environment& env;
  const DiscoveryOptions& o;
  SheetSpec spec;
  FeelerPrior prior;
  int nra = 0;
  const Part* base = nullptr;  // the base part (DiscoveryResult::base)
};

bool is_feeler(const Part& part, int i) { return i > 0 && part.tabs[i].tag < 0 && part.tabs[i].rivet_area < 0; }

std::uint64_t edge_key(const Part& part, int tab, int edge) {
  const int tag = part.tabs[tab].tag;
  if (tab == 0) return static_cast<std::uint64_t>(edge);
  if (tag >= 0) {
    int first = tab;
    while (first > 0 && part.tabs[first - 1].tag == tag) --first;
    return (static_cast<std::uint64_t>(tag + 1) << 32) | (static_cast<std::uint64_t>(tab - first) << 4) |
           static_cast<std::uint64_t>(edge);
  }
  const std::uint64_t uid = static_cast<std::uint64_t>(kFeelerTagBase - tag);
  return (1ULL << 62) | (uid << 4) | static_cast<std::uint64_t>(edge);
}

int find_tag(const Part& part, int tag) {
  for (int i = 1; i < part.size(); ++i)
    if (part.tabs[i].tag == tag) return i;
  return -1;
}

struct EdgeChoice {
  int tab, edge;
  std::uint64_t key;
  double weight;
};

// Distances (m) of an edge to every rivet area, cached per chain by edge
// identity and end points (an edge that has not moved is not measured again).
std::vector<double> edge_distances(Chain& ch, const Context& cx, const Part& part, const RealisedPart& rp, int tab,
                                   int edge, std::uint64_t key) {
  const auto& c = rp.tabs[tab].corners;
  const Vec3& a = c[edge];
  const Vec3& b = c[(edge + 1) % c.size()];
  auto it = ch.dist_cache.find(key);
  if (it != ch.dist_cache.end() && it->second.a == a && it->second.b == b) return it->second.d;
  std::vector<double> d(cx.nra);
  for (int r = 0; r < cx.nra; ++r) d[r] = edge_rivet_distance(cx.env, r, a, b, cx.o.target.edge_samples);
  ch.dist_cache[key] = {a, b, d};
  (void)part;
  return d;
}

// Eq. 1 over the feeler tabs' free edges, with the chain's distance cache.
double likelihood(Chain& ch, const Context& cx, const Part& part, const RealisedPart& rp, const std::vector<double>& pop) {
  std::vector<std::vector<double>> dist;
  for (int i = 1; i < part.size(); ++i) {
    if (!is_feeler(part, i)) continue;
    for (int e = 1; e <= 3; ++e) dist.push_back(edge_distances(ch, cx, part, rp, i, e, edge_key(part, i, e)));
  }
  if (dist.empty()) return cx.o.target.empty_likelihood;
  return eq1_likelihood(dist, pop, cx.o.target);
}

// Drops cache entries of edges no longer in the chain's part.
void prune_cache(Chain& ch) {
  std::unordered_map<std::uint64_t, char> live;
  for (int i = 0; i < ch.part.size(); ++i)
    for (int e = 0; e < ch.part.edge_count(i); ++e) live[edge_key(ch.part, i, e)] = 1;
  for (auto it = ch.dist_cache.begin(); it != ch.dist_cache.end();)
    it = live.count(it->first) ? std::next(it) : ch.dist_cache.erase(it);
}

// Free edges a jump may pick (all but rivet flanges' and too-short ones) with their policy weights.
std::vector<EdgeChoice> jump_edges(Chain& ch, const Context& cx, const Part& part, const RealisedPart& rp,
                                   const std::vector<double>& popularity) {
  std::vector<EdgeChoice> out;
  const double wmin = cx.spec.manufacturing.min_tab_width;
  std::vector<double> nearest;
  for (int i = 0; i < part.size(); ++i) {
    if (part.tabs[i].rivet_area >= 0) continue;
    const auto& c = rp.tabs[i].corners;
    const int ne = part.edge_count(i);
    for (int e = 0; e < ne; ++e) {
      if (!part.is_free_edge(i, e)) continue;
      if ((c[(e + 1) % c.size()] - c[e]).norm() < wmin) continue;
      const std::uint64_t key = edge_key(part, i, e);
      double w = 1.0;
      if (cx.o.edge_policy != EdgePolicy::Uniform) {
        const std::vector<double> d = edge_distances(ch, cx, part, rp, i, e, key);
        if (cx.o.edge_policy == EdgePolicy::Ours) {
          auto s = ch.selected.find(key);
          w = eq2_edge_weight(d, popularity, s == ch.selected.end() ? 0 : s->second, ch.steps, cx.o.target);
        } else {
          w = *std::min_element(d.begin(), d.end());  // distance; turned into a 0/1 weight below
        }
      }
      out.push_back({i, e, key, w});
    }
  }
  if (cx.o.edge_policy == EdgePolicy::GreedyNearest && !out.empty()) {
    size_t best = 0;
    for (size_t k = 1; k < out.size(); ++k)
      if (out[k].weight < out[best].weight) best = k;
    for (size_t k = 0; k < out.size(); ++k) out[k].weight = k == best ? 1.0 : 0.0;
  }
  return out;
}

double choice_probability(const std::vector<EdgeChoice>& edges, std::uint64_t key) {
  double total = 0, w = 0;
  for (const auto& e : edges) {
    total += e.weight;
    if (e.key == key) w = e.weight;
  }
  return total > 0 ? w / total : 0.0;
}

int feeler_count(const Part& part) {
  int n = 0;
  for (int i = 1; i < part.size(); ++i) n += is_feeler(part, i);
  return n;
}

// Sets the cast length of tab i (its other parameters set) and checks it; false = drop it.
bool cast_and_check(const Context& cx, Part& part, int i, std::optional<RivetPlane>* rivet) {
  part.tabs[i].params.l = cx.spec.manufacturing.min_tab_length;
  RealisedPart rp = realise(part);
  const CastResult cast = cast_tab_length(part, rp, i, cx.env, cx.spec, cx.prior, cx.o.cast_rays);
  if (cast.length < cx.spec.manufacturing.min_tab_length) return false;
  part.tabs[i].params.l = cast.length;
  realise_into(part, rp);
  ValidityOptions vo;
  vo.only_tab = i;
  vo.contact_sample_spacing = cx.o.feeler_contact_spacing * cx.env.voxel_size();
  if (!check_validity(part, rp, cx.spec, cx.env, vo).valid()) return false;
  if (rivet) *rivet = cast.rivet;
  return true;
}

// A connection from feeler tab k of `part`: the path from the frozen part to
// k, re-aimed at the rivet plane, with a flush flange. nullopt when it does not fit.
std::optional<Candidate> try_connection(Chain& ch, const Context& cx, const Part& part, int k, const RivetPlane& plane) {
  std::vector<int> path;
  for (int i = k; i >= ch.frozen; i = part.tabs[i].parent) path.push_back(i);
  std::reverse(path.begin(), path.end());
  SegmentWork w;
  w.plane = plane;
  w.part.load = part.load;
  w.part.base = part.base;
  w.part.tabs.assign(part.tabs.begin(), part.tabs.begin() + ch.frozen);
  w.first = ch.frozen;
  for (size_t n = 0; n < path.size(); ++n) {
    Tab t = part.tabs[path[n]];
    if (n > 0) t.parent = w.first + static_cast<int>(n) - 1;
    w.part.tabs.push_back(t);
  }
  const int last = w.part.size() - 1;
  for (int sol = 0; sol < 2; ++sol) {
    SegmentWork trial = w;
    const int f = attach_flange(trial.part, last, plane, cx.spec, -1, std::numeric_limits<double>::quiet_NaN(), sol == 1);
    if (f < 0) continue;
    trial.flange = f;
    const RealisedPart rp = realise(trial.part);
    ValidityOptions vo;
    vo.only_tab = last;
    if (!check_validity(trial.part, rp, cx.spec, cx.env, vo).valid()) continue;
    vo.only_tab = f;
    if (!check_validity(trial.part, rp, cx.spec, cx.env, vo).valid()) continue;
    Candidate c;
    c.work = std::move(trial);
    c.feeler_tag = part.tabs[path.front()].tag;
    // attachment: the frozen tab the path leaves
    const int attach = part.tabs[path.front()].parent;
    Segment& s = c.segment;
    s.parent_edge = part.tabs[path.front()].parent_edge;
    if (attach == 0) { s.parent = -1; s.parent_tab = 0; }
    else {
      s.parent = part.tabs[attach].tag;
      int first = attach;
      while (first > 0 && part.tabs[first - 1].tag == s.parent) --first;
      s.parent_tab = attach - first;
    }
    const Segment raw = make_segment(c.work);
    s.raw_root_mid = 0.5 * (raw.root_a + raw.root_b);
    s.raw_connect_mid = 0.5 * (raw.connect_a + raw.connect_b);
    s.regularisation = raw.regularisation;
    s.rivet_area = plane.rivet_area;
    s.chain = ch.index;
    s.iteration = ch.steps;
    return c;
  }
  return std::nullopt;
}

// Grows a feeler chain from (tab, edge) of `part`; new tabs get fresh tags.
// Connections found on the way are appended to `found`.
void grow(Chain& ch, const Context& cx, Part& part, int tab, int edge, std::vector<Candidate>& found) {
  const FeelerPrior& pr = cx.prior;
  if (ch.rng.uniform() < pr.empty_probability) return;
  for (int depth = 0; depth < pr.max_depth; ++depth) {
    if (feeler_count(part) >= cx.o.max_feeler_tabs) return;
    const RealisedPart rp = realise(part);
    const auto& c = rp.tabs[tab].corners;
    const double len = (c[(edge + 1) % c.size()] - c[edge]).norm();
    auto params = sample_feeler_parameters(pr, cx.spec, len, ch.rng);
    if (!params) return;
    const int i = part.add_tab(tab, edge, *params);
    part.tabs[i].tag = kFeelerTagBase - ch.next_uid++;
    std::optional<RivetPlane> rivet;
    if (!cast_and_check(cx, part, i, &rivet)) {
      part.tabs.pop_back();
      return;
    }
    if (rivet)
      if (auto cand = try_connection(ch, cx, part, i, *rivet)) found.push_back(std::move(*cand));
    if (ch.rng.uniform() >= pr.continue_probability) return;
    tab = i;
    const double u = ch.rng.uniform();
    edge = u < pr.far_edge_probability ? kFarEdge : (u < 0.5 + 0.5 * pr.far_edge_probability ? kStartSideEdge : kEndSideEdge);
  }
}

std::vector<double> current_popularity(const Context& cx, const std::vector<int>& counts) {
  return popularity_factors(counts, cx.o.target.beta);
}

// A proposed next state of a chain, its proposal probabilities and the
// connections found while building it.
struct Proposal {
  Part next;
  double q_fwd = 1, q_rev = 1;
  std::vector<Candidate> found;
};

// Index of the pick-th feeler tab (from 0).
int nth_feeler(const Part& part, int pick) {
  for (int i = 1; i < part.size(); ++i)
    if (is_feeler(part, i) && pick-- == 0) return i;
  return -1;
}

// Tab t and its descendants, in index order (parents come first).
std::vector<int> subtree(const Part& part, int t) {
  std::vector<int> sub;
  std::vector<char> in(part.size(), 0);
  for (int i = t; i < part.size(); ++i)
    if (i == t || (i > 0 && in[part.tabs[i].parent])) { in[i] = 1; sub.push_back(i); }
  return sub;
}

// Re-adds subtree `sub` of the chain's part (rooted at t) to p.next: t with
// new parameters, its descendants recast; a tab that no longer fits is
// dropped with its descendants.
void readd_subtree(Chain& ch, const Context& cx, int t, const std::vector<int>& sub, Proposal& p) {
  Part& next = p.next;
  std::map<int, int> where;  // old index -> new index
  for (int old : sub) {
    Tab tab = ch.part.tabs[old];
    if (old != t && !where.count(tab.parent)) continue;  // parent dropped
    const int parent = old == t ? (tab.parent < t ? tab.parent : -1) : where[tab.parent];
    if (parent < 0) break;
    const RealisedPart rp = realise(next);
    const auto& c = rp.tabs[parent].corners;
    const double len = (c[(tab.parent_edge + 1) % c.size()] - c[tab.parent_edge]).norm();
    if (old == t) {
      auto params = sample_feeler_parameters(cx.prior, cx.spec, len, ch.rng);
      if (!params) continue;
      tab.params = *params;
    } else if (tab.params.d + tab.params.w > len) {
      continue;
    }
    const int i = next.add_tab(parent, tab.parent_edge, tab.params);
    next.tabs[i].tag = tab.tag;
    std::optional<RivetPlane> rivet;
    if (!cast_and_check(cx, next, i, &rivet)) { next.tabs.pop_back(); continue; }
    where[old] = i;
    if (rivet)
      if (auto cand = try_connection(ch, cx, next, i, *rivet)) p.found.push_back(std::move(*cand));
  }
}

// Diffusion: a feeler tab picked uniformly (of nf) gets new parameters, its
// subtree is removed and re-added with its descendants recast.
Proposal propose_diffusion(Chain& ch, const Context& cx, int nf) {
  Proposal p;
  const int t = nth_feeler(ch.part, ch.rng.index(nf));
  const std::vector<int> sub = subtree(ch.part, t);
  p.next = remove_subtrees(ch.part, {t});
  readd_subtree(ch, cx, t, sub, p);
  p.q_fwd = 1.0 / nf;
  const int nf2 = feeler_count(p.next);
  p.q_rev = nf2 > 0 ? 1.0 / nf2 : 0.0;
  return p;
}

// An edge drawn with probability weight / total.
size_t draw_edge(const std::vector<EdgeChoice>& edges, double total, ChainRng& rng) {
  double u = rng.uniform() * total;
  size_t k = 0;
  while (k + 1 < edges.size() && u >= edges[k].weight) { u -= edges[k].weight; ++k; }
  while (edges[k].weight <= 0 && k > 0) --k;  // round-off guard
  return k;
}

// Jump: an edge drawn by the policy weights loses its feeler subtrees and
// grows a new feeler chain. nullopt when no edge can be drawn.
std::optional<Proposal> propose_jump(Chain& ch, const Context& cx, const std::vector<double>& pop) {
  const std::vector<EdgeChoice> edges = jump_edges(ch, cx, ch.part, ch.realised, pop);
  double total = 0;
  for (const auto& e : edges) total += e.weight;
  if (edges.empty() || !(total > 0)) return std::nullopt;
  const EdgeChoice chosen = edges[draw_edge(edges, total, ch.rng)];
  Proposal p;
  p.q_fwd = chosen.weight / total;
  ++ch.selected[chosen.key];
  const int owner_tag = ch.part.tabs[chosen.tab].tag;
  std::vector<int> roots;
  for (int i = ch.frozen; i < ch.part.size(); ++i)
    if (ch.part.tabs[i].parent == chosen.tab && ch.part.tabs[i].parent_edge == chosen.edge && is_feeler(ch.part, i))
      roots.push_back(i);
  p.next = remove_subtrees(ch.part, roots);
  const int owner = chosen.tab < ch.frozen ? chosen.tab : find_tag(p.next, owner_tag);
  grow(ch, cx, p.next, owner, chosen.edge, p.found);
  const RealisedPart rn = realise(p.next);
  // reverse: choose the same edge in the new state (selection counts as they are now)
  const std::vector<EdgeChoice> back = jump_edges(ch, cx, p.next, rn, pop);
  p.q_rev = choice_probability(back, chosen.key);
  return p;
}

// Metropolis-Hastings: an accepted state brings the connections found while building it.
void accept_or_reject(Chain& ch, const Context& cx, Proposal& p, bool diffuse, const std::vector<double>& pop) {
  RealisedPart rn = realise(p.next);
  const double fn = likelihood(ch, cx, p.next, rn, pop);
  const double a = mh_acceptance(ch.f, fn, p.q_fwd, p.q_rev);
  if (!(ch.rng.uniform() < a)) return;
  if (diffuse) ++ch.stats.diffusions_accepted; else ++ch.stats.jumps_accepted;
  ch.part = std::move(p.next);
  ch.realised = std::move(rn);
  ch.f = fn;
  for (auto& c : p.found) {
    c.u = ch.rng.uniform();
    ++ch.stats.candidates;
    ++ch.stats.found_per_ra[c.segment.rivet_area];
    ch.found.push_back(std::move(c));
  }
}

// One MH iteration of a chain.
void step(Chain& ch, const Context& cx, const std::vector<int>& counts) {
  const std::vector<double> pop = current_popularity(cx, counts);
  const int nf = feeler_count(ch.part);
  const bool diffuse = nf > 0 && ch.rng.uniform() < cx.o.diffuse_probability;
  std::optional<Proposal> p;
  if (diffuse) {
    ++ch.stats.diffusions;
    p = propose_diffusion(ch, cx, nf);
  } else {
    ++ch.stats.jumps;
    p = propose_jump(ch, cx, pop);
  }
  if (p) accept_or_reject(ch, cx, *p, diffuse, pop);
  ++ch.steps;
}

// Geometry optimisation of a candidate (Sec. 4.2); false when the result is not valid.
bool optimise(Candidate& c, const Context& cx, Chain& ch) {
  ++ch.stats.optimised;
  ++ch.stats.optimised_per_ra[c.segment.rivet_area];
  c.optimised = true;
  // SHEETGEN_DISC_DEBUG=1: one line per optimised candidate on stderr (tabs, summed length, widths per stage).
  static const bool dbg = std::getenv("SHEETGEN_DISC_DEBUG") != nullptr;
  auto summary = [](const SegmentWork& w) {
    double lo = 1e9, hi = 0;
    for (int i = w.first; i < w.flange; ++i) { lo = std::min(lo, w.part.tabs[i].params.w); hi = std::max(hi, w.part.tabs[i].params.w); }
    char buf[160];
    std::snprintf(buf, sizeof buf, "n=%d L=%.0f w=%.0f..%.0f", w.feeler_count(), w.length() * 1e3, lo * 1e3, hi * 1e3);
    return std::string(buf);
  };
  auto why = [&](const SegmentWork& w) {
    const RealisedPart rp = realise(w.part);
    const ValidityReport v = check_validity(w.part, rp, cx.spec, cx.env);
    if (!v.valid()) return std::string("V:") + v.summary();
    const FlatPattern flat = unfold(w.part, cx.spec);
    if (!flat.ok()) return std::string("UNFOLD ") + flat.message;
    const ValidityReport f = check_flat_pattern(flat, cx.spec);
    if (!f.valid()) return std::string("F:") + f.summary();
    return std::string("ok");
  };
  std::string log;
  if (dbg) log = "raw " + summary(c.work) + " [" + why(c.work) + "]";
  if (cx.o.optimise) {
    const ShortcutResult sr = shortcut_segment(c.work, cx.env, cx.spec, cx.o.shortcut);
    if (dbg) log += " | shortcut(-" + std::to_string(sr.removed_tabs) + ") " + summary(c.work);
    const ContractResult cr = contract_segment(c.work, cx.env, cx.spec, cx.o.contract);
    if (dbg) log += " | contract(" + std::to_string(cr.steps) + (cr.converged ? ",conv" : ",cap") + ") " + summary(c.work);
    const int merges = merge_coplanar(c.work, cx.env, cx.spec, cx.o.merge);
    if (merges > 0) contract_segment(c.work, cx.env, cx.spec, cx.o.contract);
    if (dbg) log += " | merge " + std::to_string(merges) + " " + summary(c.work);
    const WidenResult wr = widen_segment(c.work, cx.env, cx.spec, cx.o.widen);
    if (dbg) log += " | widen(" + std::to_string(wr.steps) + ") " + summary(c.work);
  }
  if (dbg) std::fprintf(stderr, "[seg] chain %d ra %d %s [%s]\n", ch.index, c.segment.rivet_area, log.c_str(), why(c.work).c_str());
  if (!segment_valid(c.work, cx.env, cx.spec)) { ++ch.stats.optimise_failed; ++ch.stats.failed_per_ra[c.segment.rivet_area]; return false; }
  Segment s = make_segment(c.work);
  s.parent = c.segment.parent;
  s.parent_tab = c.segment.parent_tab;
  s.rivet_area = c.segment.rivet_area;
  s.chain = c.segment.chain;
  s.iteration = c.segment.iteration;
  s.raw_root_mid = c.segment.raw_root_mid;
  s.raw_connect_mid = c.segment.raw_connect_mid;
  c.segment = std::move(s);
  return true;
}

// Optimised, and bendable with the press brake's tools on the base and its
// ancestors (bendable.hpp): a connection worth offering to the library.
bool ready_to_offer(Candidate& c, const Context& cx, Chain& ch, const SegmentLibrary& snapshot) {
  if (!optimise(c, cx, ch)) return false;
  if (c.segment.parent >= 0 && !snapshot.find(c.segment.parent)) return true;  // admit() rejects it
  const BendableResult bendable = segment_bendable(cx.problem, *cx.base, snapshot, c.segment);
  static const bool dbg = std::getenv("SHEETGEN_DISC_DEBUG") != nullptr;  // one line per segment checked
  if (dbg)
    std::fprintf(stderr, "[bendable] chain %d ra %d parent %d: %s\n", ch.index, c.segment.rivet_area, c.segment.parent,
                 bendable.ok ? "ok" : bendable.message.c_str());
  if (bendable.ok) return true;
  ++ch.stats.press_rejected;
  ++ch.stats.press_rejected_per_ra[c.segment.rivet_area];
  if (ch.stats.press_example.empty()) ch.stats.press_example = bendable.message;
  return false;
}

// End of a chain's round: decide which of its connections are optimised and queued.
void select_for_library(Chain& ch, const Context& cx, const SegmentLibrary& snapshot) {
  std::vector<Candidate> found = std::move(ch.found);
  ch.found.clear();
  const auto counts = snapshot.counts_per_rivet_area(cx.nra);
  auto full = [&](const Candidate& c) { return counts[c.segment.rivet_area] >= cx.o.library.max_per_rivet_area; };
  switch (cx.o.segment_policy) {
    case SegmentPolicy::Ours:
      for (auto& c : found) {
        // decide on the raw features against the library and this round's own picks
        AdmissionResult r = snapshot.decide(c.segment, c.u);
        if (r.outcome == Admission::Admitted) {
          for (const auto& q : ch.queue)
            if (segment_distance(q.segment, c.segment) < cx.o.library.duplicate_distance) r.outcome = Admission::Rejected;
        }
        if (r.outcome == Admission::Admitted || r.outcome == Admission::Replaced) {
          if (ready_to_offer(c, cx, ch, snapshot)) ch.queue.push_back(std::move(c));
        } else if (r.outcome == Admission::Full) {
          ++ch.stats.full;
        } else {
          ++ch.stats.rejected;
        }
      }
      break;
    case SegmentPolicy::Greedy:
      for (auto& c : found) {
        if (full(c)) { ++ch.stats.full; continue; }
        if (ready_to_offer(c, cx, ch, snapshot)) ch.queue.push_back(std::move(c));
      }
      break;
    case SegmentPolicy::Uniform: {
      if (found.empty()) break;
      Candidate& c = found[ch.rng.index(static_cast<int>(found.size()))];
      ch.stats.rejected += static_cast<long long>(found.size()) - 1;
      if (full(c)) { ++ch.stats.full; break; }
      if (ready_to_offer(c, cx, ch, snapshot)) ch.queue.push_back(std::move(c));
      break;
    }
  }
}

// Index of tab `local` of frozen segment `id` in the chain's part, or -1.
int frozen_index(const Chain& ch, int id, int local) {
  if (id < 0) return 0;
  for (int i = 1; i < ch.frozen; ++i)
    if (ch.part.tabs[i].tag == id) return i + local;
  return -1;
}

void recount_frozen(Chain& ch) {
  int f = 1;
  while (f < ch.part.size() && ch.part.tabs[f].tag >= 0) ++f;
  ch.frozen = f;
}

// Freezes an admitted segment into its chain: its feeler branch goes, its tabs
// are inserted at the end of the frozen region. A feeler_tag that is not a
// feeler's (> kFeelerTagBase, e.g. -1 for web roots) removes nothing.
void freeze(Chain& ch, const Segment& s, int feeler_tag) {
  const int branch = feeler_tag <= kFeelerTagBase ? find_tag(ch.part, feeler_tag) : -1;
  if (branch >= 0) ch.part = remove_subtrees(ch.part, {branch});
  const int attach = frozen_index(ch, s.parent, s.parent_tab);
  if (attach < 0) return;
  Part out;
  out.load = ch.part.load;
  out.base = ch.part.base;
  out.tabs.assign(ch.part.tabs.begin(), ch.part.tabs.begin() + ch.frozen);
  append_segment_tabs(out.tabs, s, attach, s.id);
  const int shift = static_cast<int>(s.tabs.size());
  for (int i = ch.frozen; i < ch.part.size(); ++i) {
    Tab t = ch.part.tabs[i];
    if (t.parent >= ch.frozen) t.parent += shift;
    out.tabs.push_back(t);
  }
  ch.part = std::move(out);
  recount_frozen(ch);
}

void unfreeze(Chain& ch, int id) {
  std::vector<int> roots;
  for (int i = 1; i < ch.part.size(); ++i)
    if (ch.part.tabs[i].tag == id) roots.push_back(i);
  ch.part = remove_subtrees(ch.part, roots);
  recount_frozen(ch);
  prune_cache(ch);
}

void check_discovery_inputs(const Problem& problem, int load_index, const DiscoveryOptions& o) {
  if (load_index < 0 || load_index >= static_cast<int>(problem.loads.size()))
    throw std::invalid_argument("discover_segments: load_index " + std::to_string(load_index) + " is not a load of the problem");
  if (o.chains < 1) throw std::invalid_argument("discover_segments: chains must be >= 1, got " + std::to_string(o.chains));
  if (o.iterations < 0) throw std::invalid_argument("discover_segments: iterations must be >= 0");
  if (o.round_length < 1) throw std::invalid_argument("discover_segments: round_length must be >= 1");
}

std::vector<Chain> start_chains(const Context& cx, const Part& base) {
  const DiscoveryOptions& o = cx.o;
  std::vector<Chain> chains(o.chains);
  for (int c = 0; c < o.chains; ++c) {
    chains[c].index = c;
    chains[c].rng = ChainRng(ChainRng::seed_for(o.seed, c));
    chains[c].part = base;
    chains[c].realised = realise(chains[c].part);
    chains[c].f = o.target.empty_likelihood;
    for (auto* v : {&chains[c].stats.found_per_ra, &chains[c].stats.optimised_per_ra, &chains[c].stats.failed_per_ra,
                    &chains[c].stats.press_rejected_per_ra, &chains[c].stats.admitted_per_ra})
      v->assign(cx.nra, 0);
  }
  return chains;
}

// Web roots go into the library first and into every chain, frozen: the
// chains grow feelers from their edges like from any admitted segment.
void add_web_roots(DiscoveryResult& result, std::vector<Chain>& chains, const Context& cx) {
  for (Segment& web : make_web_roots(result.base, cx.env, cx.spec, cx.prior, cx.o.webs)) {
    const AdmissionResult r = result.library.add(std::move(web));
    for (auto& ch : chains) freeze(ch, *result.library.find(r.id), /*feeler_tag=*/-1);
  }
}

bool cancel_requested(const DiscoveryProgress* progress) {
  return progress && progress->cancel.load(std::memory_order_relaxed);
}

// Before a round: the chains' states scored with the library's current popularity.
void refresh_chains(std::vector<Chain>& chains, const Context& cx, const std::vector<int>& counts) {
  for (auto& ch : chains) {
    ch.realised = realise(ch.part);
    prune_cache(ch);
    ch.f = likelihood(ch, cx, ch.part, ch.realised, popularity_factors(counts, cx.o.target.beta));
  }
}

// Iterations [start, end) of every chain in parallel, each chain then
// selecting its connections against `snapshot` (read-only during the round).
void run_round(tbb::task_arena& arena, std::vector<Chain>& chains, const Context& cx, const std::vector<int>& counts,
               const SegmentLibrary& snapshot, int start, int end, DiscoveryProgress* progress) {
  arena.execute([&] {
    tbb::parallel_for(0, cx.o.chains, [&](int c) {
      Chain& ch = chains[c];
      for (int it = start; it < end; ++it) {
        if (cancel_requested(progress)) break;
        step(ch, cx, counts);
        if (progress) progress->iterations.fetch_add(1, std::memory_order_relaxed);
      }
      // Optimising the round's connections (contraction, widening) is the
      // slow part of a round; a cancelled run does not wait for it.
      if (!cancel_requested(progress)) select_for_library(ch, cx, snapshot);
    });
  });
}

// Offers one queued segment of chain ch to the library and freezes it into
// the chain when admitted; a replaced segment leaves every chain's part.
void admit(Candidate& cand, Chain& ch, std::vector<Chain>& chains, SegmentLibrary& library, SegmentPolicy policy) {
  if (cand.segment.parent >= 0 && !library.find(cand.segment.parent)) { ++ch.stats.rejected; return; }
  AdmissionResult r;
  if (policy == SegmentPolicy::Ours) r = library.offer(cand.segment, cand.u);
  else r = library.add(cand.segment);
  switch (r.outcome) {
    case Admission::Admitted: ++ch.stats.admitted; ++ch.stats.admitted_per_ra[cand.segment.rivet_area]; break;
    case Admission::Replaced: ++ch.stats.replaced; ++ch.stats.admitted_per_ra[cand.segment.rivet_area]; break;
    case Admission::Rejected: ++ch.stats.rejected; return;
    case Admission::Full: ++ch.stats.full; return;
  }
  if (r.outcome == Admission::Replaced) {
    for (auto& other : chains)
      if (find_tag(other.part, r.replaced) >= 0) unfreeze(other, r.replaced);
  }
  cand.segment.id = r.id;
  freeze(ch, *library.find(r.id), cand.feeler_tag);
}

// Admissions in chain order (determinism).
void admit_round(std::vector<Chain>& chains, SegmentLibrary& library, SegmentPolicy policy) {
  for (auto& ch : chains) {
    for (auto& cand : ch.queue) admit(cand, ch, chains, library, policy);
    ch.queue.clear();
  }
}

void add_counts(std::vector<long long>& a, const std::vector<long long>& b) {
  if (a.size() < b.size()) a.resize(b.size(), 0);
  for (size_t k = 0; k < b.size(); ++k) a[k] += b[k];
}

void add_chain_stats(DiscoveryStats& t, const DiscoveryStats& s) {
  t.jumps += s.jumps; t.jumps_accepted += s.jumps_accepted;
  t.diffusions += s.diffusions; t.diffusions_accepted += s.diffusions_accepted;
  t.candidates += s.candidates; t.optimised += s.optimised; t.optimise_failed += s.optimise_failed;
  t.press_rejected += s.press_rejected;
  if (t.press_example.empty()) t.press_example = s.press_example;
  t.admitted += s.admitted; t.replaced += s.replaced; t.rejected += s.rejected; t.full += s.full;
  add_counts(t.found_per_ra, s.found_per_ra); add_counts(t.optimised_per_ra, s.optimised_per_ra);
  add_counts(t.failed_per_ra, s.failed_per_ra); add_counts(t.admitted_per_ra, s.admitted_per_ra);
  add_counts(t.press_rejected_per_ra, s.press_rejected_per_ra);
}

}  // namespace

DiscoveryResult discover_segments(const Problem& problem, const Environment& env, int load_index,
                                  const DiscoveryOptions& o, DiscoveryProgress* progress) {
  check_discovery_inputs(problem, load_index, o);
  const auto t0 = std::chrono::steady_clock::now();
  Context cx{problem, env, o, SheetSpec::from(problem), {}, env.rivet_area_count()};
  cx.prior = resolve_prior(o.prior, cx.spec);

  DiscoveryResult result;
  result.library = SegmentLibrary(o.library);
  result.base = make_base_part(problem.loads[load_index], load_index, cx.spec.thickness);
  cx.base = &result.base;
  std::vector<Chain> chains = start_chains(cx, result.base);
  if (o.web_roots) add_web_roots(result, chains, cx);
  if (progress) {
    progress->total = static_cast<long long>(o.chains) * o.iterations;
    progress->iterations = 0;
  }
  tbb::task_arena arena(o.threads > 0 ? o.threads : tbb::task_arena::automatic);
  std::vector<int> counts(cx.nra, 0);
  bool cancelled = false;
  for (int start = 0; start < o.iterations && !cancelled; start += o.round_length) {
    const int end = std::min(o.iterations, start + o.round_length);
    refresh_chains(chains, cx, counts);
    run_round(arena, chains, cx, counts, result.library, start, end, progress);
    if (progress && progress->cancel.load()) cancelled = true;
    admit_round(chains, result.library, o.segment_policy);
    counts = result.library.counts_per_rivet_area(cx.nra);
    ++result.stats.rounds;
    if (progress) progress->segments = result.library.size();
  }
  for (const auto& ch : chains) add_chain_stats(result.stats, ch.stats);
  result.library.compact();
  result.stats.per_rivet_area = result.library.counts_per_rivet_area(cx.nra);
  result.cancelled = cancelled;
  result.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace sheetgen
