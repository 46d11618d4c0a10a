#include "sheetgen/part/press_brake.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>

#include "sheetgen/core/polygon_geometry.hpp"
#include "sheetgen/part/clear_states.hpp"
#include "sheetgen/part/realisation.hpp"

namespace sheetgen {

namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kFar = 10.0;  // m, half-length along Z of the ram and the bed (they span the machine)

// ---- the standard tools

std::vector<Vec2> quad(Vec2 a, Vec2 b, Vec2 c, Vec2 d) { return {a, b, c, d}; }

std::string degrees(double rad) { return std::to_string(static_cast<int>(std::lround(rad / kDeg))); }

// The punch's name: the spec's, else its kind and tip angle, with its height
// when that is not the standard 120 mm (a tool set may hold a tall one too).
std::string punch_name(const PunchSpec& s) {
  if (!s.name.empty()) return s.name;
  std::string n = (s.kind == PunchKind::Straight ? "straight " : "gooseneck ") + degrees(s.tip_angle) + " deg";
  if (std::abs(s.height - 0.120) > 1e-6) n += " " + std::to_string(static_cast<int>(std::lround(s.height * 1e3))) + " mm";
  return n;
}

// Straight punch: the tip wedge up to where it is body_width wide, then the body.
PunchTool straight_punch(const PunchSpec& s) {
  const double tau = std::tan(s.tip_angle / 2), b = s.body_width / 2, hw = b / tau;
  PunchTool p{punch_name(s), {}, s.tip_angle, s.height};
  p.pieces.push_back({Vec2(0, 0), Vec2(b, hw), Vec2(-b, hw)});
  p.pieces.push_back(quad(Vec2(-b, hw), Vec2(b, hw), Vec2(b, s.height), Vec2(-b, s.height)));
  return p;
}

// Gooseneck: a short tip wedge, a slender column along the wedge's -X face and
// a head reaching back over +X: the space between (the throat, throat_bottom
// to throat_top above the tip on +X) takes a return flange. Every piece lies
// inside the tip's cone, so the bend's own flanges, outside that cone, clear them all.
PunchTool gooseneck_punch(const PunchSpec& s) {
  const double tau = std::tan(s.tip_angle / 2), h1 = s.throat_bottom, h2 = s.throat_top, c = 2 * h1 * tau;
  PunchTool p{punch_name(s), {}, s.tip_angle, s.height};
  p.pieces.push_back({Vec2(0, 0), Vec2(h1 * tau, h1), Vec2(-h1 * tau, h1)});
  p.pieces.push_back(quad(Vec2(-h1 * tau, h1), Vec2(h1 * tau, h1), Vec2(-h2 * tau + c, h2), Vec2(-h2 * tau, h2)));
  const double reach = h2 * tau;  // the head's overhang on +X: the cone's half-width at the throat's top
  p.pieces.push_back(quad(Vec2(-h2 * tau, h2), Vec2(reach, h2), Vec2(reach, s.height), Vec2(-s.height * tau, s.height)));
  return p;
}

DieTool v_die(const PressBrakeTooling& tooling, const DieSpec& s, double t) {
  const double v = die_opening(tooling, s, t);
  std::string name = s.name;
  if (name.empty()) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "V%.3g %.0f deg", v * 1e3, s.angle / kDeg);
    name = buf;
  }
  return DieTool{name, v, s.angle, s.height, s.width > 0 ? s.width : std::max(0.030, 3 * v), s.min_flange_ratio};
}

// ---- geometry in the tool frame

struct Prism {  // a convex profile (CCW in X, Y) extruded over [z0, z1]
  std::vector<Vec2> profile;
  double z0 = 0, z1 = 0;
  std::vector<std::vector<Vec3>> faces;
  std::vector<Vec3> normals;            // outward, unit
  std::vector<double> offsets;          // of each face's plane: dot(normals[f], x) = offsets[f] on it
  BoundingBox box;                      // of the prism
  std::vector<BoundingBox> face_boxes;  // of each face
};

