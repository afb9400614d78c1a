#!/usr/bin/env bash
# `liftmap transfer texture` (issue 32): usage, input and overlay errors with their exit codes, and a bake end to
# end: larger_sphere.off with a soup atlas and a smooth texture (scripts/make-uv-atlas.py) onto a copy rotated by
# 90 degrees with another atlas, through the exact overlay of that map (the identity of the two meshes' faces,
# written here). The baked PNG must match the texture make-uv-atlas.py painted for the rotated copy.
set -u
liftmap="$1"
meshes="$2"
source "$(dirname "$0")/lib.sh"
python=/usr/bin/python3  # Debian's, with numpy (a pyenv python first in PATH may lack it)
atlas="$(dirname "$0")/../../scripts/make-uv-atlas.py"
mesh="$meshes/larger_sphere.off"
"$python" "$atlas" "$mesh" "$tmp/A.obj" --size 512 --pattern smooth >/dev/null
"$python" "$atlas" "$mesh" "$tmp/B.obj" --size 512 --pattern smooth --shuffle 1 --rotate 90 >/dev/null
mkdir "$tmp/map"
# The overlay of the map "x -> rotated x": A's own triangles, every vertex the same point of A and of B.
"$python" - "$tmp/A.obj" "$tmp/map" <<'PY'
import sys
V, F = [], []
for line in open(sys.argv[1]):
    t = line.split()
    if t and t[0] == 'v':
        V.append(line)
    elif t and t[0] == 'f':
        F.append([int(s.split('/')[0]) - 1 for s in t[1:]])
where = {}
for f, face in enumerate(F):
    for k, v in enumerate(face):
        where.setdefault(v, (f, k))
with open(sys.argv[2] + '/overlay.obj', 'w') as out:
    out.writelines(V)
    out.writelines(f'f {a + 1} {b + 1} {c + 1}\n' for a, b, c in F)
with open(sys.argv[2] + '/overlay_points.txt', 'w') as out:
    for v in range(len(V)):
        f, k = where[v]
        b = ' '.join('1' if j == k else '0' for j in range(3))
        out.write(f'{f} {b} {f} {b}\n')
with open(sys.argv[2] + '/overlay_faces.txt', 'w') as out:
    out.writelines(f'{f} {f}\n' for f in range(len(F)))
PY

# Usage errors (2).
expect "no --from" 2 "--from is required" -- transfer texture "$tmp/map" --onto "$tmp/B.obj" -o "$tmp/x.png"
expect "not a png" 2 "must end in .png" -- transfer texture "$tmp/map" --from "$tmp/A.obj" --onto "$tmp/B.obj" \
  -o "$tmp/x.jpg"
expect "size 0" 2 "--size" -- transfer texture "$tmp/map" --from "$tmp/A.obj" --onto "$tmp/B.obj" --size 0 \
  -o "$tmp/x.png"
expect "overwrite the texture" 2 "" -- transfer texture "$tmp/map" --from "$tmp/A.obj" --onto "$tmp/B.obj" \
  -o "$tmp/A.png"

# Inputs that cannot be read (3), naming the file and line.
mkdir "$tmp/empty"
expect "no overlay" 3 "^liftmap: $tmp/empty: no overlay.obj in this folder" -- \
  transfer texture "$tmp/empty" --from "$tmp/A.obj" --onto "$tmp/B.obj" -o "$tmp/x.png"
sed -e 's|^f \([0-9]*\)/[0-9]* \([0-9]*\)/[0-9]* \([0-9]*\)/[0-9]*$|f \1 \2 \3|' "$tmp/A.obj" >"$tmp/no_vt.obj"
line=$(grep -n '^f ' "$tmp/no_vt.obj" | head -1 | cut -d: -f1)
expect "faces without vt" 3 "^liftmap: $tmp/no_vt.obj:$line: face corner '[0-9]+' has no texture coordinate index" -- \
  transfer texture "$tmp/map" --from "$tmp/no_vt.obj" --onto "$tmp/B.obj" -o "$tmp/x.png"
grep -v '^mtllib' "$tmp/A.obj" >"$tmp/no_mtl.obj"
expect "no texture image" 3 "^liftmap: $tmp/no_mtl.obj: no texture image \(it has no mtllib\); give one with --texture" \
  -- transfer texture "$tmp/map" --from "$tmp/no_mtl.obj" --onto "$tmp/B.obj" -o "$tmp/x.png"
expect "texture not an image" 3 "^liftmap: $tmp/A.obj: cannot read the image" -- \
  transfer texture "$tmp/map" --from "$tmp/A.obj" --onto "$tmp/B.obj" --texture "$tmp/A.obj" -o "$tmp/x.png"
require "nothing written on errors" test ! -e "$tmp/x.png"

# An overlay that does not belong to the meshes (4).
cp -r "$tmp/map" "$tmp/bad_face"
sed -i '1s/.*/0 1620/' "$tmp/bad_face/overlay_faces.txt"
expect "face of B out of range" 4 "overlay_faces.txt:[0-9]+: .*1620.* is not a face index of B \(1620 faces\)" -- \
  transfer texture "$tmp/bad_face" --from "$tmp/A.obj" --onto "$tmp/B.obj" -o "$tmp/x.png"
