#!/usr/bin/env python3
"""Gives a triangle mesh a UV atlas and a texture painted on it, for `liftmap transfer texture`.

make-uv-atlas.py MESH OUT.obj [--size N] [--shuffle SEED] [--rotate DEGREES] [--pattern checker|smooth]

Writes OUT.obj (the mesh with `vt` and faces `f v/vt`), OUT.mtl and OUT.png (its texture, named by the MTL's
map_Kd). The atlas is a "triangle soup": every face is its own chart, its true shape scaled into one cell of a
square grid, with 3 texels of padding around it. The texture is a pattern of the 3D position (a checker of 8 squares
along the bounding box diagonal, or a smooth colour ramp), painted at every texel centre within 2 texels of a chart
(beyond the chart, the affine extension of the face: a gutter for bilinear sampling).

--shuffle SEED  places the faces in the grid in a random order (another atlas of the same mesh)
--rotate DEG    writes the mesh rotated by DEG about the z axis through its centroid; the texture stays painted with
                the unrotated positions, so that it is what a bake from the unrotated mesh through the map
                "x -> rotated x" should give

Example: the issue's demonstration, the texture of a mesh carried onto a rotated copy of itself with its own atlas:
  scripts/make-uv-atlas.py data/meshes/elephant.off out/A.obj
  scripts/make-uv-atlas.py data/meshes/elephant.off out/B.obj --rotate 90 --shuffle 1
  (out/B.png is the expected result of `liftmap transfer texture MAP --from out/A.obj --onto out/B.obj`)
Reads OFF and OBJ (v and triangular f). Needs python3 and numpy only.
"""
import argparse
import os
import struct
import sys
import zlib

import numpy as np


def read_mesh(path):
    """Vertices (#V by 3) and triangles (#F by 3, 0-based) of an OFF or OBJ file."""
    with open(path) as f:
        text = f.read()
    if path.lower().endswith('.off'):
        tokens = []
        for line in text.splitlines():
            tokens += line.split('#')[0].split()
        if not tokens[0].endswith('OFF'):
            sys.exit(f'{path}: not an OFF file')
        nv, nf = int(tokens[1]), int(tokens[2])
        i = 4
        V = np.array(tokens[i:i + 3 * nv], dtype=float).reshape(nv, 3)
        i += 3 * nv
        F = []
        for _ in range(nf):
            n = int(tokens[i])
            if n != 3:
                sys.exit(f'{path}: a face with {n} vertices: only triangles are supported')
            F.append([int(t) for t in tokens[i + 1:i + 4]])
            i += 1 + n
        return V, np.array(F, dtype=int)
    V, F = [], []
    for line in text.splitlines():
        t = line.split('#')[0].split()
        if not t:
            continue
        if t[0] == 'v':
            V.append([float(x) for x in t[1:4]])
        elif t[0] == 'f':
            if len(t) != 4:
                sys.exit(f'{path}: a face with {len(t) - 1} vertices: only triangles are supported')
            idx = [int(s.split('/')[0]) for s in t[1:]]
            F.append([i - 1 if i > 0 else len(V) + i for i in idx])
    return np.array(V, dtype=float), np.array(F, dtype=int)


