// The only OpenCASCADE code of sheetgen (docs/code-style.md point 5). How the
// solids are built and why: docs/cad.md.
#include "sheetgen/cad/step_export.hpp"

#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepLib.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepOffsetAPI_MakeOffsetShape.hxx>
#include <BRepOffsetAPI_MakeThickSolid.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GCE2d_MakeSegment.hxx>
#include <GProp_GProps.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Poly_Triangulation.hxx>
#include <STEPControl_Writer.hxx>
#include <ShapeFix_Face.hxx>
#include <ShapeFix_Shape.hxx>
#include <ShapeUpgrade_UnifySameDomain.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <TopoDS_Wire.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <gp_Ax3.hxx>
#include <gp_Circ.hxx>
#include <gp_Pln.hxx>
#include <gp_Trsf.hxx>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <mutex>
#include <map>
#include <stdexcept>

#include "sheetgen/core/atomic_file.hpp"
#include "sheetgen/core/polygon_geometry.hpp"

namespace sheetgen {

namespace {

constexpr double kMm = 1e3;  // the files are in mm, the project in m

gp_Pnt mm(const Vec3& p) { return gp_Pnt(p.x() * kMm, p.y() * kMm, p.z() * kMm); }
gp_Dir dir(const Vec3& v) { return gp_Dir(v.x(), v.y(), v.z()); }

// The flat sheet as one planar face in z = 0 (mm, top side +z): the outline
// (counter-clockwise) with a circular hole per rivet hole; `shift` (m) is
// subtracted from every point (flat.dxf's drawing origin, or zero).
TopoDS_Face flat_face(const FlatPattern& flat, const std::vector<RivetHole>& holes, const Vec2& shift) {
  BRepBuilderAPI_MakePolygon poly;
  for (const Vec2& q : flat.outline) poly.Add(gp_Pnt((q.x() - shift.x()) * kMm, (q.y() - shift.y()) * kMm, 0));
  poly.Close();
  if (!poly.IsDone()) throw StepGeometryError("the flat outline is not a closed polygon");
  BRepBuilderAPI_MakeFace face(gp_Pln(gp::XOY()), poly.Wire(), true);
  for (const RivetHole& h : holes) {
    const gp_Pnt c((h.flat.x() - shift.x()) * kMm, (h.flat.y() - shift.y()) * kMm, 0);
    const gp_Circ circle(gp_Ax2(c, gp::DZ()), 0.5 * h.diameter * kMm);
    const TopoDS_Wire w = BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(circle).Edge()).Wire();
    face.Add(TopoDS::Wire(w.Reversed()));  // a hole runs clockwise seen from the top
  }
  if (!face.IsDone()) throw StepGeometryError("the flat outline does not make a face");
  ShapeFix_Face fix(face.Face());  // orients the hole wires whatever their start
  fix.Perform();
  return fix.Face();
}

// A polygon face in z = 0 from flat points (m).
TopoDS_Face polygon_face(const std::vector<Vec2>& pts) {
  BRepBuilderAPI_MakePolygon poly;
  for (const Vec2& q : pts) poly.Add(gp_Pnt(q.x() * kMm, q.y() * kMm, 0));
  poly.Close();
  return BRepBuilderAPI_MakeFace(gp_Pln(gp::XOY()), poly.Wire(), true).Face();
}

std::vector<TopoDS_Face> faces_of(const TopoDS_Shape& s) {
  std::vector<TopoDS_Face> out;
  for (TopExp_Explorer x(s, TopAbs_FACE); x.More(); x.Next()) out.push_back(TopoDS::Face(x.Current()));
  return out;
}

// A point strictly inside a face in z = 0, in m: the centroid of one triangle of its mesh
// (the face's centroid may lie in a notch or a hole).
Vec2 interior_point(const TopoDS_Face& face) {
  BRepMesh_IncrementalMesh mesh(face, 0.5);  // mm; any mesh will do
  TopLoc_Location loc;
  const Handle(Poly_Triangulation) tri = BRep_Tool::Triangulation(face, loc);
  if (tri.IsNull() || tri->NbTriangles() == 0) throw StepGeometryError("a flat region could not be meshed");
  int a, b, c;
  tri->Triangle(1).Get(a, b, c);
  const gp_XYZ g = (tri->Node(a).XYZ() + tri->Node(b).XYZ() + tri->Node(c).XYZ()) / 3.0;
  return Vec2(g.X(), g.Y()) / kMm;
}

// Bend zone of one bend in the flat (m): the sheet between its two tangent
// lines (-SB and BA - SB from the sharp line), as two convex polygons: the
// tab's own piece up to BA - SB, and the parent's piece from -SB to the sharp
// line across the root J0..J1. The relief notches beside the root make that
// rectangle the whole of the parent's sheet that bends. Where a bend ends at
// its parent's corner (no notch), the parent's sheet beyond the root stays
// flat: the bend is ripped from it along its end line (docs/cad.md).
std::vector<std::vector<Vec2>> bend_zone_polygons(const FlatPattern& flat, const FlatBend& b) {
  const Vec2 E = (b.b - b.a).normalized(), O = b.outward, J0 = b.root_a;
  const double root_width = (b.root_b - b.root_a).dot(E);
  // clip_half_plane keeps n . q >= c; s = (q - J0) . O, a = (q - J0) . E.
  std::vector<Vec2> child = clip_half_plane(flat.pieces[b.tab].polygon, -O, -(J0.dot(O) + b.allowance - b.setback));
  std::vector<Vec2> parent = flat.pieces[b.parent].polygon;
  parent = clip_half_plane(parent, O, J0.dot(O) - b.setback);
  // A bend past ~125 deg has BA < SB: the tab's tangent line lies behind the
  // parent's edge line, and the sheet between them is the tab's flat sheet.
  parent = clip_half_plane(parent, -O, -(J0.dot(O) + std::min(0.0, b.allowance - b.setback)));
  parent = clip_half_plane(parent, E, J0.dot(E));
  parent = clip_half_plane(parent, -E, -(J0.dot(E) + root_width));
  std::vector<std::vector<Vec2>> out;
  for (auto* poly : {&parent, &child})
    if (poly->size() >= 3 && std::abs(signed_area(*poly)) > 1e-12) out.push_back(*poly);  // > 1 mm^2 x 1e-6
  if (out.empty()) throw StepGeometryError("the bend zone of tab " + std::to_string(b.tab) + " is empty");
  return out;
}

// Whether `q` (m) lies in the flat sheet that moves with tab `tab`: its piece,
// and for a bend with BA < SB also the strip behind its root up to its
// tangent line BA - SB, which lies in the parent's piece but is the tab's sheet.
bool in_tab_sheet(const FlatPattern& flat, int tab, const Vec2& q, double tol) {
  const std::vector<Vec2>& poly = flat.pieces[tab].polygon;
  if (poly.size() < 3) return false;
  if (point_in_convex(q, poly, tol)) return true;
  for (const FlatBend& b : flat.bends)
    if (b.tab == tab && b.allowance < b.setback) {
      const Vec2 d = (b.allowance - b.setback) * b.outward;
      std::vector<Vec2> strip = {b.root_b, b.root_a, b.root_a + d, b.root_b + d};
      if (signed_area(strip) < 0) std::reverse(strip.begin(), strip.end());
      return point_in_convex(q, strip, tol);
    }
  return false;
}

// The tab whose flat sheet holds `q` (m): the pieces tile the sheet outside
// the notches; children first, so a strip behind a root goes to its tab.
int piece_at(const FlatPattern& flat, const Vec2& q) {
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (int i = static_cast<int>(flat.pieces.size()) - 1; i >= 0; --i) {
    const std::vector<Vec2>& poly = flat.pieces[i].polygon;
    if (poly.size() < 3) continue;
    if (in_tab_sheet(flat, i, q, 1e-9)) return flat.pieces[i].tab;
    const Vec2 c = polygon_centroid(poly);
    if ((c - q).norm() < best_d) best_d = (c - q).norm(), best = flat.pieces[i].tab;
  }
  return best;
}

// The tab whose plane tab `i` lies in: itself, or for a flat extension (no
// bend) its parent's, up the tree.
int plane_of(const FlatPattern& flat, int i) {
  std::vector<bool> bent(flat.pieces.size(), false);
  for (const FlatBend& b : flat.bends) bent[b.tab] = true;
  while (i > 0 && !bent[i] && flat.pieces[i].parent >= 0) i = flat.pieces[i].parent;
  return i;
}

// A flat region is placed by one tab's motion, so it must lie in that tab's
// plane: every vertex of it in a piece of the same plane (a flat extension
// shares its parent's). Otherwise the bend zones did not separate two tabs
// and the region would be placed half in the wrong plane.
void check_one_plane(const FlatPattern& flat, const TopoDS_Face& region, int tab) {
  const int plane = plane_of(flat, tab);
  for (TopExp_Explorer xv(region, TopAbs_VERTEX); xv.More(); xv.Next()) {
    const gp_Pnt p = BRep_Tool::Pnt(TopoDS::Vertex(xv.Current()));
    const Vec2 q(p.X() / kMm, p.Y() / kMm);
    bool inside = false;
    for (const FlatPiece& pc : flat.pieces)
      if (pc.polygon.size() >= 3 && plane_of(flat, pc.tab) == plane && in_tab_sheet(flat, pc.tab, q, 1e-6)) inside = true;
    if (!inside)
      throw StepGeometryError("the flat region of tab " + std::to_string(tab) + " reaches (" + std::to_string(p.X()) + ", " +
                              std::to_string(p.Y()) + ") mm of the flat, outside its plane's pieces: the bend zones did not separate it");
  }
}

gp_Trsf to_gp(const FlatPieceTransform& m) {
  const Eigen::Matrix3d& R = m.rotation;
  const Vec3 T = m.translation * kMm;
  gp_Trsf t;
  t.SetValues(R(0, 0), R(0, 1), R(0, 2), T.x(), R(1, 0), R(1, 1), R(1, 2), T.y(), R(2, 0), R(2, 1), R(2, 2), T.z());
  return t;
}

// The wire of a bend zone (flat, mm) mapped into the (u, v) plane of its
// cylinder, as edges on `cyl`: counter-clockwise when `outer`, clockwise otherwise.
TopoDS_Wire wrap_wire(const TopoDS_Wire& w, const TopoDS_Face& zone, const Handle(Geom_CylindricalSurface)& cyl,
                      const std::function<gp_Pnt2d(const gp_Pnt&)>& uv, bool outer, int tab) {
  std::vector<gp_Pnt2d> pts;
  for (BRepTools_WireExplorer xe(w, zone); xe.More(); xe.Next()) {
    if (BRepAdaptor_Curve(xe.Current()).GetType() != GeomAbs_Line)
      throw StepGeometryError("a curved edge (a hole?) lies in the bend zone of tab " + std::to_string(tab));
    pts.push_back(uv(BRep_Tool::Pnt(xe.CurrentVertex())));
  }
  double area2 = 0;  // twice the signed area in (u, v)
  for (size_t i = 0; i < pts.size(); ++i) {
    const gp_Pnt2d &p = pts[i], &q = pts[(i + 1) % pts.size()];
    area2 += p.X() * q.Y() - q.X() * p.Y();
  }
  if ((area2 > 0) != outer) std::reverse(pts.begin(), pts.end());
  std::vector<TopoDS_Vertex> verts;
  for (const gp_Pnt2d& p : pts) verts.push_back(BRepBuilderAPI_MakeVertex(cyl->Value(p.X(), p.Y())));
  BRepBuilderAPI_MakeWire wire;
  for (size_t i = 0; i < pts.size(); ++i) {
    const size_t j = (i + 1) % pts.size();
    const Handle(Geom2d_TrimmedCurve) seg = GCE2d_MakeSegment(pts[i], pts[j]).Value();
    wire.Add(BRepBuilderAPI_MakeEdge(seg, cyl, verts[i], verts[j], seg->FirstParameter(), seg->LastParameter()).Edge());
  }
  if (!wire.IsDone()) throw StepGeometryError("the bend zone of tab " + std::to_string(tab) + " is not a closed wire");
  return wire.Wire();
}

// One bend zone (flat, mm) laid on the mid-surface cylinder of its bend (mm, world).
// The cylinder's (u, v) are an affine image of the flat: u = angle = (s + SB) /
// (R + K t), so the neutral fibre keeps the flat length (the bend allowance),
// and v = distance along the axis. Straight flat edges become lines in (u, v),
// i.e. helices on the cylinder (circles where they cross the axis square).
TopoDS_Face wrap_bend_zone(const TopoDS_Face& zone, const FlatBend& b, const FlatPieceTransform& parent, double t) {
  const double theta = std::abs(b.angle), sigma = b.angle > 0 ? 1.0 : -1.0;
  const double neutral = b.allowance / theta;       // m, R + K t
  const double rho = b.inside_radius + 0.5 * t;     // m, mid-surface radius
  const Vec2 E = (b.b - b.a).normalized(), O = b.outward, J0 = b.root_a;
  const Vec3 e_w = parent.rotation * Vec3(E.x(), E.y(), 0), u_w = parent.rotation * Vec3(O.x(), O.y(), 0);
  const Vec3 n_w = parent.rotation.col(2);
  const Vec3 tangent0 = parent.apply(J0 - b.setback * O);  // parent's tangent line at a = 0
  // Axis on the inside of the bend; u = 0 at the parent's tangent line, u grows towards the tab.
  const Vec3 x_dir = -sigma * n_w, z_dir = x_dir.cross(u_w);  // y_dir = z x x = u_w
  const Handle(Geom_CylindricalSurface) cyl =
      new Geom_CylindricalSurface(gp_Ax3(mm(tangent0 + sigma * rho * n_w), dir(z_dir), dir(x_dir)), rho * kMm);
  const double v_sign = e_w.dot(z_dir) > 0 ? 1.0 : -1.0;
  const std::function<gp_Pnt2d(const gp_Pnt&)> uv = [&](const gp_Pnt& p) {  // p: flat, mm
    const Vec2 q = Vec2(p.X(), p.Y()) / kMm - J0;
    return gp_Pnt2d((q.dot(O) + b.setback) / neutral, v_sign * q.dot(E) * kMm);
  };
  const TopoDS_Wire outer = BRepTools::OuterWire(zone);
  BRepBuilderAPI_MakeFace face(cyl, wrap_wire(outer, zone, cyl, uv, true, b.tab), true);
  for (TopExp_Explorer xw(zone, TopAbs_WIRE); xw.More(); xw.Next())
    if (!xw.Current().IsSame(outer)) face.Add(wrap_wire(TopoDS::Wire(xw.Current()), zone, cyl, uv, false, b.tab));
  if (!face.IsDone()) throw StepGeometryError("the bend face of tab " + std::to_string(b.tab) + " could not be built");
  TopoDS_Face f = face.Face();
  BRepLib::BuildCurves3d(f, 1e-6);
  ShapeFix_Face fix(f);
  fix.Perform();
  return fix.Face();
}

// The self-rivets' sheets, grouped: tabs joined by self-rivets (directly or
// through another gusset) get the same group number; other tabs -1.
std::vector<int> self_rivet_groups(const FlatPattern& flat, const std::vector<RivetHole>& holes) {
  std::vector<int> root(flat.pieces.size());
  for (size_t i = 0; i < root.size(); ++i) root[i] = static_cast<int>(i);
  auto find = [&](int i) {
    while (root[i] != i) i = root[i] = root[root[i]];
    return i;
  };
  std::vector<bool> joined(root.size(), false);
  for (const RivetHole& h : holes) {
    if (h.kind != RivetKind::Self) continue;
    if (h.tab < 0 || h.other_tab < 0 || h.tab >= static_cast<int>(root.size()) || h.other_tab >= static_cast<int>(root.size()))
      throw std::invalid_argument("self-rivet hole " + hole_label(h) + " names a tab the part does not have");
    root[find(h.tab)] = find(h.other_tab);
    joined[h.tab] = joined[h.other_tab] = true;
  }
  std::vector<int> group(root.size(), -1);
  for (size_t i = 0; i < root.size(); ++i)
    if (joined[i]) group[i] = find(static_cast<int>(i));
  return group;
}

// One face of the flat sheets of a self-rivet group: sheetgen bends both
// gussets of a self-rivet into one common plane (docs/pipeline.md), so they
// overlap there; as two faces the solid would overlap itself, which no CAD
// system accepts. Their union is one plate, the riveted joint as one piece of metal.
std::vector<TopoDS_Face> joined_sheets(const std::vector<TopoDS_Face>& faces) {
  TopTools_ListOfShape args, tools;
  args.Append(faces.front());
  for (size_t i = 1; i < faces.size(); ++i) tools.Append(faces[i]);
  BRepAlgoAPI_Fuse fuse;
  fuse.SetArguments(args);
  fuse.SetTools(tools);
  fuse.SetFuzzyValue(1e-4);  // mm: the common plane is computed twice, once per gusset
  fuse.Build();
  if (!fuse.IsDone() || fuse.HasErrors()) throw StepGeometryError("joining the sheets of a self-rivet failed");
  ShapeUpgrade_UnifySameDomain unify(fuse.Shape(), true, true, false);
  unify.Build();
  return faces_of(unify.Shape());
}

// One face given to sewing and what it is, to name the faces a failed sewing
// left apart.
struct SewnFace {
  TopoDS_Face face;
  std::string what;  // "tab 3", "the bend of tab 3"
};

// "tab 12, the bend of tab 13": the inputs that ended in a shell other than
// the one with the most faces.
std::string apart_from_the_rest(const BRepBuilderAPI_Sewing& sew, const std::vector<TopoDS_Shell>& shells,
                                const std::vector<SewnFace>& inputs) {
  std::vector<TopTools_IndexedMapOfShape> faces(shells.size());
  size_t main = 0;
  for (size_t i = 0; i < shells.size(); ++i) {
    TopExp::MapShapes(shells[i], TopAbs_FACE, faces[i]);
    if (faces[i].Extent() > faces[main].Extent()) main = i;
  }
  std::string out;
  for (const SewnFace& in : inputs) {
    const TopoDS_Shape sewn = sew.IsModified(in.face) ? sew.Modified(in.face) : TopoDS_Shape(in.face);
    for (size_t i = 0; i < shells.size(); ++i)
      if (i != main && faces[i].Contains(sewn)) out += (out.empty() ? "" : ", ") + in.what;
  }
  return out;
}

// The part's mid-surface (mm, world) as one shell: the sheet outside the bend
// zones moved rigidly piece by piece (the sheets of each self-rivet joined),
// every bend zone wrapped onto its cylinder, sewn along the tangent lines
// (where the faces meet tangentially).
// `holes`: those cut in the flat sheet; `group`: self_rivet_groups.
TopoDS_Shell mid_surface(const FlatPattern& flat, const std::vector<RivetHole>& holes, const std::vector<int>& group,
                         const StepExportOptions& o) {
  const TopoDS_Face sheet = flat_face(flat, holes, Vec2::Zero());
  const std::vector<FlatPieceTransform> maps = fold_transforms(flat);
  BRepBuilderAPI_Sewing sew(o.sewing_tolerance * kMm);
  std::vector<SewnFace> inputs;
  const auto add = [&](const TopoDS_Face& f, const std::string& what) {
    sew.Add(f);
    inputs.push_back({f, what});
  };
  TopTools_ListOfShape zones;
  for (const FlatBend& b : flat.bends)
    for (const std::vector<Vec2>& poly : bend_zone_polygons(flat, b)) {
      const TopoDS_Face zone = polygon_face(poly);
      zones.Append(zone);
      add(wrap_bend_zone(zone, b, maps[b.parent], o.thickness), "the bend of tab " + std::to_string(b.tab));
    }
  TopoDS_Shape planar = sheet;
  if (!zones.IsEmpty()) {
    TopTools_ListOfShape args;
    args.Append(sheet);
    BRepAlgoAPI_Cut cut;
    cut.SetArguments(args);
    cut.SetTools(zones);
    // mm. Zone sides lie on the outline's edges, but a bend whose root ends
    // within the unfolding's corner tolerance (FlatPatternOptions::corner_tolerance,
    // 1e-7 m = 1e-4 mm) of its parent edge's end has no relief and its zone
    // stops that far short of the corner: a fuzzy value below it leaves a
    // sliver of sheet there joining the parent's flat region to the tab's, and
    // the two are then placed as one face in the parent's plane (docs/cad.md
    // "Corners within the tolerance"). 1e-3 mm is 10x that tolerance and far
    // below the kerf (0.2 mm), the least real feature of the outline.
    cut.SetFuzzyValue(1e-3);
    cut.Build();
    if (!cut.IsDone() || cut.HasErrors()) throw StepGeometryError("cutting the bend zones out of the flat sheet failed");
    planar = cut.Shape();
  }
  std::map<int, std::vector<TopoDS_Face>> grouped;
  for (const TopoDS_Face& f : faces_of(planar)) {
    const int tab = piece_at(flat, interior_point(f));
    if (tab < 0) throw StepGeometryError("a flat region belongs to no tab");
    check_one_plane(flat, f, tab);
    const TopoDS_Face placed = TopoDS::Face(BRepBuilderAPI_Transform(f, to_gp(maps[tab]), true).Shape());
    if (group[tab] >= 0)
      grouped[group[tab]].push_back(placed);
    else
      add(placed, "tab " + std::to_string(tab));
  }
  for (const auto& g : grouped)
    for (const TopoDS_Face& f : joined_sheets(g.second)) add(f, "the self-riveted plate " + std::to_string(g.first));
  sew.Perform();
  std::vector<TopoDS_Shell> shells;
  for (TopExp_Explorer x(sew.SewedShape(), TopAbs_SHELL); x.More(); x.Next()) shells.push_back(TopoDS::Shell(x.Current()));
  if (shells.size() != 1)
    throw StepGeometryError("the bent sheet sewed into " + std::to_string(shells.size()) + " pieces instead of one (apart from the rest: " +
                            apart_from_the_rest(sew, shells, inputs) + ")");
  return shells[0];
}

// The mid-surface thickened by t/2 to each side. OpenCASCADE's simple offset
// fits: the faces meet tangentially (planes and cylinders, G1 across every
// tangent line), so every face offsets to a face of the same kind and the
// walls along the cut edges are ruled between the two offset edges.
TopoDS_Solid thicken(const TopoDS_Shape& mid, double t_mm) {
  BRepOffsetAPI_MakeOffsetShape bottom;
  bottom.PerformBySimple(mid, -0.5 * t_mm);
  if (!bottom.IsDone()) throw StepGeometryError("offsetting the bent sheet by -t/2 failed");
  BRepOffsetAPI_MakeThickSolid thick;
  thick.MakeThickSolidBySimple(bottom.Shape(), t_mm);
  if (!thick.IsDone()) throw StepGeometryError("thickening the bent sheet failed");
  for (TopExp_Explorer x(thick.Shape(), TopAbs_SHELL); x.More(); x.Next()) {
    // A fresh solid on the offset's closed shell: the offset keeps the shell's
    // orientation, which sewing chose freely, so the solid is turned outside out.
    TopoDS_Shell shell = TopoDS::Shell(x.Current());
    shell.Closed(BRep_Tool::IsClosed(shell));  // the offset leaves the flag unset; booleans read it
    TopoDS_Solid solid = BRepBuilderAPI_MakeSolid(shell).Solid();
    if (!BRepLib::OrientClosedSolid(solid)) throw StepGeometryError("the thickened sheet is not a closed solid");
    return solid;
  }
  throw StepGeometryError("thickening the bent sheet gave no solid");
}

StepSolidReport measure(const TopoDS_Shape& shape, double inside_radius_mm, double t_mm) {
  StepSolidReport r;
  for (TopExp_Explorer x(shape, TopAbs_SOLID); x.More(); x.Next()) ++r.solids;
  r.valid = BRepCheck_Analyzer(shape).IsValid();
  GProp_GProps props;
  BRepGProp::VolumeProperties(shape, props);
  r.volume_mm3 = props.Mass();
  const double tol = 1e-3;  // mm
  for (const TopoDS_Face& f : faces_of(shape)) {
    ++r.faces;
    const BRepAdaptor_Surface s(f);
    if (s.GetType() != GeomAbs_Cylinder) continue;
    const double radius = s.Cylinder().Radius();
    if (std::abs(radius - inside_radius_mm) < tol || std::abs(radius - inside_radius_mm - t_mm) < tol)
      ++r.bend_faces;
    else
      ++r.hole_faces;
  }
  Bnd_Box box;
  BRepBndLib::AddOptimal(shape, box, false, false);
  box.Get(r.box_min_mm[0], r.box_min_mm[1], r.box_min_mm[2], r.box_max_mm[0], r.box_max_mm[1], r.box_max_mm[2]);
  return r;
}

double inside_radius_mm(const FlatPattern& flat) {
  return flat.bends.empty() ? -1 : flat.bends.front().inside_radius * kMm;
}

// The thickened sheet as written: one face per surface (each bend zone was
// wrapped as two pieces, parent's and tab's side), checked, and the solid
// itself rather than a compound holding it.
TopoDS_Shape finished(const TopoDS_Shape& sheet) {
  ShapeUpgrade_UnifySameDomain unify(sheet, true, true, false);
  unify.Build();
  TopoDS_Shape shape = unify.Shape();
  if (!BRepCheck_Analyzer(shape).IsValid()) {
    // A ruled wall of the offset occasionally comes out with its wire turned
    // the wrong way ("unorientable" on the shelf sample); ShapeFix orients it.
    ShapeFix_Shape fix(shape);
    fix.Perform();
    shape = fix.Shape();
  }
  std::vector<TopoDS_Shape> solids;
  for (TopExp_Explorer x(shape, TopAbs_SOLID); x.More(); x.Next()) solids.push_back(x.Current());
  return solids.size() == 1 ? solids[0] : shape;
}

double volume_mm3(const TopoDS_Shape& s) {
  GProp_GProps props;
  BRepGProp::VolumeProperties(s, props);
  return props.Mass();
}

// The holes drilled square through their sheets, so each wall is a true
// cylinder a CAD system recognises as a hole. Each drill spans its sheet's
// thickness exactly; a self-rivet's two holes, one place in the joined
// plate, are drilled once. Returns a null shape unless the result is one
// valid solid that lost the drills' volume (to 1 %): the caller then cuts
// the holes in the flat sheet instead.
TopoDS_Shape drilled(const TopoDS_Shape& solid, const FlatPattern& flat, const std::vector<RivetHole>& holes, double t) {
  const std::vector<FlatPieceTransform> maps = fold_transforms(flat);
  TopTools_ListOfShape drills;
  std::vector<Vec3> centres;
  double removed = 0;  // mm^3
  for (const RivetHole& h : holes) {
    const Vec3 c = maps[h.tab].apply(h.flat), n = maps[h.tab].rotation.col(2);
    if (std::any_of(centres.begin(), centres.end(), [&](const Vec3& q) { return (q - c).norm() < 1e-6; })) continue;
    centres.push_back(c);
    const double r = 0.5 * h.diameter * kMm;
    drills.Append(BRepPrimAPI_MakeCylinder(gp_Ax2(mm(c - 0.5 * t * n), dir(n)), r, t * kMm).Shape());
    removed += M_PI * r * r * t * kMm;
  }
  TopTools_ListOfShape args;
  args.Append(solid);
  BRepAlgoAPI_Cut cut;
  cut.SetArguments(args);
  cut.SetTools(drills);
  cut.SetFuzzyValue(1e-5);  // mm: the drills' caps lie on the sheet's faces
  cut.Build();
  if (!cut.IsDone() || cut.HasErrors()) return TopoDS_Shape();
  const TopoDS_Shape out = finished(cut.Shape());
  if (out.ShapeType() != TopAbs_SOLID || !BRepCheck_Analyzer(out).IsValid()) return TopoDS_Shape();
  if (std::abs(volume_mm3(solid) - volume_mm3(out) - removed) > 0.01 * removed) return TopoDS_Shape();
  return out;
}

TopoDS_Shape bent_solid(const FlatPattern& flat, const std::vector<RivetHole>& holes, const StepExportOptions& o) {
  if (!flat.ok()) throw std::invalid_argument("the flat pattern is not valid: " + flat.message);
  if (!(o.thickness > 0)) throw std::invalid_argument("StepExportOptions::thickness must be > 0 m");
  for (const RivetHole& h : holes)
    if (h.tab < 0 || h.tab >= static_cast<int>(flat.pieces.size()))
      throw std::invalid_argument("rivet hole " + hole_label(h) + " names tab " + std::to_string(h.tab));
  const std::vector<int> group = self_rivet_groups(flat, holes);
  const double t_mm = o.thickness * kMm;
  if (!holes.empty()) {
    const TopoDS_Shape plain = finished(thicken(mid_surface(flat, {}, group, o), t_mm));
    const TopoDS_Shape out = plain.ShapeType() == TopAbs_SOLID ? drilled(plain, flat, holes, o.thickness) : TopoDS_Shape();
    if (!out.IsNull()) return out;
  }
  // Holes cut in the flat sheet: their walls are the offset's ruled faces.
  return finished(thicken(mid_surface(flat, holes, group, o), t_mm));
}

TopoDS_Solid flat_solid(const FlatPattern& flat, const std::vector<RivetHole>& holes, const StepExportOptions& o) {
  if (flat.outline.size() < 3) throw std::invalid_argument("the flat pattern has no outline");
  if (!(o.thickness > 0)) throw std::invalid_argument("StepExportOptions::thickness must be > 0 m");
  Vec2 origin = Vec2::Constant(std::numeric_limits<double>::infinity());  // flat.dxf's drawing origin
  for (const Vec2& q : flat.outline) origin = origin.cwiseMin(q);
  BRepPrimAPI_MakePrism prism(flat_face(flat, holes, origin), gp_Vec(0, 0, o.thickness * kMm));
  return TopoDS::Solid(prism.Shape());
}

// STEP writing goes through OpenCASCADE's global parameters (Interface_Static), hence one writer at a time.
std::mutex step_writer_mutex;

// The STEP writer reports its progress on stdout, which is the CLI's summary
// (and a Blender user's console): silenced while it runs.
struct QuietMessenger {
  Message_SequenceOfPrinters saved;
  QuietMessenger() : saved(Message::DefaultMessenger()->Printers()) { Message::DefaultMessenger()->ChangePrinters().Clear(); }
  ~QuietMessenger() { Message::DefaultMessenger()->ChangePrinters() = saved; }
};

void write_step(const std::string& path, const TopoDS_Shape& shape, const StepExportOptions& o) {
  AtomicFile file(path);
  {
    std::lock_guard<std::mutex> lock(step_writer_mutex);
    const QuietMessenger quiet;
    STEPControl_Writer writer;
    Interface_Static::SetCVal("write.step.schema", "AP214IS");
    Interface_Static::SetCVal("write.step.unit", "MM");
    Interface_Static::SetCVal("write.step.product.name", o.product.c_str());
    if (writer.Transfer(shape, STEPControl_AsIs) != IFSelect_RetDone)
      throw std::runtime_error("cannot write " + path + ": the solid could not be translated to STEP");
    if (writer.Write(file.temp_path().c_str()) != IFSelect_RetDone)
      throw std::runtime_error("cannot write " + path + " (is its folder there and writable?)");
  }
  const std::string why = file.commit();
  if (!why.empty()) throw std::runtime_error("cannot write " + path + ": " + why);
}

// OpenCASCADE reports failures as Standard_Failure; callers see one runtime_error.
template <class F>
auto guarded(const char* what, F&& f) {
  try {
    return f();
  } catch (const Standard_Failure& e) {
    throw StepGeometryError(std::string(what) + ": OpenCASCADE failed (" + e.GetMessageString() + ")");
  }
}

}  // namespace

