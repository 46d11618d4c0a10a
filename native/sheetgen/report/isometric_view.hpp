#pragma once
// The small picture of the bent part on the drawing sheet: the mid-surface
// polygons in an isometric projection, shaded by how squarely they face a
// light, in painter's order (far to near; hidden lines are not removed, the
// nearer faces simply cover the farther ones). The view looks down along one
// of the four diagonals (+-1, +-1, -1) of the world (z up): the one that sees
// the tabs most face-on, so that no sheet is drawn edge-on where another
// diagonal would show it. Plain geometry: no cairo here.
#include <vector>

#include "sheetgen/report/drawing_sheet.hpp"

namespace sheetgen {

struct IsometricFace {
  int tab = -1;
  std::vector<SheetPoint> polygon;  // projected, m: x to the right, y up on the picture
  double shade = 0;                 // 0 (dark) .. 1 (white)
  double depth = 0;                 // m, centroid's distance along the view direction (larger = farther)
};

struct IsometricView {
  double view[3] = {0, 0, -1};  // unit, the direction the viewer looks along
  double right[3] = {1, 0, 0};  // unit, the picture's x
  double up[3] = {0, 1, 0};     // unit, the picture's y (world z projects upwards)
  std::vector<IsometricFace> faces;  // far to near
  SheetPoint min, max;               // m, bounding box of the projected faces
  SheetPoint project(const SheetPoint3& p) const;
  double depth(const SheetPoint3& p) const;
};

// Faces with fewer than 3 corners are skipped. Deterministic: ties between the
// diagonals go to the first of (+1, +1), (-1, +1), (-1, -1), (+1, -1) in x, y.
IsometricView isometric_view(const std::vector<std::vector<SheetPoint3>>& tabs);

}  // namespace sheetgen
