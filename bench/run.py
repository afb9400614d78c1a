#!/usr/bin/python3
"""Runs liftmap's benchmark and rewrites bench/RESULTS.md.

Per example pair: `liftmap map` end to end, median wall time per stage over several runs, peak memory, outer
iterations and the distortion of the map f; the "fixed common base domain" baseline (the Tutte pair lifted
without optimisation, paper §4.4) on the same pair and landmarks, measured in the same run. Then the per-stage
benchmark programs of bench/<stage>/ (their output is copied verbatim).

usage: bench/run.py BUILD_DIR [--runs N] [--quick]
"""
import argparse
import json
import os
import platform
import re
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MESHES = os.path.join(ROOT, "data", "meshes")
TIMEOUT = 900  # seconds per liftmap run; a pair that takes longer is reported as such


def example_pairs():
    pairs = []
    for name in sorted(os.listdir(os.path.join(ROOT, "examples"))):
        folder = os.path.join(ROOT, "examples", name)
        meshes_file = os.path.join(folder, "meshes.txt")
        if not os.path.isfile(meshes_file):
            continue
        a, b = open(meshes_file).read().split()[:2]
        pairs.append((name, os.path.join(MESHES, a), os.path.join(MESHES, b), os.path.join(folder, "landmarks.txt")))
    return pairs


def run_map(liftmap, a, b, landmarks, extra):
    out = tempfile.mkdtemp(prefix="liftmap_bench_")
    cmd = ["/usr/bin/time", "-f", "%M", liftmap, "map", a, b, "-l", landmarks, "-o", out, "--quiet"] + extra
    t0 = time.monotonic()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=TIMEOUT)
    except subprocess.TimeoutExpired:
        subprocess.run(["rm", "-rf", out])
        raise RuntimeError(f"timed out after {TIMEOUT} s")
    wall = time.monotonic() - t0
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} exited {p.returncode}: {p.stderr.strip()}")
    peak_kb = int(p.stderr.strip().splitlines()[-1])
    report = json.load(open(os.path.join(out, "report.json")))
    subprocess.run(["rm", "-rf", out])
    return wall, peak_kb, report


def median_runs(liftmap, a, b, landmarks, extra, runs):
    results = [run_map(liftmap, a, b, landmarks, extra) for _ in range(runs)]
    med = {k: statistics.median(r[2]["seconds"][k] for r in results) for k in ("cut", "flatten", "lift", "verify", "total")}
    med["wall"] = statistics.median(r[0] for r in results)
    med["peak_mb"] = max(r[1] for r in results) / 1024.0
    return med, results[-1][2]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--pairs", nargs="*", help="example pairs to run (default: all of examples/)")
    args = ap.parse_args()
    liftmap = os.path.join(args.build, "app", "liftmap")
    lines = ["# liftmap benchmark results", ""]
    pairs = " --pairs " + " ".join(args.pairs) if args.pairs else ""
    lines.append(f"Produced by `bench/run.py {args.build} --runs {args.runs}{pairs}` on "
                 f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}; machine: {platform.machine()}, "
                 f"{os.cpu_count()} cores, {platform.platform()}. Times are medians of {args.runs} runs; "
                 "ratios compare runs made side by side in this one invocation.")
    lines += ["", "## End to end (`liftmap map`) and the fixed-common-base-domain baseline", ""]
    lines.append("| pair | faces A / B | landmarks | cut s | flatten s | lift s | verify s | total s | peak MB "
                 "| outer its | distortion f mean / p95 / max | baseline (Tutte, no optimisation) mean / max |")
    lines.append("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name, a, b, lm in example_pairs():
        if args.pairs and name not in args.pairs:
            continue
        try:
            med, rep = median_runs(liftmap, a, b, lm, [], args.runs)
            base_med, base = median_runs(liftmap, a, b, lm, ["--max-iterations", "0"], 1)
        except RuntimeError as e:
            lines.append(f"| {name} | | | | | | | | | | {e} | |")
            sys.stderr.write(lines[-1] + "\n")
            continue
        d = rep["distortion"]["f"]
        bd = base["distortion"]["f"]
        lines.append(
            f"| {name} | {rep['input']['A']['faces']} / {rep['input']['B']['faces']} | {len(rep['landmarks'])} "
            f"| {med['cut']:.2f} | {med['flatten']:.2f} | {med['lift']:.2f} | {med['verify']:.2f} | {med['total']:.2f} "
            f"| {med['peak_mb']:.0f} | {len(rep['flatten']['iterations']) - 1} "
            f"| {d['mean']:.3f} / {d['p95']:.3f} / {d['max']:.2f} | {bd['mean']:.3f} / {bd['max']:.2f} |")
        sys.stderr.write(lines[-1] + "\n")
    lines += ["", "Distortion is per-sample max(Sigma, 1/sigma) of f, area-weighted (report.json explains the "
              "sampling); the baseline lifts the Tutte pair with the same cut and landmarks (paper Figure 14).", ""]
    for stage in ("cut", "flatten", "lift"):
        exe = os.path.join(args.build, "bench", stage, f"bench_{stage}")
        if not os.path.exists(exe):
            continue
        p = subprocess.run([exe, MESHES], capture_output=True, text=True)
        lines += [f"## Stage benchmark: `bench_{stage}`", "", "```", p.stdout.strip(), "```", ""]
        if p.returncode != 0:
            lines += [f"(exited {p.returncode}: {p.stderr.strip()[:500]})", ""]
    with open(os.path.join(ROOT, "bench", "RESULTS.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("bench: wrote bench/RESULTS.md")


if __name__ == "__main__":
    main()
