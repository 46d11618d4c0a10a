#!/usr/bin/python3
"""Discovery policy ablation on the maze (paper Sec. 6.4.1, Fig. 13).

Runs build/bench/discovery_ablation_bench for the five policy pairs (ours,
segment greedy, segment uniform, edge greedy, edge uniform) over several seeds,
writes the raw CSV into BUILD_DIR/ablation_discovery.csv, prints a markdown
table (means over seeds) for docs/ablation_discovery.md and draws the bar plot
of the segments per rivet area into docs/ablation_discovery.png.

Usage: /usr/bin/python3 bench/ablation_edge_policies.py [BUILD_DIR] [--iterations N] [--chains M] [--seeds 1,2,3]
"""
import argparse
import csv
import io
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build", nargs="?", default=os.path.join(ROOT, "build"))
    ap.add_argument("--iterations", type=int, default=500)
    ap.add_argument("--chains", type=int, default=10)
    ap.add_argument("--seeds", default="1,2,3")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs"))
    a = ap.parse_args()
    exe = os.path.join(a.build, "bench", "discovery_ablation_bench")
    problem = os.path.join(ROOT, "sample_scenes", "maze", "problem.json")
    seeds = a.seeds.split(",")
    text = subprocess.run([exe, problem, str(a.iterations), str(a.chains)] + seeds, check=True,
                          capture_output=True, text=True).stdout
    rows = list(csv.DictReader(io.StringIO(text)))
    with open(os.path.join(a.build, "ablation_discovery.csv"), "w") as f:  # raw runs, next to the build
        f.write(text)
    ras = [k for k in rows[0] if k.startswith("ra_")]
    policies = []
    for r in rows:
        if r["policy"] not in policies:
            policies.append(r["policy"])
    mean = {}
    for p in policies:
        rs = [r for r in rows if r["policy"] == p]
        mean[p] = {k: sum(float(r[k]) for r in rs) / len(rs) for k in ["segments", "distinct", "seconds"] + ras}
        mean[p]["reached"] = sum(sum(1 for k in ras if float(r[k]) > 0) for r in rs) / len(rs)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8, 4))
    width = 0.8 / len(policies)
    for i, p in enumerate(policies):
        xs = [j + i * width for j in range(len(ras))]
        ax.bar(xs, [mean[p][k] for k in ras], width, label=p.replace("_", " "))
    ax.set_xticks([j + 0.4 - width / 2 for j in range(len(ras))])
    ax.set_xticklabels(["RA%d" % (j + 1) for j in range(len(ras))])
    ax.set_ylabel("segments in library (mean over %d seeds)" % len(seeds))
    ax.set_title("Maze: segments per rivet area, %d chains x %d iterations" % (a.chains, a.iterations))
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "ablation_discovery.png"), dpi=120)

    lines = ["| policy | " + " | ".join("RA%d" % (j + 1) for j in range(len(ras))) +
             " | segments | distinct (5 cm) | rivet areas reached | time (s) |",
             "|---" * (len(ras) + 5) + "|"]
    for p in policies:
        m = mean[p]
        lines.append("| %s | " % p.replace("_", " ") + " | ".join("%.1f" % m[k] for k in ras) +
                     " | %.1f | %.1f | %.1f | %.1f |" % (m["segments"], m["distinct"], m["reached"], m["seconds"]))
    table = "\n".join(lines)
    print(table)
    return 0


if __name__ == "__main__":
    sys.exit(main())
