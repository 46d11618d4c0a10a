"""Makes the add-on's images in docs/images/.

    /usr/bin/python3 scripts/make_screenshots.py [--chains 4 --iterations 300] [--no-ui]

1. For each sample scene (corner, corner_obstacle, slanted): the headless batch
   (scripts/blender_batch.py --render) on sample_scenes/<scene>/scene.blend,
   copying its render.png to docs/images/blender_render_<scene>.png and the flat
   pattern to docs/images/blender_flat_<scene>.png.
2. The sidebar: Blender with its UI under Xvfb (xvfb-run, Debian package xvfb)
   opens the corner run's scene.blend, selects the wall, opens the Sheet Metal
   tab and saves a screenshot of the window to docs/images/blender_sidebar.png.
   Skipped with a message when xvfb-run is not installed.

Inside Blender (step 2) this file runs with ``-- --ui PNG``.
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# Blender runs this file by path (step 2) and no PYTHONPATH reaches its Python:
# the one bootstrap line that makes the tools package importable (tools/sheetgen_tools/__init__.py).
sys.path.insert(0, os.path.join(ROOT, "tools"))
from sheetgen_tools import addon_loader  # noqa: E402
IMAGES = os.path.join(ROOT, "docs", "images")
SCENES = ("corner", "corner_obstacle", "slanted")


def driver(argv):
    ap = argparse.ArgumentParser()
    ap.add_argument("--chains", type=int, default=4)
    ap.add_argument("--iterations", type=int, default=300)
    ap.add_argument("--samples", type=int, default=32)
    ap.add_argument("--blender", default=shutil.which("blender") or "blender")
    ap.add_argument("--no-ui", action="store_true")
    ap.add_argument("--scenes", nargs="*", default=list(SCENES))
    args = ap.parse_args(argv)
    os.makedirs(IMAGES, exist_ok=True)
    work = tempfile.mkdtemp(prefix="sheetgen-shots-")
    for scene in args.scenes:
        out = os.path.join(work, scene)
        cmd = [args.blender, "-b", os.path.join(ROOT, "sample_scenes", scene, "scene.blend"), "--python-exit-code", "1",
               "--python", os.path.join(ROOT, "scripts", "blender_batch.py"), "--", "--out", out, "--render",
               "--chains", str(args.chains), "--iterations", str(args.iterations), "--samples", str(args.samples)]
        print(" ".join(cmd), flush=True)
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        print("\n".join(l for l in p.stdout.splitlines() if not l.startswith("Fra:"))[-1500:], flush=True)
        if p.returncode not in (0, 2):
            raise SystemExit("batch failed on %s" % scene)
        if os.path.exists(os.path.join(out, "render.png")):
            shutil.copy(os.path.join(out, "render.png"), os.path.join(IMAGES, "blender_render_%s.png" % scene))
            for f in os.listdir(out):
                if f.startswith("render_") and f.endswith("_flat.png"):
                    shutil.copy(os.path.join(out, f), os.path.join(IMAGES, "blender_flat_%s.png" % scene))
    if not args.no_ui:
        xvfb = shutil.which("xvfb-run")
        if xvfb is None:
            print("xvfb-run not found (apt install xvfb): no sidebar screenshot")
        else:
            png = os.path.join(IMAGES, "blender_sidebar.png")
            blend = os.path.join(work, "corner", "scene.blend")
            cmd = [xvfb, "-a", "-s", "-screen 0 1400x1100x24", args.blender, "--factory-startup",
                   "--enable-event-simulate", blend,
                   "--python-exit-code", "1", "--python", os.path.abspath(__file__), "--", "--ui", png]
            print(" ".join(cmd), flush=True)
            p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
            print(p.stdout[-2000:])
            if not os.path.exists(png):
                raise SystemExit("no sidebar screenshot was written")
    shutil.rmtree(work, ignore_errors=True)


def ui(png):
    """Inside Blender with a window: show the Sheet Metal sidebar, screenshot once the UI has drawn, quit."""
    import bpy
    addon_loader.enable_addon()
    state = {"step": 0}

    def view3d():
        for window in bpy.context.window_manager.windows:
            for area in window.screen.areas:
                if area.type == 'VIEW_3D':
                    return window, area
        return None, None

    def setup():
        window, area = view3d()
        if area is None:
            return 0.5
        wall = bpy.data.objects.get("wall")
        for o in bpy.context.view_layer.objects:
            o.select_set(False)
        if wall is not None:
            bpy.context.view_layer.objects.active = wall
            wall.select_set(True)
        space = area.spaces.active
        space.show_region_ui = True
        space.overlay.show_extras = True
        for region in area.regions:
            if region.type == 'UI':
                try:
                    region.active_panel_category = "Sheet Metal"
                except (AttributeError, TypeError):
                    pass
        region = next(r for r in area.regions if r.type == 'WINDOW')
        with bpy.context.temp_override(window=window, area=area, region=region):
            bpy.ops.view3d.view_all(center=False)
        # Blender 3.4 has no Python access to the sidebar's active tab: click it (--enable-event-simulate).
        # The tabs run down the right edge of the UI region in registration order: Item, Tool, View,
        # Sheet Metal; the last is ~40 % down the strip, measured on the factory layout at 1400x1100.
        ui_region = next(r for r in area.regions if r.type == 'UI')
        x = ui_region.x + ui_region.width - 8
        y = ui_region.y + ui_region.height - 190
        state["tab"] = (x, y)
        window.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=y)
        window.event_simulate(type='LEFTMOUSE', value='PRESS', x=x, y=y)
        window.event_simulate(type='LEFTMOUSE', value='RELEASE', x=x, y=y)
        # Widen the sidebar: drag its left edge 160 px to the left.
        ex, ey = ui_region.x, ui_region.y + ui_region.height // 2
        window.event_simulate(type='MOUSEMOVE', value='NOTHING', x=ex, y=ey)
        window.event_simulate(type='LEFTMOUSE', value='PRESS', x=ex, y=ey)
        for k in range(1, 9):
            window.event_simulate(type='MOUSEMOVE', value='NOTHING', x=ex - 20 * k, y=ey)
        window.event_simulate(type='LEFTMOUSE', value='RELEASE', x=ex - 160, y=ey)
        window.event_simulate(type='MOUSEMOVE', value='NOTHING', x=200, y=200)
        print("ui region", ui_region.x, ui_region.y, ui_region.width, ui_region.height, "click", x, y, flush=True)
        return None

    def shoot():
        window, area = view3d()
        state["step"] += 1
        try:
            if state["step"] == 1:
                setup()
                return 2.0
            with bpy.context.temp_override(window=window, area=area):
                bpy.ops.screen.screenshot(filepath=png)
            print("wrote %s" % png, flush=True)
        except Exception:  # noqa: BLE001 - never leave a Blender window open under Xvfb
            import traceback
            traceback.print_exc()
        bpy.ops.wm.quit_blender()
        return None

    bpy.app.timers.register(shoot, first_interval=2.0)


if __name__ == "__main__":
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    if "--ui" in argv:
        ui(os.path.abspath(argv[argv.index("--ui") + 1]))
    else:
        driver(argv)
