#!/usr/bin/env python3
"""Whole-map sweep of the flattening start (issue 24): random landmark configurations on the libcgal-demo meshes
(each mapped onto a rotated, scaled and moved copy of itself, with the same landmarks) and on generated tentacle
pairs (scripts/make_tentacle_pair.py), tentacles cut and uncut, plus the four example pairs.

For every configuration it runs `liftmap map`, reads report.json and checks:
  exit 0; the start's smallest face area over the mean above 1e-10; the final flattenings' max distortion at most
  1000; the whole map under 60 s; the first outer iteration at most 3 times the median of the others.
It prints a markdown table (worst first by the first check that fails) and exits 1 if any configuration fails.
With --no-timing (the ctest `map_sweep`) the two checks on time are listed in the table but fail nothing: a test
does not depend on the machine's speed or load; `make bench` keeps them.

usage: map_sweep.py BUILD_DIR OUT_DIR [--limit N] [--table FILE] [--budget SECONDS] [--map-args "ARGS"] [--no-timing]
--map-args adds options to every `liftmap map` (e.g. "--start-relaxation 0" for the start without its relaxation).
With --budget, no configuration starts once the budget is spent; those not run are listed as such.
"""
import argparse
import json
import math
import os
import random
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MESHES = os.path.join(ROOT, "data", "meshes")
# Genus-0 closed meshes of libcgal-demo with protrusions (legs, tails, necks, horns, fingers, ears), small enough
# for a map well under a minute on two cores.
REAL = ["camel", "cow", "bull", "dino", "triceratops", "homer", "man", "bear", "hand", "blobby"]
EXAMPLES = ["sphere-ellipsoid", "camel-cow", "man-homer", "fandisk-bunny"]


def read_off(path):
    """Positions and faces of an OFF or COFF file (colours ignored)."""
    with open(path) as f:
        lines = [l.split("#")[0].split() for l in f]
    lines = [l for l in lines if l]
    assert lines[0][0].endswith("OFF"), path
    head = lines[0][1:] if len(lines[0]) > 1 else lines[1]
    first = 1 if len(lines[0]) > 1 else 2
    nv, nf = int(head[0]), int(head[1])
    V = [tuple(float(x) for x in l[:3]) for l in lines[first:first + nv]]
    F = [tuple(int(x) for x in l[1:1 + int(l[0])]) for l in lines[first + nv:first + nv + nf]]
    return V, F


def write_off(path, V, F):
    with open(path, "w") as f:
        f.write(f"OFF\n{len(V)} {len(F)} 0\n")
        f.writelines(f"{x:.17g} {y:.17g} {z:.17g}\n" for x, y, z in V)
        f.writelines(f"{len(t)} {' '.join(map(str, t))}\n" for t in F)


def moved_copy(V, rng):
    """V rotated about a random axis, scaled by 0.5-2 and moved."""
    axis = [rng.gauss(0, 1) for _ in range(3)]
    n = math.sqrt(sum(a * a for a in axis))
    x, y, z = (a / n for a in axis)
    t = rng.uniform(0, 2 * math.pi)
    c, s, C = math.cos(t), math.sin(t), 1 - math.cos(t)
    R = [[c + x * x * C, x * y * C - z * s, x * z * C + y * s],
         [y * x * C + z * s, c + y * y * C, y * z * C - x * s],
         [z * x * C - y * s, z * y * C + x * s, c + z * z * C]]
    k = math.exp(rng.uniform(math.log(0.5), math.log(2)))
    d = [rng.uniform(-3, 3) for _ in range(3)]
    return [tuple(k * sum(R[i][j] * v[j] for j in range(3)) + d[i] for i in range(3)) for v in V]


def configurations(out):
    """(name, A, B, landmarks file) of every configuration, generating its inputs under out/inputs."""
    rng = random.Random(24)
    inputs = os.path.join(out, "inputs")
    os.makedirs(inputs, exist_ok=True)
    configs = []
    for ex in EXAMPLES:
        with open(os.path.join(ROOT, "examples", ex, "meshes.txt")) as f:
            a, b = f.read().split()
        configs.append((ex, os.path.join(MESHES, a), os.path.join(MESHES, b),
                        os.path.join(ROOT, "examples", ex, "landmarks.txt")))
    for name in REAL:
        V, F = read_off(os.path.join(MESHES, name + ".off"))
        copy = os.path.join(inputs, name + "-moved.off")
        write_off(copy, moved_copy(V, rng), F)
        for k in (2, 5, 10, 20):
            lm = os.path.join(inputs, f"{name}-k{k}.txt")
            with open(lm, "w") as f:
                f.write(f"# {k} random vertices of {name}, the same on its moved copy\n")
                f.writelines(f"{v} {v}\n" for v in rng.sample(range(len(V)), k))
            configs.append((f"{name}-moved k={k}", os.path.join(MESHES, name + ".off"), copy, lm))
    for lc in (2, 4, 6, 8):
        for uncut in (True, False):
            for k in (3, 12):
                d = os.path.join(inputs, f"tentacle-{lc}-{'uncut' if uncut else 'cut'}-{k}")
                args = [sys.executable, os.path.join(ROOT, "scripts", "make_tentacle_pair.py"), d, "--lc", str(lc),
                        "--landmarks", str(k), "--seed", str(rng.randrange(1 << 30))]
                if uncut:
                    args.append("--uncut")
                subprocess.run(args, check=True, stdout=subprocess.DEVNULL)
                configs.append((f"tentacle L/C={lc} {'uncut' if uncut else 'cut'} k={k}",
                                os.path.join(d, "tentacle.off"), os.path.join(d, "bump.off"),
                                os.path.join(d, "landmarks.txt")))
    return configs