// `p` becomes `profile` extruded over [z0, z1], in the storage it has: a
// bend check refills its tools for every punch, die and side it tries, and
// fresh faces each time were most of the check's allocations.
void fill_prism(Prism& p, const std::vector<Vec2>& profile, double z0, double z1) {
  const size_t n = profile.size();
  p.profile = profile;
  p.z0 = z0;
  p.z1 = z1;
  p.faces.resize(n + 2);
  p.normals.resize(n + 2);
  std::vector<Vec3>& bottom = p.faces[n];
  std::vector<Vec3>& top = p.faces[n + 1];
  bottom.resize(n);
  top.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const Vec2 a = profile[i], b = profile[(i + 1) % n];
    p.faces[i].assign({Vec3(a.x(), a.y(), z0), Vec3(b.x(), b.y(), z0), Vec3(b.x(), b.y(), z1), Vec3(a.x(), a.y(), z1)});
    p.normals[i] = Vec3(b.y() - a.y(), a.x() - b.x(), 0).normalized();
    bottom[i] = Vec3(profile[n - 1 - i].x(), profile[n - 1 - i].y(), z0);
    top[i] = Vec3(a.x(), a.y(), z1);
  }
  p.normals[n] = -Vec3::UnitZ();
  p.normals[n + 1] = Vec3::UnitZ();
  p.offsets.resize(n + 2);
  for (size_t f = 0; f < n + 2; ++f) p.offsets[f] = p.normals[f].dot(p.faces[f][0]);
  p.face_boxes.resize(n + 2);
  p.box = BoundingBox();
  for (size_t f = 0; f < n + 2; ++f) {
    BoundingBox b;
    for (const Vec3& v : p.faces[f]) b.extend(v);
    p.face_boxes[f] = b;
    p.box.extend(b);
  }
}

std::vector<Vec2> mirrored(const std::vector<Vec2>& profile) {
  std::vector<Vec2> m;
  for (auto it = profile.rbegin(); it != profile.rend(); ++it) m.push_back(Vec2(-it->x(), it->y()));
  return m;
}

// A lower bound on the distance from a polygon to a prism, m: how far the
// whole polygon lies outside the plane of one of the prism's faces (a
// separating plane; 0 or less when there is none among them). The polygon
// near a tool's bounding box is mostly beside a slanted face of it (the
// punch's tip, the die's V), where the box says nothing and this settles it.
double separating_face_gap(const std::vector<Vec3>& polygon, const Prism& prism) {
  double best = -std::numeric_limits<double>::infinity();
  for (size_t f = 0; f < prism.normals.size(); ++f) {
    double outside = std::numeric_limits<double>::infinity();
    for (const Vec3& v : polygon) outside = std::min(outside, prism.normals[f].dot(v) - prism.offsets[f]);
    best = std::max(best, outside);
  }
  return best;
}

// Distance from a convex planar polygon to a prism, m (0 when inside or
// crossing): exact below `stop_below`; at or above it, possibly only a lower
// bound (the gap between bounding boxes, or a separating face plane), which answers "closer than
// stop_below?" the same way at a fraction of the cost: most tabs are far
// from most tools. `pb` is the polygon's bounding box.
double polygon_prism_distance(const std::vector<Vec3>& polygon, const BoundingBox& pb, const Vec3& normal,
                              const Prism& prism, double stop_below) {
  const double gap = box_gap(pb, prism.box);
  if (gap >= stop_below) return gap;
  const double apart = separating_face_gap(polygon, prism);
  if (apart >= stop_below) return apart;
  for (const Vec3& v : polygon)
    if (v.z() >= prism.z0 && v.z() <= prism.z1 && point_in_convex(Vec2(v.x(), v.y()), prism.profile)) return 0;
  double d = std::numeric_limits<double>::infinity();
  for (size_t f = 0; f < prism.faces.size() && d >= stop_below; ++f) {
    const double face_gap = box_gap(pb, prism.face_boxes[f]);
    if (face_gap >= stop_below) {
      d = std::min(d, face_gap);
      continue;
    }
    d = std::min(d, convex_polygon_distance(polygon, normal, prism.faces[f], prism.normals[f], stop_below));
  }
  return d;
}

// The tool frame of bend `k` at its current angle `a` (signed) in `rp`.
struct ToolFrame {
  Vec3 origin, x, y, z;
  Vec3 point(const Vec3& p) const { const Vec3 r = p - origin; return Vec3(r.dot(x), r.dot(y), r.dot(z)); }
  Vec3 vector(const Vec3& v) const { return Vec3(v.dot(x), v.dot(y), v.dot(z)); }
};

