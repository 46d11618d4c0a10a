#include "sheetgen/discovery/segment_library.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

namespace sheetgen {

double segment_distance(const Segment& a, const Segment& b) {
  return (a.raw_root_mid - b.raw_root_mid).norm() + (a.raw_connect_mid - b.raw_connect_mid).norm();
}

double regularisation_score(int tab_count, const Vec3& root_dir, const Vec3& connect_dir) {
  const double n = root_dir.norm() * connect_dir.norm();
  const double c = n > 0 ? std::abs(root_dir.dot(connect_dir)) / n : 0.0;
  return tab_count + (1.0 - c);
}

const char* to_string(Admission a) {
  switch (a) {
    case Admission::Admitted: return "admitted";
    case Admission::Replaced: return "replaced";
    case Admission::Rejected: return "rejected";
    case Admission::Full: return "full";
  }
  return "?";
}

const Segment* SegmentLibrary::find(int id) const {
  auto it = std::lower_bound(segments_.begin(), segments_.end(), id,
                             [](const Segment& s, int v) { return s.id < v; });
  return it != segments_.end() && it->id == id ? &*it : nullptr;
}

bool SegmentLibrary::has_children(int id) const {
  for (const Segment& s : segments_)
    if (s.parent == id) return true;
  return false;
}

std::vector<int> SegmentLibrary::counts_per_rivet_area(int n) const {
  std::vector<int> c(std::max(0, n), 0);
  for (const Segment& s : segments_)
    if (s.rivet_area >= 0 && s.rivet_area < n) ++c[s.rivet_area];
  return c;
}

double SegmentLibrary::distance_to_library(const Segment& s, int* nearest) const {
  double best = std::numeric_limits<double>::infinity();
  int who = -1;
  for (const Segment& o : segments_) {
    if (o.rivet_area < 0) continue;  // web roots (no connection) are not compared
    const double d = segment_distance(s, o);
    if (d < best) { best = d; who = o.id; }
  }
  if (nearest) *nearest = who;
  return best;
}

double SegmentLibrary::admission_probability(double distance) const {
  if (!std::isfinite(distance)) return 1.0;
  return 1.0 - std::exp(-distance / options_.admission_scale);
}

AdmissionResult SegmentLibrary::decide(const Segment& s, double u) const {
  AdmissionResult r;
  int nearest = -1;
  r.distance = distance_to_library(s, &nearest);
  r.probability = admission_probability(r.distance);
  if (r.distance < options_.duplicate_distance && nearest >= 0) {
    const Segment* old = find(nearest);
    if (s.regularisation < old->regularisation - 1e-9 && !has_children(nearest)) {
      r.outcome = Admission::Replaced;
      r.replaced = nearest;
    } else {
      r.outcome = Admission::Rejected;
    }
    return r;
  }
  const int n = s.rivet_area >= 0 ? s.rivet_area + 1 : 0;
  const auto counts = counts_per_rivet_area(n);
  if (s.rivet_area >= 0 && counts[s.rivet_area] >= options_.max_per_rivet_area) {
    r.outcome = Admission::Full;
    return r;
  }
  r.outcome = u < r.probability ? Admission::Admitted : Admission::Rejected;
  return r;
}

AdmissionResult SegmentLibrary::add(Segment s) {
  AdmissionResult r;
  r.distance = distance_to_library(s);
  r.probability = 1.0;
  const auto counts = counts_per_rivet_area(s.rivet_area + 1);
  if (s.rivet_area >= 0 && counts[s.rivet_area] >= options_.max_per_rivet_area) {
    r.outcome = Admission::Full;
    return r;
  }
  s.id = next_id_++;
  r.id = s.id;
  r.outcome = Admission::Admitted;
  segments_.push_back(std::move(s));
  return r;
}

AdmissionResult SegmentLibrary::offer(Segment s, double u) {
  AdmissionResult r = decide(s, u);
  if (r.outcome == Admission::Admitted) {
    s.id = next_id_++;
    r.id = s.id;
    segments_.push_back(std::move(s));
  } else if (r.outcome == Admission::Replaced) {
    segments_.erase(std::remove_if(segments_.begin(), segments_.end(),
                                   [&](const Segment& o) { return o.id == r.replaced; }),
                    segments_.end());
    s.id = next_id_++;
    r.id = s.id;
    segments_.push_back(std::move(s));
  }
  return r;
}

void SegmentLibrary::compact() {
  std::map<int, int> remap;
  for (size_t i = 0; i < segments_.size(); ++i) remap[segments_[i].id] = static_cast<int>(i);
  for (Segment& s : segments_) {
    s.id = remap.at(s.id);
    if (s.parent >= 0) s.parent = remap.at(s.parent);
  }
  next_id_ = static_cast<int>(segments_.size());
}

namespace {

// The same segment found twice (web roots are built without random numbers,
// so every pass makes the same ones): same attachment, edges, raw features
// and area.
bool same_segment(const Segment& a, const Segment& b, int b_parent) {
  constexpr double eps = 1e-9;  // m
  return a.parent == b_parent && a.parent_tab == b.parent_tab && a.parent_edge == b.parent_edge &&
         a.rivet_area == b.rivet_area && a.tabs.size() == b.tabs.size() && (a.root_a - b.root_a).norm() < eps &&
         (a.root_b - b.root_b).norm() < eps && (a.connect_a - b.connect_a).norm() < eps &&
         (a.connect_b - b.connect_b).norm() < eps && segment_distance(a, b) < eps && std::abs(a.area - b.area) < eps * eps;
}

}  // namespace

int SegmentLibrary::absorb(const SegmentLibrary& other) {
  if (segments_.empty()) {  // a first search composes exactly its own library
    *this = other;
    return size();
  }
  std::map<int, int> remap;  // other's id -> id here
  int copied = 0;
  for (const Segment& s : other.segments()) {  // id order: parents first
    const int parent = s.parent >= 0 ? remap.at(s.parent) : -1;
    auto same = std::find_if(segments_.begin(), segments_.end(),
                             [&](const Segment& o) { return same_segment(o, s, parent); });
    if (same != segments_.end()) {
      remap[s.id] = same->id;
      continue;
    }
    if (s.rivet_area >= 0 && !other.has_children(s.id) && distance_to_library(s) < options_.duplicate_distance)
      continue;
    Segment c = s;
    c.id = next_id_++;
    c.parent = parent;
    remap[s.id] = c.id;
    segments_.push_back(std::move(c));
    ++copied;
  }
  return copied;
}

Part assemble_part(const Part& base, const SegmentLibrary& library, std::vector<int> ids) {
  if (base.tabs.empty()) throw std::invalid_argument("assemble_part: base part has no base tab");
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  Part part;
  part.load = base.load;
  part.base = base.base;
  part.tabs.push_back(base.tabs[0]);
  std::map<int, int> first_index;  // segment id -> part index of its tabs[0]
  for (int id : ids) {
    const Segment* s = library.find(id);
    if (!s) throw std::invalid_argument("assemble_part: segment " + std::to_string(id) + " is not in the library");
    int attach = 0;
    if (s->parent >= 0) {
      auto it = first_index.find(s->parent);
      if (it == first_index.end())
        throw std::invalid_argument("assemble_part: segment " + std::to_string(id) + " needs its parent segment " +
                                    std::to_string(s->parent) + ", which is not in the subset");
      attach = it->second + s->parent_tab;
    }
    first_index[id] = part.size();
    append_segment_tabs(part.tabs, *s, attach, id);
  }
  return part;
}

void append_segment_tabs(std::vector<Tab>& tabs, const Segment& segment, int attach, int tag) {
  const int first = static_cast<int>(tabs.size());
  for (size_t k = 0; k < segment.tabs.size(); ++k) {
    Tab t = segment.tabs[k];
    if (k == 0) { t.parent = attach; t.parent_edge = segment.parent_edge; }
    else t.parent += first;
    t.tag = tag;
    tabs.push_back(t);
  }
}

std::vector<int> segment_closure(const SegmentLibrary& library, int id) {
  std::vector<int> out;
  for (const Segment* s = library.find(id); s; s = s->parent >= 0 ? library.find(s->parent) : nullptr) out.push_back(s->id);
  std::sort(out.begin(), out.end());
  return out;
}

Part assemble_with(const Part& base, const SegmentLibrary& library, const Segment& segment) {
  Part part = assemble_part(base, library, segment.parent >= 0 ? segment_closure(library, segment.parent) : std::vector<int>{});
  int attach = 0;
  if (segment.parent >= 0) {
    const auto first = std::find_if(part.tabs.begin(), part.tabs.end(), [&](const Tab& t) { return t.tag == segment.parent; });
    if (first == part.tabs.end())
      throw std::invalid_argument("assemble_with: parent segment " + std::to_string(segment.parent) + " is not in the library");
    attach = static_cast<int>(first - part.tabs.begin()) + segment.parent_tab;
  }
  append_segment_tabs(part.tabs, segment, attach, segment.id);
  return part;
}

}  // namespace sheetgen