StepSolidReport bent_part_solid_report(const FlatPattern& flat, const std::vector<RivetHole>& holes,
                                       const StepExportOptions& options) {
  return guarded("building the bent solid", [&] {
    return measure(bent_solid(flat, holes, options), inside_radius_mm(flat), options.thickness * kMm);
  });
}

StepSolidReport write_part_step(const std::string& path, const FlatPattern& flat, const std::vector<RivetHole>& holes,
                                const StepExportOptions& options) {
  return guarded(path.c_str(), [&] {
    const TopoDS_Shape solid = bent_solid(flat, holes, options);
    StepSolidReport r = measure(solid, inside_radius_mm(flat), options.thickness * kMm);
    if (r.solids != 1 || !r.valid) { 
      throw StepGeometryError("cannot write " + path + ": the bent solid is not valid (" + std::to_string(r.solids) +
                              " solids, OpenCASCADE's check " + (r.valid ? "passed" : "failed") + ")");
    }
    write_step(path, solid, options);
    return r;
  });
}

StepSolidReport write_flat_step(const std::string& path, const FlatPattern& flat, const std::vector<RivetHole>& holes,
                                const StepExportOptions& options) {
  return guarded(path.c_str(), [&] {
    const TopoDS_Solid solid = flat_solid(flat, holes, options);
    StepSolidReport r = measure(solid, inside_radius_mm(flat), options.thickness * kMm);
    if (!r.valid) throw StepGeometryError("cannot write " + path + ": the flat solid is not valid");
    write_step(path, solid, options);
    return r;
  });
}

}  // namespace sheetgen