def run(liftmap, name, a, b, lm, out, extra=()):
    folder = os.path.join(out, "maps", name.replace(" ", "_").replace("/", "").replace("=", ""))
    t0 = time.monotonic()
    p = subprocess.run([liftmap, "map", a, b, "-l", lm, "-o", folder, "--quiet", *extra], capture_output=True, text=True,
                       timeout=900)
    row = {"name": name, "exit": p.returncode, "seconds": time.monotonic() - t0, "error": p.stderr.strip()[-200:]}
    if p.returncode != 0:
        return row
    with open(os.path.join(folder, "report.json")) as f:
        report = json.load(f)
    its = report["flatten"]["iterations"]
    row["start_min_area"] = its[0].get("min_area_ratio", float("nan"))
    row["start_max_distortion"] = its[0]["max_distortion"]
    row["final_max_distortion"] = its[-1]["max_distortion"]
    row["final_energy"] = its[-1]["energy"]
    row["outer"] = len(its) - 1
    row["start_s"] = its[0].get("seconds", 0)
    row["relaxation_steps"] = report["flatten"].get("joint_start_relaxation", {}).get("steps", 0)
    secs = [i["seconds"] for i in its[1:]]
    row["first_s"] = secs[0] if secs else 0
    row["median_s"] = statistics.median(secs[1:]) if len(secs) > 1 else float("nan")
    row["drift"] = [s["drift"] for s in report["flatten"].get("start", [{"drift": 0}, {"drift": 0}])]
    return row


def failures(row):
    return quality_failures(row) + (timing_failures(row) if row["exit"] == 0 else [])


def quality_failures(row):
    if row["exit"] != 0:
        return [f"exit {row['exit']}"]
    f = []
    if not row["start_min_area"] > 1e-10:
        f.append("start squeezed")
    if not row["final_max_distortion"] <= 1000:
        f.append("max distortion > 1000")
    return f


def timing_failures(row):
    f = []
    if not row["seconds"] < 60:
        f.append("over 60 s")
    if row["first_s"] > 3 * row["median_s"]:
        f.append("first iteration > 3x median")
    return f


def table(rows):
    lines = ["| configuration | exit | map s | start s (relaxation steps) | start: smallest face / mean "
             "| start max dist. | drift A, B | outer its | first it. s / median | final max dist. | final energy | fails |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if r["exit"] != 0:
            lines.append(f"| {r['name']} | {r['exit']} | {r['seconds']:.1f} | | | | | | | | | {r['error']} |")
            continue
        lines.append(f"| {r['name']} | 0 | {r['seconds']:.1f} | {r['start_s']:.2f} ({r['relaxation_steps']}) | "
                     f"{r['start_min_area']:.2g} | "
                     f"{r['start_max_distortion']:.3g} | {r['drift'][0]:g}, {r['drift'][1]:g} | {r['outer']} | "
                     f"{r['first_s']:.2f} / {r['median_s']:.2f} | {r['final_max_distortion']:.3g} | "
                     f"{r['final_energy']:.5g} | {', '.join(failures(r))} |")
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("build")
    ap.add_argument("out")
    ap.add_argument("--limit", type=int, default=0, help="run only the first N configurations")
    ap.add_argument("--table", help="also write the table to this file")
    ap.add_argument("--budget", type=float, default=0, help="seconds after which no configuration starts (0: none)")
    ap.add_argument("--map-args", default="", help="options added to every liftmap map")
    ap.add_argument("--no-timing", action="store_true", help="the checks on time fail nothing (listed only)")
    args = ap.parse_args()
    liftmap = os.path.join(args.build, "app", "liftmap")
    configs = configurations(args.out)
    if args.limit:
        configs = configs[:args.limit]
    rows, skipped = [], []
    started = time.monotonic()
    for i, c in enumerate(configs):
        if args.budget and time.monotonic() - started > args.budget:
            skipped.append(c[0])
            continue
        row = run(liftmap, *c, args.out, args.map_args.split())
        rows.append(row)
        print(f"[{i + 1}/{len(configs)}] {row['name']}: {row['seconds']:.1f} s, "
              f"{', '.join(failures(row)) or 'ok'}", flush=True)
    text = table(rows)
    bad = [r for r in rows if (quality_failures(r) if args.no_timing else failures(r))]
    summary = (f"\n{len(rows)} configurations, {len(bad)} failing a check{' other than time' if args.no_timing else ''}, "
               f"{sum(1 for r in rows if r['exit'] != 0)} maps failing; slowest map "
               f"{max(r['seconds'] for r in rows):.1f} s\n")
    if skipped:
        summary += f"Not run (budget spent): {', '.join(skipped)}\n"
    print(text + summary)
    if args.table:
        with open(args.table, "w") as f:
            f.write(text + summary)
    return 1 if bad or skipped else 0


if __name__ == "__main__":
    sys.exit(main())
