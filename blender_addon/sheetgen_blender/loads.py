"""Load boxes and their force arrows.

The arrow is an empty of type SINGLE_ARROW (drawn by Blender itself, so it
also exists headless and in renders of the viewport). It is not parented: a
Copy Location constraint keeps it on the box origin while its own rotation
points +Z along the force in world axes, so rotating the box does not turn the
(world-frame) force arrow.
"""
import bpy
from mathutils import Vector

ARROW_SUFFIX = "_force"


def _arrow_size(obj):
    return max(max(obj.dimensions), 0.05) * 1.25


def make_load(obj, collection=None):
    """Mark ``obj`` as a load and give it an arrow; returns the arrow."""
    s = obj.sheetgen
    s.is_load = True
    arrow = s.arrow
    if arrow is None or arrow.name not in bpy.data.objects:
        arrow = bpy.data.objects.new(obj.name + ARROW_SUFFIX, None)
        arrow.empty_display_type = 'SINGLE_ARROW'
        arrow.sheetgen.is_arrow = True
        arrow.hide_select = True
        for col in ([collection] if collection else obj.users_collection):
            col.objects.link(arrow)
        con = arrow.constraints.new('COPY_LOCATION')
        con.target = obj
        s.arrow = arrow
    update_arrow(obj)
    return arrow


def update_arrow(obj):
    arrow = obj.sheetgen.arrow
    if arrow is None:
        return
    f = Vector(obj.sheetgen.force)
    # Only the one-force load has a single direction to show; a case list or the envelope has many.
    arrow.hide_viewport = obj.sheetgen.own_cases != 'FORCE'
    arrow.rotation_mode = 'QUATERNION'
    arrow.rotation_quaternion = Vector((0, 0, 1)).rotation_difference(f.normalized()) if f.length > 0 else (1, 0, 0, 0)
    arrow.empty_display_size = _arrow_size(obj)
    arrow.location = obj.matrix_world.translation


def clear_load(obj):
    s = obj.sheetgen
    s.is_load = False
    arrow = s.arrow
    s.arrow = None
    if arrow is not None and arrow.name in bpy.data.objects:
        bpy.data.objects.remove(arrow, do_unlink=True)
