"""Rivet-area tags on mesh faces.

The tag is an INT face attribute ``sheetgen_rivet_area`` (0 = none, k = the
object's rivet area with ``area_id`` k). Blender 3.4 BMesh has no bool face
layer, and in edit mode ``mesh.attributes`` has no data (docs/platform.md), so every
read and write goes through BMesh: the edit BMesh in edit mode, a temporary one
in object mode. A BYTE_COLOR corner attribute ``sheetgen_rivet_color`` mirrors
the tags for the viewport (Solid shading, colour "Attribute"): it shows in
any mode, headless included, and does not touch the user's materials.
"""
import colorsys
from contextlib import contextmanager

import bmesh

ATTR = "sheetgen_rivet_area"
COLOR_ATTR = "sheetgen_rivet_color"
UNTAGGED = (0.8, 0.8, 0.8, 1.0)


def palette(k):
    """A distinct, saturated colour for area id k >= 1 (golden-ratio hue steps)."""
    h = (0.02 + 0.618034 * (k - 1)) % 1.0
    return colorsys.hsv_to_rgb(h, 0.85, 1.0)


@contextmanager
def editing(obj, write=True):
    """A BMesh of ``obj``'s mesh with face indices; written back on exit when ``write``."""
    me = obj.data
    if obj.mode == 'EDIT':
        bm = bmesh.from_edit_mesh(me)
        bm.faces.ensure_lookup_table()
        yield bm
        if write:
            bmesh.update_edit_mesh(me, loop_triangles=False, destructive=False)
    else:
        bm = bmesh.new()
        bm.from_mesh(me)
        bm.faces.ensure_lookup_table()
        try:
            yield bm
            if write:
                bm.to_mesh(me)
                me.update()
        finally:
            bm.free()


def _layer(bm, create=True):
    lay = bm.faces.layers.int.get(ATTR)
    if lay is None and create:
        lay = bm.faces.layers.int.new(ATTR)
    return lay


def _paint(obj, bm, lay):
    col = bm.loops.layers.color.get(COLOR_ATTR) or bm.loops.layers.color.new(COLOR_ATTR)
    colors = {a.area_id: (*a.color, 1.0) for a in obj.sheetgen.rivet_areas}
    for f in bm.faces:
        c = colors.get(f[lay], UNTAGGED) if lay is not None else UNTAGGED
        for loop in f.loops:
            loop[col] = c


def _make_active_color(obj):
    me = obj.data
    attr = me.color_attributes.get(COLOR_ATTR)
    if attr is not None:
        me.color_attributes.active_color = attr


def face_ids(obj):
    """The tag of every face (polygon), in polygon order; zeros when untagged."""
    with editing(obj, write=False) as bm:
        lay = _layer(bm, create=False)
        return [f[lay] for f in bm.faces] if lay is not None else [0] * len(bm.faces)


def selected_faces(obj):
    with editing(obj, write=False) as bm:
        return [f.index for f in bm.faces if f.select]


def assign_selected(obj, area_id):
    """Tag the selected faces with ``area_id`` (0 untags them); returns how many faces changed."""
    with editing(obj) as bm:
        lay = _layer(bm)
        n = 0
        for f in bm.faces:
            if f.select and f[lay] != area_id:
                f[lay] = area_id
                n += 1
        _paint(obj, bm, lay)
    _make_active_color(obj)
    return n


def clear_area(obj, area_id):
    """Untag every face of area ``area_id``; returns how many."""
    with editing(obj) as bm:
        lay = _layer(bm, create=False)
        n = 0
        if lay is not None:
            for f in bm.faces:
                if f[lay] == area_id:
                    f[lay] = 0
                    n += 1
        _paint(obj, bm, lay)
    return n


def select_area(obj, area_id, extend=False):
    """Select the faces of area ``area_id`` (edit mode selection); returns how many."""
    with editing(obj) as bm:
        lay = _layer(bm, create=False)
        if not extend:
            for f in bm.faces:
                f.select_set(False)
        n = 0
        if lay is not None:
            for f in bm.faces:
                if f[lay] == area_id:
                    f.select_set(True)
                    n += 1
        bm.select_flush_mode()
    return n


def recolor(obj):
    with editing(obj) as bm:
        _paint(obj, bm, _layer(bm, create=False))
    _make_active_color(obj)


def new_area(obj, name=None):
    """Add a rivet area to ``obj`` with the next free id and a palette colour; make it active."""
    s = obj.sheetgen
    k = max([a.area_id for a in s.rivet_areas] + [0]) + 1
    item = s.rivet_areas.add()
    item.area_id = k
    item.name = name or "%s_rivets_%d" % (obj.name, k)
    item["color"] = palette(k)  # no update callback: there is nothing to repaint yet
    s.rivet_area_index = len(s.rivet_areas) - 1
    return item


def active_area(obj):
    s = obj.sheetgen
    if 0 <= s.rivet_area_index < len(s.rivet_areas):
        return s.rivet_areas[s.rivet_area_index]
    return None


def show_in_viewports(screen):
    """Solid shading with attribute colours in every 3D view of ``screen`` (None headless: no-op)."""
    if screen is None:
        return 0
    n = 0
    for area in screen.areas:
        if area.type == 'VIEW_3D':
            for space in area.spaces:
                if space.type == 'VIEW_3D':
                    if space.shading.type not in {'SOLID'}:
                        space.shading.type = 'SOLID'
                    space.shading.color_type = 'VERTEX'
                    n += 1
    return n