ToolFrame tool_frame(const RealisedPart& rp, const Part& part, int k, double a) {
  const RealisedTab& tab = rp.tabs[k];
  const Vec3 z = tab.x_axis;
  const Vec3 n_par = rp.tabs[part.tabs[k].parent].normal;
  const Vec3 u_p = n_par.cross(z);  // in the parent's plane, away from the bend line
  const Vec3 n_in = part.tabs[k].params.theta3 >= 0 ? n_par : Vec3(-n_par);  // the inside of the bend
  const double h = std::abs(a) / 2;
  return ToolFrame{tab.origin, std::sin(h) * n_in - std::cos(h) * u_p, std::cos(h) * n_in + std::sin(h) * u_p, z};
}

// How far a tab reaches from the bend line (o, along z, length L) in its own
// plane (direction u) at the point s along the line, m.
double flange_depth_at(const std::vector<Vec3>& corners, const Vec3& o, const Vec3& z, const Vec3& u, double s0) {
  double reach = 0;
  for (size_t i = 0; i < corners.size(); ++i) {
    const Vec3 p = corners[i] - o, q = corners[(i + 1) % corners.size()] - o;
    const double sp = p.dot(z), sq = q.dot(z);
    if ((sp - s0) * (sq - s0) > 0 || sp == sq) continue;
    const double f = (s0 - sp) / (sq - sp);
    reach = std::max(reach, p.dot(u) + f * (q.dot(u) - p.dot(u)));
  }
  return reach;
}

// A flange's reach from the bend line at 40 points along it, m.
constexpr int kFlangePoints = 40;
using FlangeDepths = std::array<double, kFlangePoints>;
FlangeDepths flange_depths(const std::vector<Vec3>& corners, const Vec3& o, const Vec3& z, const Vec3& u, double L) {
  FlangeDepths at;
  for (int i = 0; i < kFlangePoints; ++i) at[i] = flange_depth_at(corners, o, z, u, (i + 0.5) / kFlangePoints * L);
  return at;
}

// A flange over the die: the share of the bend line along which it reaches
// `need`, and its deepest reach (m).
struct FlangeReach {
  double share = 0, deepest = 0;
};
FlangeReach flange_reach(const FlangeDepths& depths, double need) {
  FlangeReach r;
  for (double d : depths) {
    r.deepest = std::max(r.deepest, d);
    if (d >= need) r.share += 1.0 / kFlangePoints;
  }
  return r;
}

// The highest Y of segment a-b where |X| <= half_width (0 when it misses the slab).
double highest_in_slab(const Vec3& a, const Vec3& b, double half_width) {
  double t0 = 0, t1 = 1;
  const double dx = b.x() - a.x();
  for (double bound : {-half_width, half_width}) {
    const bool upper = bound > 0;
    if (dx == 0) {
      if (upper ? a.x() > bound : a.x() < bound) return 0;
      continue;
    }
    const double t = (bound - a.x()) / dx;
    if ((dx > 0) == upper) t1 = std::min(t1, t);
    else t0 = std::max(t0, t);
  }
  if (t0 > t1) return 0;
  return std::max(a.y() + t0 * (b.y() - a.y()), a.y() + t1 * (b.y() - a.y()));
}

// ---- one bend with one punch and die

struct Attempt {
  std::string reason;      // "" when the bend can be made
  // How far it got: 0 the angles, 1 the flanges, 2 the open press, 3 to 4
  // through the stroke; kMade when the bend can be made.
  double progress = 0;
  double flange_need = 0;  // m, the die's shortest flange when that rule failed
};

constexpr double kMade = 5;

// Which failure to report: the one that got furthest; among flange failures,
// the one of the die with the shortest flange (the smallest die).
bool nearer(const Attempt& a, const Attempt& than) {
  if (a.progress != than.progress) return a.progress > than.progress;
  return a.flange_need > 0 && (than.flange_need == 0 || a.flange_need < than.flange_need);
}

class BendCheck {
 public:
  BendCheck(const Part& part, const SheetSpec& spec, const ToolSet& tools, std::vector<double> angles, int k)
      : part_(part), t_(spec.thickness), tools_(tools), k_(k), parent_(part.tabs[k].parent) {
    ro_.angles = std::move(angles);
    moves_.assign(part.size(), 0);
    moves_[k] = 1;
    for (int i = k + 1; i < part.size(); ++i) moves_[i] = moves_[part.tabs[i].parent];  // parents come first
  }

