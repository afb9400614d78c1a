#!/usr/bin/env python3
"""Synthetic pairs for the flattening start (issue 24): a unit sphere with a thin tentacle of length-to-girth
ratio L/C, and a unit sphere with a short bump of the same girth, both surfaces of revolution about z, closed and
genus 0, with random corresponding landmarks.

A tentacle that no landmark lies on hangs uncut off the cut disk's interior, where a harmonic (Tutte) start
shrinks it like exp(-2 pi L / C) in length. Landmarks correspond through the shapes' common parametrisation:
(part, fraction along the part, angle about z), where the parts are the body, the tube and its cap.

usage: make_tentacle_pair.py OUT_DIR [--lc 6] [--bump-lc 0.3] [--radius 0.2] [--around 24] [--landmarks 10]
                             [--seed 1] [--uncut]
writes OUT_DIR/tentacle.off, OUT_DIR/bump.off and OUT_DIR/landmarks.txt (0-based vertex of A, vertex of B).
"""
import argparse
import math
import os
import random


def profile(radius, length, around, body_step):
    """Samples (r, z, part, fraction) along the profile from the bottom pole (z = -1) to the tip.

    The axial step follows the local circumference (2 pi r / around), so that triangles stay near equilateral,
    bounded by body_step on the body."""
    theta_j = math.pi - math.asin(radius)  # where the body's circle meets the tube's radius
    z_j = -math.cos(theta_j)
    body_len = theta_j
    cap_len = 0.5 * math.pi * radius
    total = body_len + length + cap_len

    def at(s):
        if s <= body_len:
            t = s
            return math.sin(t), -math.cos(t), 0, s / body_len
        if s <= body_len + length:
            return radius, z_j + (s - body_len), 1, (s - body_len) / max(length, 1e-12)
        t = (s - body_len - length) / radius  # 0 .. pi / 2 along the cap
        return radius * math.cos(t), z_j + length + radius * math.sin(t), 2, t / (0.5 * math.pi)

    samples = []
    s = 0.0
    while True:
        r, z, part, frac = at(s)
        samples.append((r, z, part, frac))
        step = min(body_step, max(2 * math.pi * max(r, 1e-9) / around * 0.87, 0.25 * body_step * radius))
        if s + 0.5 * step >= total:
            break
        s = min(s + step, total)
    if samples[-1][0] > 1e-9:  # end exactly at the tip
        samples.append((0.0, z_j + length + radius, 2, 1.0))
    return samples


def surface(radius, length, around, body_step):
    """Vertices, faces, and per-vertex (part, fraction, angle) of the surface of revolution."""
    prof = profile(radius, length, around, body_step)
    verts, params, rings = [], [], []
    for i, (r, z, part, frac) in enumerate(prof):
        if i == 0 or i == len(prof) - 1:
            rings.append([len(verts)])
            verts.append((0.0, 0.0, z))
            params.append((part, frac, 0.0))
            continue
        ring = []
        shift = 0.5 * (i % 2)
        for j in range(around):
            a = 2 * math.pi * (j + shift) / around
            ring.append(len(verts))
            verts.append((r * math.cos(a), r * math.sin(a), z))
            params.append((part, frac, a))
        rings.append(ring)
    faces = []
    for lo, hi in zip(rings[:-1], rings[1:]):
        if len(lo) == 1:
            faces += [(lo[0], hi[(j + 1) % around], hi[j]) for j in range(around)]
        elif len(hi) == 1:
            faces += [(lo[j], lo[(j + 1) % around], hi[0]) for j in range(around)]
        else:
            for j in range(around):
                a, b = lo[j], lo[(j + 1) % around]
                c, d = hi[j], hi[(j + 1) % around]
                faces += [(a, b, d), (a, d, c)]
    return verts, faces, params


def write_off(path, V, F):
    with open(path, "w") as f:
        f.write(f"OFF\n{len(V)} {len(F)} 0\n")
        for v in V:
            f.write(f"{v[0]:.17g} {v[1]:.17g} {v[2]:.17g}\n")
        for t in F:
            f.write(f"3 {t[0]} {t[1]} {t[2]}\n")


def nearest(params, part, frac, angle):
    best, best_d = 0, float("inf")
    for i, (p, fr, a) in enumerate(params):
        if p != part:
            continue
        da = abs((a - angle + math.pi) % (2 * math.pi) - math.pi)
        d = (fr - frac) ** 2 + 0.05 * da * da
        if d < best_d:
            best, best_d = i, d
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out")
    ap.add_argument("--lc", type=float, default=6.0, help="the tentacle's length over its circumference")
    ap.add_argument("--bump-lc", type=float, default=0.3, help="the bump's length over its circumference")
    ap.add_argument("--radius", type=float, default=0.2, help="tube radius (the body's is 1)")
    ap.add_argument("--around", type=int, default=24, help="vertices around each ring")
    ap.add_argument("--landmarks", type=int, default=10)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--uncut", action="store_true", help="no landmark on the tube or its cap")
    args = ap.parse_args()
    if args.landmarks < 2:
        ap.error("--landmarks must be at least 2")
    os.makedirs(args.out, exist_ok=True)
    circumference = 2 * math.pi * args.radius
    body_step = 2 * math.pi / args.around * 0.87
    Va, Fa, Pa = surface(args.radius, args.lc * circumference, args.around, body_step)
    Vb, Fb, Pb = surface(args.radius, args.bump_lc * circumference, args.around, body_step)
    write_off(os.path.join(args.out, "tentacle.off"), Va, Fa)
    write_off(os.path.join(args.out, "bump.off"), Vb, Fb)
    rng = random.Random(args.seed)
    pairs, used = [], set()
    while len(pairs) < args.landmarks:
        part = 0 if args.uncut else rng.choice([0, 0, 1, 2])
        frac = rng.uniform(0.05, 0.95) if part == 0 else rng.uniform(0.0, 1.0)
        angle = rng.uniform(0, 2 * math.pi)
        a, b = nearest(Pa, part, frac, angle), nearest(Pb, part, frac, angle)
        if a in used or b in {q for _, q in pairs}:
            continue
        used.add(a)
        pairs.append((a, b))
    with open(os.path.join(args.out, "landmarks.txt"), "w") as f:
        f.write(f"# tentacle (L/C {args.lc}) to bump (L/C {args.bump_lc}), seed {args.seed}"
                f"{', tentacle uncut' if args.uncut else ''}\n")
        for a, b in pairs:
            f.write(f"{a} {b}\n")
    print(f"{args.out}: tentacle {len(Va)} vertices, bump {len(Vb)} vertices, {len(pairs)} landmarks")


if __name__ == "__main__":
    main()
