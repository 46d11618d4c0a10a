#!/usr/bin/python3
"""Every sample problem solves at the default settings (10 chains x 1000
iterations) with status ok, and each part passes the independent checks of
tests/python/verify_result.py (brute-force clearance, flange on its rivet area,
CalculiX compliance and margin of safety, ezdxf outline).

Run: /usr/bin/python3 tests/python/test_solve_samples.py --sheetgen build/native/cli/sheetgen [--jobs N] [SCENE ...]
"""
import argparse
import concurrent.futures
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
# bulkhead_hole has a part only through the second search with web roots
# (docs/discovery.md "Web roots"), so it checks that pass end to end.
SCENES = ["corner", "corner_obstacle", "slanted", "bulkhead_hole"]


def verify(out, sheetgen):
    """The independent checks of one solved scene, in a child process."""
    return subprocess.run([sys.executable, os.path.join(HERE, "verify_result.py"), out, "--sheetgen", sheetgen],
                          capture_output=True, text=True)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sheetgen", required=True)
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1,
                    help="verifications run at once (default: the number of cores)")
    ap.add_argument("scenes", nargs="*", default=SCENES)
    args = ap.parse_args()
    sheetgen = os.path.abspath(args.sheetgen)
    passed, failed = 0, 0
    # The scenes solve one at a time on 2 threads; each scene's verification
    # (gmsh and CalculiX, single-threaded, minutes per part) runs in a worker
    # while the next scene solves and the other scenes verify. Serially the
    # verifications were most of this test's 24 minutes.
    pending = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        for scene in args.scenes:
            out = tempfile.mkdtemp(prefix="sheetgen_sample_%s_" % scene)
            t0 = time.monotonic()
            p = subprocess.run([sheetgen, "solve", os.path.join(ROOT, "sample_scenes", scene, "problem.json"), "--out", out,
                                "--threads", "2"], capture_output=True, text=True)
            solve_s = time.monotonic() - t0
            print("== %s: exit %d in %.1f s\n%s" % (scene, p.returncode, solve_s, p.stdout.strip()), flush=True)
            if p.returncode != 0:
                print(p.stderr)
                failed += 1
                continue
            pending.append((scene, time.monotonic(), pool.submit(verify, out, sheetgen)))
        for scene, t0, future in pending:
            v = future.result()
            print("== %s: verified (finished %.1f s after its solve)\n%s" % (scene, time.monotonic() - t0, v.stdout.strip()))
            if v.returncode == 0:
                passed += 1
            else:
                print(v.stderr)
                failed += 1
    print("solve samples: %d passed, %d failed" % (passed, failed))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