  Attempt run(int p, int d, bool flipped) {
    const PunchTool& punch = tools_.punches[p];
    const DieTool& die = tools_.dies[d];
    if (std::string r = angle_rule(punch, die); !r.empty()) return {r, 0};
    flat_state();
    if (std::string r = flange_rule(die); !r.empty()) return {r, 1, die.min_flange_ratio * die.v_opening};
    if (std::string r = fits_open_press(punch, die); !r.empty()) return {r, 2};
    build_tools(p, d, flipped);
    const double target = part_.tabs[k_].params.theta3;
    const int steps = std::max(1, static_cast<int>(std::ceil(std::abs(target) / tools_.max_step)));
    clear_until_.assign(part_.size() * prism_count(), -1);
    for (int s = 0; s <= steps; ++s) {
      if (std::string r = collision(s, steps, punch, die); !r.empty()) {
        char at[64];
        std::snprintf(at, sizeof at, " at %.0f deg of its %.0f deg", std::abs(target * s / steps) / kDeg,
                      std::abs(target) / kDeg);
        return {r + at, 3 + static_cast<double>(s + 1) / (steps + 1)};
      }
    }
    return {"", kMade};
  }

 private:
  // The part in one state of the stroke, in the tool frame. It does not depend
  // on the punch, the die or the side, so each state is computed once per bend
  // and shared by every tool combination tried (up to punches x dies x 2).
  struct Pose {
    std::vector<std::vector<Vec3>> corners;  // per tab
    std::vector<Vec3> normals;
    std::vector<BoundingBox> boxes;
  };

  // A punch with the ram above it; a die with the bed below it (build_tools).
  struct PunchSide {
    std::vector<Prism> pieces;
    Prism ram;
  };
  struct DieSide {
    std::vector<Prism> halves;
    Prism bed;
  };

  // rp_ with the bend still flat (the flange and open-press rules, the tools' placement).
  void flat_state() {
    if (flat_) return;
    ro_.angles[k_] = 0;
    realise_into(part_, rp_, ro_);
    flat_ = true;
    // The flanges' reach does not depend on the die: measured once for all.
    const RealisedTab& tab = rp_.tabs[k_];
    const double L = (tab.bend_end() - tab.origin).norm();
    const Vec3 z = tab.x_axis, n_par = rp_.tabs[parent_].normal;
    child_depths_ = flange_depths(tab.corners, tab.origin, z, z.cross(n_par), L);
    parent_depths_ = flange_depths(rp_.tabs[parent_].corners, tab.origin, z, n_par.cross(z), L);
  }

  // State s of `steps` along the stroke (bend angle theta3 * s / steps), realised.
  const Pose& pose(int s, int steps) {
    if (poses_.empty()) poses_.resize(steps + 1);
    Pose& p = poses_[s];
    if (!p.corners.empty()) return p;
    realised_pose(s, steps, p);
    // Turning about Z keeps each corner's distance from it: any state gives the radii.
    if (radius_.empty())
      for (const std::vector<Vec3>& c : p.corners) {
        double r = 0;
        for (const Vec3& v : c) r = std::max(r, std::hypot(v.x(), v.y()));
        radius_.push_back(r);
      }
    return p;
  }

  // Tab i in state s, in the tool frame: turned from the flat state when
  // skipping clear states, else from the state realised anew.
  struct TabView {
    const std::vector<Vec3>* corners;
    Vec3 normal;
    BoundingBox box;
  };
  TabView tab_in_state(int i, int s, int steps) {
    if (s == 0 || !tools_.skip_clear_states) {
      const Pose& p = pose(s, steps);
      return {&p.corners[i], p.normals[i], p.boxes[i]};
    }
    const Pose& flat = pose(0, steps);
    if (turned_state_ != s) {
      const double h = std::abs(part_.tabs[k_].params.theta3 * s / steps) / 2;
      cos_ = std::cos(h);
      sin_ = std::sin(h);
      turned_state_ = s;
    }
    // The tool frame halves the bend, so in it the bent tab's subtree turns
    // about Z by +a/2 and the rest of the part by -a/2 (a the bend angle;
    // docs/manufacturing.md derives the signs): the corners realised_pose
    // gives, to rounding, without realising the part.
    const double c = cos_, sn = moves_[i] ? sin_ : -sin_;
    auto turn = [&](const Vec3& v) { return Vec3(c * v.x() - sn * v.y(), sn * v.x() + c * v.y(), v.z()); };
    const std::vector<Vec3>& from = flat.corners[i];
    turned_.resize(from.size());
    TabView v{&turned_, turn(flat.normals[i]), BoundingBox()};
    for (size_t j = 0; j < from.size(); ++j) v.box.extend(turned_[j] = turn(from[j]));
    return v;
  }

