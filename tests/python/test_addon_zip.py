#!/usr/bin/python3
"""The installable add-on (issue 35, item 3): scripts/package_addon.sh writes
sheetgen_blender-<version>.zip; a Blender with an empty user configuration
installs it as Preferences > Add-ons > Install does, enables it, opens a sample
.blend and generates its part, which equals the CLI's on the same problem.

Run: PYTHONPATH=tools /usr/bin/python3 tests/python/test_addon_zip.py --sheetgen build/native/cli/sheetgen \
         --build-dir build

Inside Blender (started by the test) this file runs with ``-- --inside ZIP BLEND OUT_JSON``.
"""
import ast
import json
import os
import subprocess
import sys
import tempfile
import tomllib
import unittest
import zipfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENE = "shelf"
# 6 chains x 300 iterations, beam 2, seed 1: shelf has a valid part there in 3.5 s on the shared
# 2-core machine (corner, the scene this test used before, 14 s).
SETTINGS = {"chains": 6, "iterations": 300, "beam_width": 2, "seed": 1}


def inside(zip_path, blend, out_json):
    """In `blender -b --factory-startup` with BLENDER_USER_CONFIG and BLENDER_USER_SCRIPTS empty."""
    import addon_utils
    import bpy
    facts = {"install": list(bpy.ops.preferences.addon_install(filepath=zip_path))}
    facts["enable"] = list(bpy.ops.preferences.addon_enable(module="sheetgen_blender"))
    import sheetgen_blender
    from sheetgen_blender import native, results
    facts["addon_file"] = sheetgen_blender.__file__
    facts["native_file"] = native.get().__file__ if native.get() is not None else native.error()
    facts["enabled"] = list(addon_utils.check("sheetgen_blender"))
    facts["operators"] = sorted(n for n in dir(bpy.ops.sheetgen))
    bpy.ops.wm.open_mainfile(filepath=blend)
    s = bpy.context.scene.sheetgen
    for k, v in SETTINGS.items():
        setattr(s, k, v)
    facts["generate"] = list(bpy.ops.sheetgen.generate())
    col = s.result_collection
    doc = results.run_document(col)
    facts["parts"] = [{"load": p["load"], "status": p["status"], "mass_kg": p.get("mass_kg"),
                       "area_m2": p.get("area_m2"), "bends": p.get("bends"),
                       "flat_area_m2": p.get("flat_pattern", {}).get("area_m2")} for p in doc["parts"]]
    facts["objects"] = {o.name: {"faces": len(o.data.polygons), "area_m2": sum(f.area for f in o.data.polygons)}
                        for o in col.objects if o.type == 'MESH'}
    with open(out_json, "w", encoding="utf-8") as f:
        json.dump(facts, f, indent=1)