"$python" "$atlas" "$meshes/ellipsoid.off" "$tmp/E.obj" --size 512 >/dev/null
expect "another mesh as A" 4 "not a face index of A|does not belong to these meshes" -- \
  transfer texture "$tmp/map" --from "$tmp/E.obj" --onto "$tmp/B.obj" -o "$tmp/x.png"
cp -r "$tmp/map" "$tmp/moved"
sed -i '1s/^v .*/v 5 5 5/' "$tmp/moved/overlay.obj"
expect "overlay vertex off A" 4 "does not belong to these meshes: vertex 0 is at" -- \
  transfer texture "$tmp/moved" --from "$tmp/A.obj" --onto "$tmp/B.obj" -o "$tmp/x.png"

# The bake: a PNG of A's texture's size, B's OBJ/MTL next to it, and the texture painted for the rotated copy.
expect "bake" 0 "^liftmap: [0-9]+ chart texels and [0-9]+ gutter texels of 512 x 512 baked into $tmp/out/baked.png" \
  -- transfer texture "$tmp/map" --from "$tmp/A.obj" --onto "$tmp/B.obj" -o "$tmp/out/baked.png"
require "mtl names the png" grep -qx "map_Kd baked.png" "$tmp/out/baked.mtl"
require "obj names the mtl" grep -qx "mtllib baked.mtl" "$tmp/out/baked.obj"
require "obj keeps B's vt" test "$(grep -c '^vt ' "$tmp/out/baked.obj")" = "$(grep -c '^vt ' "$tmp/B.obj")"
expect "bake through the overlay obj, --size, --clamp" 0 "of 256 x 256 baked" -- transfer texture \
  "$tmp/map/overlay.obj" --from "$tmp/A.obj" --onto "$tmp/B.obj" --size 256 --clamp --gutter 2 -o "$tmp/small.png"
expect "bake without gutter" 0 " 0 gutter texels" -- transfer texture "$tmp/map" --from "$tmp/A.obj" --onto "$tmp/B.obj" \
  --gutter 0 -o "$tmp/charts.png"
# Differences in 1/255 from the texture make-uv-atlas.py painted for B, over B's chart texels (those the bake without
# gutter paints: the smooth pattern is never black); the gutter must keep them and fill every texel within 2 texels
# of a chart (where make-uv-atlas.py painted).
if ! figures=$("$python" - "$tmp/out/baked.png" "$tmp/charts.png" "$tmp/B.png" <<'PY'
import sys, zlib
import numpy as np

def read_png(path):
    data = open(path, 'rb').read()
    pos, idat, w, h = 8, b'', 0, 0
    while pos < len(data):
        n = int.from_bytes(data[pos:pos + 4], 'big')
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        if kind == b'IHDR':
            w, h = int.from_bytes(body[0:4], 'big'), int.from_bytes(body[4:8], 'big')
            assert body[8:10] == b'\x08\x02', '8-bit RGB expected'
        elif kind == b'IDAT':
            idat += body
        pos += 12 + n
    raw = np.frombuffer(zlib.decompress(idat), dtype=np.uint8).reshape(h, 1 + 3 * w)
    out = np.zeros((h, 3 * w), dtype=np.int64)
    for y in range(h):
        f, row = raw[y, 0], raw[y, 1:].astype(np.int64)
        up = out[y - 1] if y else np.zeros(3 * w, dtype=np.int64)
        if f in (0, 2):
            out[y] = (row + (up if f == 2 else 0)) % 256
            continue
        cur = np.zeros(3 * w, dtype=np.int64)
        for i in range(3 * w):
            a = cur[i - 3] if i >= 3 else 0
            c = up[i - 3] if i >= 3 else 0
            b = up[i]
            if f == 1:
                pred = a
            elif f == 3:
                pred = (a + b) // 2
            else:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
            cur[i] = (row[i] + pred) % 256
        out[y] = cur
    return out.reshape(h, w, 3)

baked, charts, expected = (read_png(p) for p in sys.argv[1:4])
chart = charts.sum(axis=2) > 0
d = np.abs(charts - expected)[chart].max(axis=1)
kept = (baked[chart] == charts[chart]).all()
unfilled = ((expected.sum(axis=2) > 0) & (baked.sum(axis=2) == 0)).sum()
print(f'{chart.sum()} chart texels: max {d.max()}/255, mean {d.mean():.3f}/255; gutter keeps the charts: {kept}; '
      f'texels within 2 of a chart left empty: {unfilled}')
sys.exit(0 if d.max() <= 2 and d.mean() <= 0.6 and kept and unfilled == 0 else 1)
PY
); then
  echo "FAIL baked texture differs from the expected one: $figures"
  failures=$((failures + 1))
fi
checks=$((checks + 1))
echo "baked against expected: $figures"
finish