  // State s realised anew and taken into its tool frame.
  void realised_pose(int s, int steps, Pose& p) {
    ro_.angles[k_] = part_.tabs[k_].params.theta3 * s / steps;
    realise_into(part_, pose_rp_, ro_);
    const ToolFrame f = tool_frame(pose_rp_, part_, k_, ro_.angles[k_]);
    p.corners.reserve(pose_rp_.tabs.size());
    p.normals.reserve(pose_rp_.tabs.size());
    p.boxes.reserve(pose_rp_.tabs.size());
    for (const RealisedTab& tab : pose_rp_.tabs) {
      std::vector<Vec3> c;
      c.reserve(tab.corners.size());
      BoundingBox b;
      for (const Vec3& v : tab.corners) b.extend(c.emplace_back(f.point(v)));
      p.corners.push_back(std::move(c));
      p.normals.push_back(f.vector(tab.normal));
      p.boxes.push_back(b);
    }
  }

  std::string angle_rule(const PunchTool& punch, const DieTool& die) const {
    const double inner = M_PI - std::abs(part_.tabs[k_].params.theta3) - tools_.springback;
    char buf[160];
    if (inner < punch.tip_angle || inner < die.angle) {
      if (inner < punch.tip_angle)
        std::snprintf(buf, sizeof buf, "the bend closes to %.0f deg under load, less than the punch %s's tip",
                      inner / kDeg, punch.name.c_str());
      else
        std::snprintf(buf, sizeof buf, "the bend closes to %.0f deg under load, less than the die %s's V",
                      inner / kDeg, die.name.c_str());
      return buf;
    }
    return "";
  }

  // Each flange must rest on the die's shoulder along at least half of the
  // bend line: a tab cut on a slant is short near one end and still bends.
  std::string flange_rule(const DieTool& die) const {
    const double need = die.min_flange_ratio * die.v_opening;
    const FlangeReach child = flange_reach(child_depths_, need);
    const FlangeReach parent = flange_reach(parent_depths_, need);
    const bool child_short = child.share < 0.5;
    if (!child_short && parent.share >= 0.5) return "";
    const FlangeReach& f = child_short ? child : parent;
    char buf[240];
    std::snprintf(buf, sizeof buf,
                  "the flange of tab %d reaches %.1f x V = %.1f mm on the die %s along %.0f %% of the bend line, "
                  "not half (it is %.1f mm deep at most)",
                  child_short ? k_ : parent_, die.min_flange_ratio, need * 1e3, die.name.c_str(), 100 * f.share,
                  f.deepest * 1e3);
    return buf;
  }

  // Only what lies under the ram must pass below the open punch: the rest of
  // the part stands in front of the machine or behind it.
  std::string fits_open_press(const PunchTool& punch, const DieTool& die) const {
    const ToolFrame f = tool_frame(rp_, part_, k_, 0);
    const double rw = tools_.machine.ram_width / 2;
    double top = 0;
    for (const RealisedTab& tab : rp_.tabs)
      for (size_t i = 0; i < tab.corners.size(); ++i) {
        const Vec3 a = f.point(tab.corners[i]), b = f.point(tab.corners[(i + 1) % tab.corners.size()]);
        top = std::max(top, highest_in_slab(a, b, rw));
      }
    const double room = tools_.machine.open_height - die.height - punch.height;
    if (top + t_ / 2 <= room) return "";
    char buf[160];
    std::snprintf(buf, sizeof buf, "the part stands %.0f mm above the die, more than the %.0f mm under the open punch",
                  (top + t_ / 2) * 1e3, room * 1e3);
    return buf;
  }

  // The punch (with the ram above it) and the die (with the bed below it) of
  // a run, in the tool frame: each is drawn once per bend and kept, since the
  // runs try every punch with every die on both sides.
  void build_tools(int p, int d, bool flipped) {
    if (punch_sides_.empty()) {
      punch_sides_.resize(2 * tools_.punches.size());
      die_sides_.resize(tools_.dies.size());
    }
    PunchSide& punch = punch_sides_[2 * p + flipped];
    if (punch.pieces.empty()) draw_punch(tools_.punches[p], flipped, punch);
    DieSide& die = die_sides_[d];
    if (die.halves.empty()) draw_die(tools_.dies[d], die);
    punch_ = &punch;
    die_ = &die;
  }

