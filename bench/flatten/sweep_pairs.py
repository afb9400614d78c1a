#!/usr/bin/env python3
"""The flattening on eleven pairs, one line each: the pairs docs/performance.md judges a flattening setting on.

    bench/flatten/sweep_pairs.py BUILD [--only NAME ...] [--meshes DIR]

Runs BUILD/bench/flatten/profile_flatten on the three example pairs with their landmarks and on eight pairs of the
meshes from `make meshes` with 5 random vertex landmarks each (seeds 100-107, the same on every machine), one after
the other, with this process's environment: set PROFILE_* variables (profile_flatten.cpp reads them) to compare a
setting against the default. Prints per pair the start's per-disk pre-optimisation and joint relaxation steps, the
outer iterations' Newton steps, the final energy and the flattening's seconds, then the sums. One run each: the
seconds are indicative only; judge speed side by side (docs/performance.md says how).
"""

import argparse
import os
import random
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "bench"))
from map_sweep import read_off  # noqa: E402  (bench/map_sweep.py: the OFF reader of the whole-map sweep)

EXAMPLES = ["camel-cow", "man-homer", "fandisk-bunny"]
RANDOM_PAIRS = [("armadillo", "bunny00"), ("diplodocus", "camel"), ("man", "cow"), ("hand", "triceratops"),
                ("bear", "blobby"), ("triceratops", "camel"), ("armadillo", "homer"), ("camel", "cow")]


def pairs(meshes, folder):
    """(name, mesh A, mesh B, landmark file) of the eleven pairs; the random landmark files written into folder."""
    out = []
    for name in EXAMPLES:
        a, b = open(os.path.join(ROOT, "examples", name, "meshes.txt")).read().split()
        out.append((name, os.path.join(meshes, a), os.path.join(meshes, b),
                    os.path.join(ROOT, "examples", name, "landmarks.txt")))
    for k, (a, b) in enumerate(RANDOM_PAIRS):
        path_a, path_b = os.path.join(meshes, a + ".off"), os.path.join(meshes, b + ".off")
        rng = random.Random(100 + k)
        va = rng.sample(range(len(read_off(path_a)[0])), 5)
        vb = rng.sample(range(len(read_off(path_b)[0])), 5)
        landmarks = os.path.join(folder, f"{a}-{b}-random5.txt")
        with open(landmarks, "w") as f:
            f.write("".join(f"{x} {y}\n" for x, y in zip(va, vb)))
        out.append((f"{a}-{b} random", path_a, path_b, landmarks))
    return out


def run(profile, a, b, landmarks):
    """One profile_flatten run: (per-disk steps, relaxation steps, outer Newton steps per iteration, energy, seconds,
    stop reason)."""
    text = subprocess.run([profile, a, b, landmarks], capture_output=True, text=True, check=True).stdout
    steps = [int(s) for i, s in re.findall(r"^iterate (\d+): .*Newton steps (\d+)", text, re.M) if int(i) > 0]
    energy = re.findall(r"^iterate \d+: energy (\S+)", text, re.M)[-1]
    start = re.search(r"per-disk steps (\d+) \+ (\d+), joint relaxation (\d+) steps", text)
    per_disk, relaxation = int(start.group(1)) + int(start.group(2)), int(start.group(3))
    total = re.search(r"^flatten total (\S+) s ?(.*)$", text, re.M)
    return per_disk, relaxation, steps, float(energy), float(total.group(1)), total.group(2).strip()


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("build", help="the build folder (holds bench/flatten/profile_flatten)")
    parser.add_argument("--only", nargs="*", help="pair names to run (default: all eleven)")
    parser.add_argument("--meshes", default=os.path.join(ROOT, "data", "meshes"), help="folder of `make meshes`")
    args = parser.parse_args()
    profile = os.path.join(args.build, "bench", "flatten", "profile_flatten")
    if not os.access(profile, os.X_OK):
        sys.exit(f"sweep_pairs: {profile} not found: build it (cmake --build {args.build} --target profile_flatten)")
    settings = " ".join(f"{k}={v}" for k, v in sorted(os.environ.items()) if k.startswith("PROFILE_"))
    print(f"# settings: {settings or 'the defaults'}")
    print(f"{'pair':<28} {'per-disk':>8} {'relaxation':>10} {'outer Newton steps':>20} {'energy':>12} {'seconds':>8}")
    sums = [0, 0, 0, 0.0]
    with tempfile.TemporaryDirectory() as folder:
        for name, a, b, landmarks in pairs(args.meshes, folder):
            if args.only and name not in args.only and name.split()[0] not in args.only:
                continue
            per_disk, relaxation, steps, energy, seconds, stop = run(profile, a, b, landmarks)
            outer = "+".join(map(str, steps))
            print(f"{name:<28} {per_disk:>8} {relaxation:>10} {outer:>20} {energy:>12.6f} {seconds:>8.2f} {stop}",
                  flush=True)
            sums[0] += per_disk
            sums[1] += relaxation
            sums[2] += sum(steps)
            sums[3] += seconds
    print(f"{'sum':<28} {sums[0]:>8} {sums[1]:>10} {sums[2]:>20} {'':>12} {sums[3]:>8.2f}")


if __name__ == "__main__":
    main()
