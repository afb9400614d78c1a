#!/usr/bin/env python3
"""Maps two meshes with the liftmap module, prints the map's distortion and carries a per-vertex colour from A to B.

    PYTHONPATH=build/python python3 examples/python/map_pair.py \\
        data/meshes/larger_sphere.off data/meshes/ellipsoid.off examples/sphere-ellipsoid/landmarks.txt out/python

writes out/python/ (the files of `liftmap map`) and out/python/B_coloured.off: B with A's colours.
"""

import os
import sys

import numpy as np

import liftmap


def colour_by_position(V):
    """An RGB colour per vertex from its position in the bounding box, in [0, 1]."""
    return (V - V.min(0)) / np.maximum(V.max(0) - V.min(0), 1e-300)


def write_coloured_off(path, V, F, rgb):
    """An OFF file with one colour (0-255) per vertex."""
    with open(path, "w") as f:
        f.write(f"COFF\n{len(V)} {len(F)} 0\n")
        for p, c in zip(V, np.round(255 * rgb).astype(int)):
            f.write(f"{p[0]:.17g} {p[1]:.17g} {p[2]:.17g} {c[0]} {c[1]} {c[2]} 255\n")
        for t in F:
            f.write(f"3 {t[0]} {t[1]} {t[2]}\n")


def main(path_a, path_b, path_landmarks, out):
    VA, FA = liftmap.read_mesh(path_a)
    VB, FB = liftmap.read_mesh(path_b)
    landmarks = liftmap.read_surface_landmarks(path_landmarks, VA, FA, VB, FB)  # every token form of the CLI
    m = liftmap.map(VA, FA, VB, FB, landmarks, name_a=path_a, name_b=path_b,
                    progress=lambda stage, message: print(f"{stage:8} {message}", file=sys.stderr))
    f = m.report["distortion"]["f"]
    print(f"distortion of f: mean {f['mean']:.3f}, median {f['median']:.3f}, p95 {f['p95']:.3f}, max {f['max']:.3g}")
    m.save(out)
    # Each vertex of B takes A's colour at its image on A.
    write_coloured_off(os.path.join(out, "B_coloured.off"), VB, FB, m.transfer(colour_by_position(VA)))
    print(f"map written to {out}/, B with A's colours to {out}/B_coloured.off")


if __name__ == "__main__":
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    main(*sys.argv[1:])