  void draw_punch(const PunchTool& punch, bool flipped, PunchSide& side) {
    const RealisedTab& tab = rp_.tabs[k_];
    const double L = (tab.bend_end() - tab.origin).norm(), top = t_ / 2;
    // Segmented (box-and-pan) punches are set up a little shorter than the
    // bend line, so that flanges standing at its ends, a box's sides, clear
    // them: the punch stops the clearance short of each end.
    const double inset = std::min(t_ / 2 + tools_.gap + 1e-6, 0.25 * L);
    side.pieces.resize(punch.pieces.size());
    for (size_t i = 0; i < punch.pieces.size(); ++i) {
      std::vector<Vec2> shifted;
      for (const Vec2& v : punch.pieces[i]) shifted.push_back(v + Vec2(0, top));
      fill_prism(side.pieces[i], flipped ? mirrored(shifted) : shifted, inset, L - inset);
    }
    const double rw = tools_.machine.ram_width / 2;
    fill_prism(side.ram, quad(Vec2(-rw, top + punch.height), Vec2(rw, top + punch.height), Vec2(rw, top + punch.height + 1),
                              Vec2(-rw, top + punch.height + 1)), -kFar, kFar);
  }

  void draw_die(const DieTool& die, DieSide& side) {
    const RealisedTab& tab = rp_.tabs[k_];
    const double L = (tab.bend_end() - tab.origin).norm(), bottom = -t_ / 2;
    // The die's top a hair below the clearance: the flat sheet lies on it by design.
    const double v = die.v_opening / 2, depth = v / std::tan(die.angle / 2), w = die.width / 2, h = die.height;
    const double seat = bottom - tools_.gap - 1e-6;
    const std::vector<Vec2> left = {Vec2(-w, bottom - h), Vec2(0, bottom - h), Vec2(0, seat - depth),
                                    Vec2(-v, seat), Vec2(-w, seat)};
    side.halves.resize(2);
    fill_prism(side.halves[0], left, 0, L);
    fill_prism(side.halves[1], mirrored(left), 0, L);
    const double bw = tools_.machine.bed_width / 2;
    fill_prism(side.bed, quad(Vec2(-bw, bottom - h - 1), Vec2(bw, bottom - h - 1), Vec2(bw, bottom - h),
                              Vec2(-bw, bottom - h)), -kFar, kFar);
  }

  // Punch pieces, the die's two halves, the ram and the bed.
  int prism_count() const { return static_cast<int>(punch_->pieces.size()) + 4; }

  // The first tab too close to a tool or the machine in state s of `steps`.
  //
  // Conservative advancement: in the tool frame every tab turns about the
  // bend line (Z) by half the bend's step from one state to the next, so a
  // point at radius r from that line moves at most r * step / 2. A tab found
  // d >= need from a tool is therefore clear of it for the next
  // (d - need) / (r * step / 2) states, which are not looked at (nor, when
  // every pair is clear, realised). Only states provably clear are skipped,
  // so the first collision found, and its message, are the same as when
  // every state is checked.
  std::string collision(int s, int steps, const PunchTool& punch, const DieTool& die) {
    const double need = t_ / 2 + tools_.gap;
    const double half_step = std::abs(part_.tabs[k_].params.theta3) / steps / 2;
    const int np = prism_count(), n_punch = static_cast<int>(punch_->pieces.size());
    for (int i = 0; i < part_.size(); ++i) {
      const bool own = i == k_ || i == parent_;  // the bend's flanges touch punch tip and die by design
      std::optional<TabView> tab;  // tab i in state s, placed when a pair needs it
      for (int j = 0; j < np; ++j) {
        const bool tool = j < n_punch + 2;
        if (own && tool) continue;
        int& until = clear_until_[i * np + j];
        if (until >= s) continue;
        if (!tab) tab = tab_in_state(i, s, steps);
        const Prism& prism = j < n_punch       ? punch_->pieces[j]
                             : j < n_punch + 2 ? die_->halves[j - n_punch]
                             : j == n_punch + 2 ? punch_->ram
                                                : die_->bed;
        const double d = polygon_prism_distance(*tab->corners, tab->box, tab->normal, prism, need);
        if (d < need) return hit_message(i, j, punch, die);
        if (tools_.skip_clear_states) until = s + clear_states(d - need, radius_[i] * half_step, steps);
      }
    }
    return "";
  }