def soup_atlas(V, F, size, order):
    """Per-corner UVs (#F*3 by 2): face f's true shape scaled into grid cell order[f], 3 texels from its sides."""
    n = len(F)
    columns = int(np.ceil(np.sqrt(n)))
    cell = size / columns  # texels
    pad = 3.0
    if cell - 2 * pad < 4:
        sys.exit(f'{n} faces do not fit a {size} x {size} atlas (cells of {cell:.1f} texels); raise --size')
    UV = np.zeros((3 * n, 2))
    for f in range(n):
        p = V[F[f]]
        # The face in its own plane: corner 0 at the origin, edge 0-1 along x.
        e1, e2 = p[1] - p[0], p[2] - p[0]
        x = e1 / np.linalg.norm(e1)
        normal = np.cross(e1, e2)
        y = np.cross(normal, x)
        y /= np.linalg.norm(y)
        q = np.array([[0, 0], [e1 @ x, e1 @ y], [e2 @ x, e2 @ y]])
        q -= q.min(axis=0)
        q *= (cell - 2 * pad) / q.max()
        c = order[f]
        corner = np.array([(c % columns) * cell + pad, (c // columns) * cell + pad])
        texel = q + corner  # x right, y down from the top row
        UV[3 * f:3 * f + 3, 0] = texel[:, 0] / size
        UV[3 * f:3 * f + 3, 1] = 1.0 - texel[:, 1] / size
    return UV


def pattern(X, lo, diagonal, kind):
    """RGB in [0,1] of 3D points X (#X by 3)."""
    s = (X - lo) / diagonal
    if kind == 'smooth':
        return np.clip(np.stack([0.5 + 0.4 * np.sin(2 * np.pi * s[:, 0]), 0.5 + 0.4 * np.cos(2 * np.pi * s[:, 1]),
                                 0.2 + 0.6 * s[:, 2]], axis=1), 0, 1)
    cells = np.floor(8 * s).astype(int).sum(axis=1) % 2
    ramp = 0.35 + 0.5 * s
    return np.where(cells[:, None] == 1, np.clip(ramp, 0, 1), 0.12)


def distance_to_edges(P, t):
    """Distance of points P (#P by 2) to the nearest edge of triangle t (3 by 2)."""
    d = np.full(len(P), np.inf)
    for k in range(3):
        a, e = t[k], t[(k + 1) % 3] - t[k]
        s = np.clip((P - a) @ e / (e @ e), 0, 1)
        d = np.minimum(d, np.linalg.norm(P - a - s[:, None] * e, axis=1))
    return d


def paint(V, F, UV, size, kind):
    """The texture (size by size by 3 bytes): the pattern at every texel centre within 2 texels of a chart."""
    image = np.zeros((size, size, 3))
    lo, hi = V.min(axis=0), V.max(axis=0)
    diagonal = np.linalg.norm(hi - lo)
    margin = 2.0
    for f in range(len(F)):
        t = np.stack([UV[3 * f:3 * f + 3, 0] * size, (1 - UV[3 * f:3 * f + 3, 1]) * size], axis=1)
        x0, y0 = np.floor(t.min(axis=0) - margin).astype(int)
        x1, y1 = np.ceil(t.max(axis=0) + margin).astype(int)
        xs, ys = np.meshgrid(np.arange(max(x0, 0), min(x1, size)), np.arange(max(y0, 0), min(y1, size)))
        P = np.stack([xs.ravel() + 0.5, ys.ravel() + 0.5], axis=1)
        M = np.array([t[1] - t[0], t[2] - t[0]]).T
        b12 = np.linalg.solve(M, (P - t[0]).T).T
        b = np.column_stack([1 - b12.sum(axis=1), b12])
        near = (b.min(axis=1) >= 0) | (distance_to_edges(P, t) <= margin)
        X = b[near] @ V[F[f]]
        image[ys.ravel()[near], xs.ravel()[near]] = pattern(X, lo, diagonal, kind)
    return np.round(np.clip(image, 0, 1) * 255).astype(np.uint8)


def write_png(path, rgb):
    """An 8-bit RGB PNG (no filtering)."""
    h, w, _ = rgb.shape
    raw = b''.join(b'\x00' + rgb[y].tobytes() for y in range(h))

    def chunk(kind, data):
        return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data) & 0xffffffff)

    with open(path, 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 2, 0, 0, 0)) +
                chunk(b'IDAT', zlib.compress(raw, 6)) + chunk(b'IEND', b''))


def write_obj(path, V, F, UV, mtl):
    with open(path, 'w') as f:
        f.write(f'mtllib {mtl}\nusemtl material\n')
        f.writelines(f'v {x:.17g} {y:.17g} {z:.17g}\n' for x, y, z in V)
        f.writelines(f'vt {u:.17g} {v:.17g}\n' for u, v in UV)
        f.writelines(f'f {a + 1}/{3 * i + 1} {b + 1}/{3 * i + 2} {c + 1}/{3 * i + 3}\n' for i, (a, b, c) in enumerate(F))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('mesh')
    parser.add_argument('out', help='OUT.obj; OUT.mtl and OUT.png are written next to it')
    parser.add_argument('--size', type=int, default=1024, help='texels of the square texture (default 1024)')
    parser.add_argument('--shuffle', type=int, help='seed of a random order of the faces in the grid')
    parser.add_argument('--rotate', type=float, default=0.0, help='degrees about z through the centroid')
    parser.add_argument('--pattern', choices=['checker', 'smooth'], default='checker')
    args = parser.parse_args()
    if not args.out.endswith('.obj'):
        sys.exit('the output must be an .obj file')
    V, F = read_mesh(args.mesh)
    order = np.arange(len(F))
    if args.shuffle is not None:
        order = np.random.default_rng(args.shuffle).permutation(len(F))
    UV = soup_atlas(V, F, args.size, order)
    image = paint(V, F, UV, args.size, args.pattern)
    stem = os.path.splitext(args.out)[0]
    name = os.path.basename(stem)
    if args.rotate:
        a = np.radians(args.rotate)
        R = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])
        c = V.mean(axis=0)
        V = (V - c) @ R.T + c
    write_png(stem + '.png', image)
    with open(stem + '.mtl', 'w') as f:
        f.write(f'newmtl material\nKd 1 1 1\nmap_Kd {name}.png\n')
    write_obj(args.out, V, F, UV, name + '.mtl')
    print(f'{args.out}: {len(F)} faces, each its own chart in a {args.size} x {args.size} atlas; texture {stem}.png')


if __name__ == '__main__':
    main()
