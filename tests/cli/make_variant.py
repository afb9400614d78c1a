#!/usr/bin/env python3
"""Writes a variant of a plain OFF mesh, to recreate in a test the inputs that exposed a problem.

make_variant.py KIND IN OUT [VALUE]
  scale VALUE, translate VALUE   coordinates times VALUE / plus VALUE (every axis)
  invert                         every face's vertex order reversed (inward normals)
  bom                            a UTF-8 byte-order mark before the content
  one_line                       the whole OFF on one line
  extra_face                     the header announces one face fewer than the file has
  ply_ascii, ply_binary          the mesh as PLY (the first face's first index replaced by VALUE if given)
  ply_nan                        ASCII PLY with the first vertex's y coordinate 'nan'
  stl_binary                     binary STL; VALUE, if given, is the triangle count written in its header
  stl_ascii_nan                  ASCII STL with the first vertex's y coordinate 'nan'
"""
import struct
import sys


def read_off(path):
    tokens = []
    with open(path) as f:
        for line in f:
            tokens += line.split('#')[0].split()
    assert tokens[0] == 'OFF'
    nv, nf = int(tokens[1]), int(tokens[2])
    i = 4
    V = [[float(x) for x in tokens[i + 3 * k:i + 3 * k + 3]] for k in range(nv)]
    i += 3 * nv
    F = []
    for _ in range(nf):
        assert tokens[i] == '3'
        F.append([int(x) for x in tokens[i + 1:i + 4]])
        i += 4
    return V, F


def off_text(V, F, nf=None):
    lines = ['OFF', '%d %d 0' % (len(V), len(F) if nf is None else nf)]
    lines += ['%r %r %r' % tuple(v) for v in V]
    lines += ['3 %d %d %d' % tuple(f) for f in F]
    return '\n'.join(lines) + '\n'


def ply_header(V, F, fmt):
    return ('ply\nformat %s 1.0\nelement vertex %d\nproperty double x\nproperty double y\nproperty double z\n'
            'element face %d\nproperty list uchar int vertex_indices\nend_header\n' % (fmt, len(V), len(F)))


def main():
    kind, src, dst = sys.argv[1:4]
    value = sys.argv[4] if len(sys.argv) > 4 else None
    V, F = read_off(src)
    out = None
    if kind == 'scale':
        out = off_text([[x * float(value) for x in v] for v in V], F)
    elif kind == 'translate':
        out = off_text([[x + float(value) for x in v] for v in V], F)
    elif kind == 'invert':
        out = off_text(V, [[f[0], f[2], f[1]] for f in F])
    elif kind == 'bom':
        out = '\ufeff' + off_text(V, F)
    elif kind == 'one_line':
        out = off_text(V, F).replace('\n', ' ').strip() + '\n'
    elif kind == 'extra_face':
        out = off_text(V, F, nf=len(F) - 1)
    elif kind in ('ply_ascii', 'ply_nan'):
        if value is not None:
            F[0][0] = int(value)
        rows = ['%r %r %r' % tuple(v) for v in V]
        if kind == 'ply_nan':
            rows[0] = '%r nan %r' % (V[0][0], V[0][2])
        out = ply_header(V, F, 'ascii') + '\n'.join(rows + ['3 %d %d %d' % tuple(f) for f in F]) + '\n'
    elif kind == 'ply_binary':
        if value is not None:
            F[0][0] = int(value)
        data = ply_header(V, F, 'binary_little_endian').encode()
        data += b''.join(struct.pack('<3d', *v) for v in V)
        data += b''.join(struct.pack('<B3i', 3, *f) for f in F)
        open(dst, 'wb').write(data)
        return
    elif kind == 'stl_binary':
        n = len(F) if value is None else int(value)
        data = b' ' * 80 + struct.pack('<I', n)
        for f in F:
            data += struct.pack('<12fH', 0, 0, 0, *[x for k in f for x in V[k]], 0)
        open(dst, 'wb').write(data)
        return
    elif kind == 'stl_ascii_nan':
        rows = ['solid test']
        for j, f in enumerate(F):
            rows += ['facet normal 0 0 0', 'outer loop']
            for k in f:
                x, y, z = V[k]
                rows.append('vertex %r %s %r' % (x, 'nan' if k == F[0][0] else repr(y), z))
            rows += ['endloop', 'endfacet']
        out = '\n'.join(rows + ['endsolid test']) + '\n'
    else:
        sys.exit('unknown kind ' + kind)
    with open(dst, 'w', encoding='utf-8') as f:
        f.write(out)


main()