  std::string hit_message(int i, int j, const PunchTool& punch, const DieTool& die) const {
    const int n_punch = static_cast<int>(punch_->pieces.size());
    char buf[160];
    if (j < n_punch) std::snprintf(buf, sizeof buf, "tab %d hits the punch %s", i, punch.name.c_str());
    else if (j < n_punch + 2) std::snprintf(buf, sizeof buf, "tab %d hits the die %s", i, die.name.c_str());
    else if (j == n_punch + 2) std::snprintf(buf, sizeof buf, "tab %d hits the ram above the punch", i);
    else std::snprintf(buf, sizeof buf, "tab %d hits the bed below the die", i);
    return buf;
  }

  const Part& part_;
  double t_;
  const ToolSet& tools_;
  int k_, parent_;
  RealiseOptions ro_;
  RealisedPart rp_;       // the bend flat (flat_state)
  bool flat_ = false;
  FlangeDepths child_depths_{}, parent_depths_{};  // of the bent tab and its parent (flat_state)
  RealisedPart pose_rp_;  // scratch for pose()
  std::vector<Pose> poses_;  // realised states (the flat one only, when skipping clear states)
  std::vector<Vec3> turned_;          // scratch of tab_in_state()
  int turned_state_ = -1;             // the state cos_ and sin_ are of
  double cos_ = 1, sin_ = 0;
  std::vector<PunchSide> punch_sides_;  // per punch and side (2 p + flipped), drawn when first tried
  std::vector<DieSide> die_sides_;      // per die, drawn when first tried
  const PunchSide* punch_ = nullptr;    // of the current run (build_tools)
  const DieSide* die_ = nullptr;
  std::vector<double> radius_;       // m, per tab: its farthest corner from the bend line (any state)
  std::vector<char> moves_;          // per tab: in the bent tab's subtree
  std::vector<int> clear_until_;     // per tab and prism: the last state known clear (collision())
};

}  // namespace

ToolSet make_tool_set(const PressBrakeTooling& tooling, double t) {
  ToolSet s;
  for (const PunchSpec& p : tooling.punches)
    s.punches.push_back(p.kind == PunchKind::Straight ? straight_punch(p) : gooseneck_punch(p));
  for (const DieSpec& d : tooling.dies) s.dies.push_back(v_die(tooling, d, t));
  s.machine = PressBrakeMachine{tooling.ram_width, tooling.bed_width, tooling.open_height};
  s.springback = tooling.springback;
  return s;
}

ToolSet standard_tool_set(double t) { return make_tool_set(default_press_brake_tooling(), t); }

BendToolChoice choose_bend_tools(const Part& part, int k, const std::vector<double>& angles, const SheetSpec& spec,
                                 const ToolSet& tools) {
  if (tools.punches.empty() || tools.dies.empty()) throw std::invalid_argument("press brake: an empty tool set");
  if (k <= 0 || k >= part.size() || static_cast<int>(angles.size()) != part.size())
    throw std::invalid_argument("press brake: tab " + std::to_string(k) + " is not a bend of the part");
  BendCheck check(part, spec, tools, angles, k);
  Attempt nearest{"", -1};
  for (size_t p = 0; p < tools.punches.size(); ++p)
    for (size_t d = 0; d < tools.dies.size(); ++d)
      for (bool flipped : {false, true}) {
        const Attempt a = check.run(static_cast<int>(p), static_cast<int>(d), flipped);
        if (a.reason.empty()) return {true, {k, static_cast<int>(p), static_cast<int>(d), flipped}, ""};
        if (nearer(a, nearest)) nearest = a;
      }
  return {false, {k, -1, -1, false}, "bend of tab " + std::to_string(k) + ": " + nearest.reason};
}

PressBrakeResult check_press_brake(const Part& part, const std::vector<int>& order, const SheetSpec& spec,
                                   const ToolSet& tools) {
  PressBrakeResult r;
  std::vector<double> angles(part.size(), 0.0);
  for (int k : order) {
    const BendToolChoice c = choose_bend_tools(part, k, angles, spec, tools);
    if (!c.ok) {
      r.failed_tab = k;
      r.message = c.reason;
      return r;
    }
    r.tooling.push_back(c.tooling);
    angles[k] = part.tabs[k].params.theta3;
  }
  r.ok = true;
  return r;
}

}  // namespace sheetgen