class AddonZip(unittest.TestCase):
    SHEETGEN = None
    BUILD_DIR = None

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory(prefix="sheetgen-zip-")
        t = cls.tmp.name
        pkg = subprocess.run(["bash", os.path.join(ROOT, "scripts", "package_addon.sh"), "--build-dir", cls.BUILD_DIR,
                              "--out", t], capture_output=True, text=True, timeout=120)
        assert pkg.returncode == 0, pkg.stderr
        cls.zip = pkg.stdout.strip().splitlines()[-1]
        # The CLI on the scene's problem file beside Blender (two cores: they overlap).
        cli_out = os.path.join(t, "cli")
        cli = subprocess.Popen([cls.SHEETGEN, "solve", os.path.join(ROOT, "sample_scenes", SCENE, "problem.json"),
                                "--out", cli_out, "--chains", str(SETTINGS["chains"]),
                                "--iterations", str(SETTINGS["iterations"]), "--beam", str(SETTINGS["beam_width"]),
                                "--seed", str(SETTINGS["seed"])], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                               text=True)
        env = dict(os.environ)
        env.pop("PYTHONPATH", None)      # nothing of this checkout on Blender's path: only the zip
        env["BLENDER_USER_CONFIG"] = os.path.join(t, "config")     # empty: a first start
        env["BLENDER_USER_SCRIPTS"] = os.path.join(t, "scripts")
        cls.facts_path = os.path.join(t, "facts.json")
        cls.blender = subprocess.run(
            ["blender", "-b", "--factory-startup", "--python-exit-code", "1", "--python", os.path.abspath(__file__),
             "--", "--inside", cls.zip, os.path.join(ROOT, "sample_scenes", SCENE, "scene.blend"), cls.facts_path],
            env=env, cwd=t, capture_output=True, text=True, timeout=600)
        _, err = cli.communicate(timeout=600)
        assert cli.returncode in (0, 2), err
        with open(os.path.join(cli_out, "result.json"), encoding="utf-8") as f:
            cls.cli = json.load(f)
        cls.scripts = env["BLENDER_USER_SCRIPTS"]

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def facts(self):
        self.assertEqual(self.blender.returncode, 0, self.blender.stdout[-3000:] + self.blender.stderr[-3000:])
        with open(self.facts_path, encoding="utf-8") as f:
            return json.load(f)

    def test_zip_layout_and_manifest(self):
        with open(os.path.join(ROOT, "blender_addon", "sheetgen_blender", "__init__.py"), encoding="utf-8") as f:
            tree = ast.parse(f.read())
        bl_info = next(ast.literal_eval(n.value) for n in tree.body if isinstance(n, ast.Assign)
                       and getattr(n.targets[0], "id", None) == "bl_info")
        version = ".".join(map(str, bl_info["version"]))
        self.assertEqual(os.path.basename(self.zip), "sheetgen_blender-%s.zip" % version)
        src = os.path.join(ROOT, "blender_addon", "sheetgen_blender")
        want = sorted("sheetgen_blender/" + os.path.relpath(os.path.join(d, f), src) for d, _, fs in os.walk(src)
                      for f in fs if f.endswith(".py") or f == "blender_manifest.toml")
        so = os.path.basename([p for p in os.listdir(os.path.join(self.BUILD_DIR, "python"))
                               if p.startswith("_sheetgen_native")][0])
        self.assertEqual(so, "_sheetgen_native.cpython-311-x86_64-linux-gnu.so")   # Blender 3.4's system Python
        with zipfile.ZipFile(self.zip) as z:
            names = sorted(z.namelist())
            self.assertEqual(names, sorted(want + ["sheetgen_blender/" + so, "sheetgen_blender/LICENSE"]))
            manifest = tomllib.loads(z.read("sheetgen_blender/blender_manifest.toml").decode())
            with open(os.path.join(self.BUILD_DIR, "python", so), "rb") as f:
                self.assertEqual(z.read("sheetgen_blender/" + so), f.read())
        self.assertEqual(manifest["schema_version"], "1.0.0")
        self.assertEqual(manifest["id"], "sheetgen_blender")    # the package name, a Python identifier
        self.assertEqual(manifest["version"], version)
        self.assertEqual(manifest["name"], bl_info["name"])
        self.assertEqual(manifest["type"], "add-on")
        self.assertEqual(manifest["blender_version_min"], "4.2.0")
        self.assertEqual(manifest["license"], ["SPDX:GPL-3.0-or-later"])
        self.assertEqual(manifest["platforms"], ["linux-x64"])
        for key in ("tagline", "maintainer"):
            self.assertTrue(manifest[key])
        self.assertLessEqual(len(manifest["tagline"]), 64)
        self.assertFalse(manifest["tagline"].endswith("."))
        for reason in manifest["permissions"].values():
            self.assertLessEqual(len(reason), 64)
        with open(os.path.join(ROOT, "LICENSE"), encoding="utf-8") as f:
            self.assertIn("GNU GENERAL PUBLIC LICENSE\n                       Version 3", f.read(200))

    def test_no_module_no_zip(self):
        with tempfile.TemporaryDirectory() as d:
            os.makedirs(os.path.join(d, "python"))
            run = subprocess.run(["bash", os.path.join(ROOT, "scripts", "package_addon.sh"), "--build-dir", d,
                                  "--out", d], capture_output=True, text=True, timeout=60)
            self.assertEqual(run.returncode, 1)
            self.assertEqual(run.stderr.count("\n"), 1)
            self.assertIn("expected one %s/python/_sheetgen_native*.so, found 0" % d, run.stderr)
            self.assertEqual(os.listdir(d), ["python"])

    def test_installed_from_the_zip_into_the_empty_configuration(self):
        facts = self.facts()
        self.assertEqual(facts["install"], ["FINISHED"])
        self.assertEqual(facts["enable"], ["FINISHED"])
        self.assertEqual(facts["enabled"], [True, True])
        addon = os.path.join(self.scripts, "addons", "sheetgen_blender")
        self.assertEqual(facts["addon_file"], os.path.join(addon, "__init__.py"))
        self.assertEqual(facts["native_file"], os.path.join(addon, "_sheetgen_native.cpython-311-x86_64-linux-gnu.so"))
        # every operator the add-on's sources define is registered
        import re
        src = os.path.join(ROOT, "blender_addon", "sheetgen_blender")
        defined = set()
        for d, _, fs in os.walk(src):
            for f in fs:
                if f.endswith(".py"):
                    with open(os.path.join(d, f), encoding="utf-8") as fh:
                        defined |= set(re.findall(r'bl_idname = "sheetgen\.(\w+)"', fh.read()))
        self.assertIn("generate", defined)
        self.assertEqual(sorted(defined), facts["operators"])

    def test_generated_part_equals_the_cli_part(self):
        facts = self.facts()
        self.assertEqual(facts["generate"], ["FINISHED"])
        cli = {p["load"]: p for p in self.cli["parts"]}
        self.assertEqual([p["load"] for p in facts["parts"]], ["avionics_box"])
        for p in facts["parts"]:
            self.assertEqual(p["status"], "ok")
            c = cli[p["load"]]
            self.assertEqual(c["status"], "ok")
            # The .blend is the imported problem.json: same problem, seed and settings, same part.
            self.assertEqual(p["mass_kg"], c["mass_kg"])
            self.assertEqual(p["area_m2"], c["area_m2"])
            self.assertEqual(p["bends"], c["bends"])
            self.assertGreater(p["mass_kg"], 0.05)
            bent = facts["objects"]["%s part" % p["load"]]
            self.assertGreater(bent["faces"], 0)
            flat = facts["objects"]["%s flat" % p["load"]]
            # the flat object's faces add up to the CLI's flat pattern area (float32 coordinates)
            fa = c["flat_pattern"]["area_m2"]
            self.assertEqual(p["flat_area_m2"], fa)
            self.assertAlmostEqual(flat["area_m2"], fa, delta=fa * 1e-5)


if __name__ == "__main__":
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    if "--inside" in argv:
        i = argv.index("--inside")
        inside(*argv[i + 1:i + 4])
    else:
        import argparse
        ap = argparse.ArgumentParser()
        ap.add_argument("--sheetgen", required=True)
        ap.add_argument("--build-dir", required=True)
        args, rest = ap.parse_known_args()
        AddonZip.SHEETGEN = os.path.abspath(args.sheetgen)
        AddonZip.BUILD_DIR = os.path.abspath(args.build_dir)
        unittest.main(argv=[sys.argv[0]] + rest, verbosity=2)
