// Library admission, replacement, cap and assembly on crafted segments.
#include <gtest/gtest.h>

#include <cmath>

#include "sheetgen/discovery/segment_library.hpp"
#include "../common/scene_fixture.hpp"

namespace sheetgen {
namespace {

Segment crafted(double x, int ra, int tabs, double reg_extra = 0) {
  Segment s;
  s.rivet_area = ra;
  s.raw_root_mid = Vec3(x, 0, 0);
  s.raw_connect_mid = Vec3(x, 0.3, 0);
  for (int k = 0; k < tabs; ++k) {
    Tab t;
    t.parent = k - 1;
    t.parent_edge = k == 0 ? 0 : kFarEdge;
    t.params = {0, 0.016, 0.05, 0, 0, -M_PI / 2};
    s.tabs.push_back(t);
  }
  s.tabs.back().rivet_area = ra;
  s.regularisation = tabs + reg_extra;
  return s;
}

TEST(SegmentLibrary, DistanceAndAdmissionProbability) {
  SegmentLibrary lib;  // scale 5 cm, duplicate 2 cm
  EXPECT_DOUBLE_EQ(segment_distance(crafted(0, 0, 2), crafted(0.03, 0, 2)), 0.06);  // both edges 3 cm apart
  EXPECT_EQ(lib.admission_probability(std::numeric_limits<double>::infinity()), 1.0);
  EXPECT_NEAR(lib.admission_probability(0.05), 1 - std::exp(-1.0), 1e-15);
  // empty library: always admitted
  EXPECT_EQ(lib.offer(crafted(0, 0, 2), 0.999).outcome, Admission::Admitted);
  // D = 0.06 m: p = 1 - e^-1.2 = 0.6988; u = 0.69 admits, u = 0.70 rejects
  EXPECT_EQ(lib.decide(crafted(0.03, 0, 2), 0.70).outcome, Admission::Rejected);
  const AdmissionResult r = lib.offer(crafted(0.03, 0, 2), 0.69);
  EXPECT_EQ(r.outcome, Admission::Admitted);
  EXPECT_NEAR(r.probability, 1 - std::exp(-1.2), 1e-12);
  EXPECT_EQ(lib.size(), 2);
}

TEST(SegmentLibrary, NearDuplicateWithBetterRegularisationReplaces) {
  SegmentLibrary lib;
  const int a = lib.offer(crafted(0, 0, 3, 0.5), 0.0).id;
  // 1 cm + 1 cm = 2 cm... use 0.5 cm: D = 1 cm < 2 cm: a near-duplicate
  const AdmissionResult worse = lib.offer(crafted(0.005, 0, 3, 0.6), 0.0);
  EXPECT_EQ(worse.outcome, Admission::Rejected);  // higher (worse) regularisation
  const AdmissionResult better = lib.offer(crafted(0.005, 0, 2, 0.1), 0.0);
  EXPECT_EQ(better.outcome, Admission::Replaced);
  EXPECT_EQ(better.replaced, a);
  EXPECT_EQ(lib.size(), 1);
  EXPECT_EQ(lib.find(a), nullptr);
  EXPECT_EQ(lib.segments()[0].tabs.size(), 2u);
  // a segment with a child segment is never replaced
  Segment child = crafted(0.5, 1, 1);
  child.parent = better.id;
  lib.add(child);
  EXPECT_EQ(lib.offer(crafted(0.005, 0, 1, 0.0), 0.0).outcome, Admission::Rejected);
}

TEST(SegmentLibrary, CapPerRivetArea) {
  LibraryOptions o;
  o.max_per_rivet_area = 2;
  SegmentLibrary lib(o);
  EXPECT_EQ(lib.add(crafted(0, 0, 1)).outcome, Admission::Admitted);
  EXPECT_EQ(lib.add(crafted(1, 0, 1)).outcome, Admission::Admitted);
  EXPECT_EQ(lib.add(crafted(2, 0, 1)).outcome, Admission::Full);
  EXPECT_EQ(lib.offer(crafted(3, 0, 1), 0.0).outcome, Admission::Full);
  EXPECT_EQ(lib.add(crafted(2, 1, 1)).outcome, Admission::Admitted);
  EXPECT_EQ(lib.counts_per_rivet_area(2), (std::vector<int>{2, 1}));
}

TEST(SegmentLibrary, AssemblePartNeedsParents) {
  const Problem p = testing_scenes::base_problem();
  const Part base = make_base_part(p.loads[0], 0, 1.6e-3);
  SegmentLibrary lib;
  Segment root = crafted(0, 0, 2);
  const int r = lib.add(root).id;
  Segment child = crafted(0.5, 1, 1);
  child.parent = r;
  child.parent_tab = 1;
  child.parent_edge = kEndSideEdge;
  const int c = lib.add(child).id;
  EXPECT_THROW(assemble_part(base, lib, {c}), std::invalid_argument);
  const Part part = assemble_part(base, lib, {c, r});
  ASSERT_EQ(part.size(), 4);
  EXPECT_EQ(part.tabs[1].parent, 0);
  EXPECT_EQ(part.tabs[2].parent, 1);
  EXPECT_EQ(part.tabs[3].parent, 2);  // tab 1 of segment r
  EXPECT_EQ(part.tabs[3].parent_edge, kEndSideEdge);
  EXPECT_EQ(part.tabs[3].tag, c);
}

// A segment not yet in the library, assembled with its ancestors, is the part
// assemble_part makes once it is admitted (it gets the largest id, so its tabs
// come last either way).
TEST(SegmentLibrary, AssembleWithMatchesTheAdmittedSegment) {
  const Problem p = testing_scenes::base_problem();
  const Part base = make_base_part(p.loads[0], 0, 1.6e-3);
  SegmentLibrary lib;
  const int r = lib.add(crafted(0, 0, 2)).id;
  lib.add(crafted(0.2, 1, 2));  // a sibling: not an ancestor, not assembled
  Segment child = crafted(0.5, 1, 2);
  child.parent = r;
  child.parent_tab = 1;
  child.parent_edge = kEndSideEdge;
  const Part before = assemble_with(base, lib, child);
  const int c = lib.add(child).id;
  EXPECT_EQ(segment_closure(lib, c), (std::vector<int>{r, c}));
  const Part after = assemble_part(base, lib, segment_closure(lib, c));
  ASSERT_EQ(before.size(), 5);
  ASSERT_EQ(after.size(), before.size());
  for (int i = 0; i < before.size(); ++i) {
    EXPECT_EQ(before.tabs[i].parent, after.tabs[i].parent) << "tab " << i;
    EXPECT_EQ(before.tabs[i].parent_edge, after.tabs[i].parent_edge) << "tab " << i;
  }
  // A root segment hangs from the base tab.
  const Part root_only = assemble_with(base, lib, crafted(0.9, 2, 1));
  ASSERT_EQ(root_only.size(), 2);
  EXPECT_EQ(root_only.tabs[1].parent, 0);
}

// Pooling two libraries (a seed retry, docs/pipeline.md step 4d): a copy into
// an empty pool keeps the ids; then the other library's segments come with new
// ids and their parents remapped, an identical segment (a web root every pass
// builds alike) is shared with its children hanging from the pooled one, and a
// childless near-duplicate connection is left out.
TEST(SegmentLibrary, AbsorbPoolsAnotherLibrary) {
  LibraryOptions o;
  o.max_per_rivet_area = 2;  // the cap is the admission's, not the pool's
  SegmentLibrary first(o), second(o), pool;
  Segment web = crafted(0, -1, 1);
  web.root_a = Vec3(0, 0, 0);
  web.root_b = Vec3(0.1, 0, 0);
  const int w = first.add(web).id;
  Segment a = crafted(0.3, 0, 1);
  a.parent = w;
  first.add(a);
  first.add(crafted(0.6, 0, 1));

  const int w2 = second.add(web).id;           // the same web root
  Segment b = crafted(1.0, 0, 1);              // far from every segment of `first`
  b.parent = w2;
  const int b_id = second.add(b).id;
  second.add(crafted(0.605, 0, 2));            // 1 cm from `first`'s third: a near-duplicate
  Segment grandchild = crafted(1.5, 1, 1);
  grandchild.parent = b_id;
  second.add(grandchild);

  EXPECT_EQ(pool.absorb(first), 3);
  EXPECT_EQ(pool.options().max_per_rivet_area, 2);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(pool.segments()[i].id, first.segments()[i].id);
  EXPECT_EQ(pool.absorb(second), 2);  // b and its child; the web root is shared, the duplicate left out
  ASSERT_EQ(pool.size(), 5);
  const Segment& pb = pool.segments()[3];
  const Segment& pg = pool.segments()[4];
  EXPECT_EQ(pb.id, 3);
  EXPECT_EQ(pb.parent, w);  // hangs from the pooled web root
  EXPECT_DOUBLE_EQ(pb.raw_root_mid.x(), 1.0);
  EXPECT_EQ(pg.parent, pb.id);
  EXPECT_EQ(pool.counts_per_rivet_area(2), (std::vector<int>{3, 1}));  // over the cap of 2
  EXPECT_EQ(segment_closure(pool, pg.id), (std::vector<int>{w, 3, 4}));
}

}  // namespace
}  // namespace sheetgen
