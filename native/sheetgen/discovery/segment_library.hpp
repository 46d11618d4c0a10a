#pragma once
// The Segment Library (paper Sec. 4, docs/architecture.md "Segment library"): optimised
// segments from the base tab (or from an earlier segment) to a rivet area,
// kept as a tree, with the admission / replacement rule and the assembly of a
// Part from a subset of segments closed under parents (what composition needs).
#include <string>
#include <vector>

#include "sheetgen/part/part.hpp"

namespace sheetgen {

struct Segment {
  int id = -1;
  // Attachment: the first tab leaves edge `parent_edge` of tab `parent_tab` of
  // segment `parent` (parent = -1: the base tab, parent_tab = 0).
  int parent = -1;
  int parent_tab = 0;
  int parent_edge = 0;
  // The tabs as a Part fragment: tabs[0].parent = -1 (attached as above),
  // tabs[k].parent = index into this vector (< k). The last tab is the rivet
  // flange (rivet_area >= 0), except in a web root (web_roots.hpp), which
  // has no flange and rivet_area = -1. Tags are ignored.
  std::vector<Tab> tabs;
  int rivet_area = -1;
  double area = 0;          // m^2, sum of w * l over the tabs (each tab's area is exactly w l)
  double length = 0;        // m, sum of l over the non-flange tabs
  int bends = 0;            // bend operations this segment adds (= tabs.size())
  int chain = -1;           // chain that found it
  int iteration = -1;       // iteration of that chain at which it was found
  // Root edge (first tab's bend line P0 -> P1) and connecting edge (the
  // flange's bend line) of the optimised segment, world, m.
  Vec3 root_a = Vec3::Zero(), root_b = Vec3::Zero();
  Vec3 connect_a = Vec3::Zero(), connect_b = Vec3::Zero();
  // Similarity features: midpoints of the root and connecting edges of the
  // candidate before geometry optimisation (m). Raw candidates are compared
  // with raw candidates, so the decision can be taken before optimising.
  Vec3 raw_root_mid = Vec3::Zero(), raw_connect_mid = Vec3::Zero();
  // Regularisation (lower is better): number of tabs + (1 - |cos angle|)
  // between the root and connecting edge directions.
  double regularisation = 0;
};

// Distance between two segments (m): |root midpoint difference| + |connecting
// midpoint difference|, on the raw features.
double segment_distance(const Segment& a, const Segment& b);
// Regularisation score of a segment from its tab count and edge directions.
double regularisation_score(int tab_count, const Vec3& root_dir, const Vec3& connect_dir);

struct LibraryOptions {
  // Admission probability p(D) = 1 - exp(-D / admission_scale), D = distance to the nearest segment (m).
  double admission_scale = 0.05;      // m: D = 5 cm gives p = 0.63, 15 cm gives 0.95
  double duplicate_distance = 0.02;   // m: closer than this is a near-duplicate (replace or reject)
  int max_per_rivet_area = 10;        // cap per rivet area (the paper's ablation caps at 10)
};

enum class Admission { Admitted, Replaced, Rejected, Full };
const char* to_string(Admission a);

struct AdmissionResult {
  Admission outcome = Admission::Rejected;
  int id = -1;        // id of the admitted segment (Admitted / Replaced)
  int replaced = -1;  // id of the removed segment (Replaced)
  double distance = 0;     // m, to the nearest segment before the offer (infinity when empty)
  double probability = 0;  // admission probability used
};

class SegmentLibrary {
 public:
  explicit SegmentLibrary(const LibraryOptions& options = {}) : options_(options) {}

  const LibraryOptions& options() const { return options_; }
  // Live segments in id order.
  const std::vector<Segment>& segments() const { return segments_; }
  int size() const { return static_cast<int>(segments_.size()); }
  bool empty() const { return segments_.empty(); }
  const Segment* find(int id) const;  // nullptr when absent (never admitted or replaced)
  bool has_children(int id) const;
  std::vector<int> counts_per_rivet_area(int rivet_area_count) const;

  // Nearest segment (id, or -1) and its distance (infinity when empty).
  double distance_to_library(const Segment& s, int* nearest = nullptr) const;
  // p(D) of LibraryOptions.
  double admission_probability(double distance) const;

  // Admits `s` unconditionally (still subject to the per-area cap); gives it the next id.
  AdmissionResult add(Segment s);
  // The paper's rule: a near-duplicate (D < duplicate_distance) replaces its
  // nearest segment when its regularisation is lower and the old one has no
  // child segments, else is rejected; otherwise it is admitted when u < p(D).
  // u is a uniform [0, 1) number drawn by the caller (determinism).
  AdmissionResult offer(Segment s, double u);
  // Same decision without changing the library.
  AdmissionResult decide(const Segment& s, double u) const;

  // Renumbers ids 0..n-1 in id order, remapping parents.
  void compact();

  // Pools the segments of `other` (a library of the same base, e.g. another
  // seed's discovery) into this one, its parents before its children, with
  // new ids (docs/pipeline.md, step 4d). A segment identical to one here (same
  // parent, edges, features, area) is not copied: its children hang from the one
  // here. A childless connection closer than duplicate_distance to one here
  // is left out, as admission would. The per-area cap does not apply: a pool
  // of k libraries holds up to k times it. Into an empty library, `other` is
  // copied as it is (ids and options). Returns the segments copied.
  int absorb(const SegmentLibrary& other);

 private:
  LibraryOptions options_;
  std::vector<Segment> segments_;
  int next_id_ = 0;
};

// Builds a Part: `base` (a part with only its base tab, e.g. make_base_part)
// plus the tabs of the segments `ids`, which must be closed under parents
// (throws std::invalid_argument naming the missing parent otherwise). Tabs get
// tag = segment id. Parents come first (ids are admitted after their parents).
Part assemble_part(const Part& base, const SegmentLibrary& library, std::vector<int> ids);

// Appends the tabs of `segment` to `tabs`, its first tab hanging from tab
// `attach` (an index into `tabs`), each tagged `tag`.
void append_segment_tabs(std::vector<Tab>& tabs, const Segment& segment, int attach, int tag);

// Segment `id` with all its ancestors, sorted (a subset closed under parents).
std::vector<int> segment_closure(const SegmentLibrary& library, int id);

// `base` plus a segment not (yet) in the library and its ancestors, which
// are: what discovery checks before it offers the segment. The new
// segment's tabs get tag = segment.id.
Part assemble_with(const Part& base, const SegmentLibrary& library, const Segment& segment);

}  // namespace sheetgen
