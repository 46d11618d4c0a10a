# Run by freecadcmd (FreeCAD's own Python), not directly: reads each STEP file
# named in the environment variable STEP_FILES (a JSON list) with FreeCAD's
# importer and prints one line "PROBE {json}" per file: solids, shells, whether
# the shape is valid (BRepCheck) and every shell closed, volume (mm^3), the
# bounding box (mm) and the radius of every cylindrical face (mm).
import json
import os

import Part

for path in json.loads(os.environ["STEP_FILES"]):
    shape = Part.Shape()
    shape.read(path)
    box = shape.BoundBox
    print("PROBE " + json.dumps({
        "path": path,
        "solids": len(shape.Solids),
        "shells": len(shape.Shells),
        "valid": shape.isValid(),
        "closed": bool(shape.Shells) and all(s.isClosed() for s in shape.Shells),
        "volume": shape.Volume,
        "bbox": [box.XMin, box.YMin, box.ZMin, box.XMax, box.YMax, box.ZMax],
        "cylinders": [f.Surface.Radius for f in shape.Faces if f.Surface.__class__.__name__ == "Cylinder"],
    }), flush=True)
