"""Every documented bad input raises the documented liftmap exception, its message naming the element."""

import re

import numpy as np
import pytest

import liftmap
from conftest import PATH_A


def torus(n=12, m=8):
    """A closed genus-1 mesh: n by m quads of a torus, split into triangles."""
    u, v = np.meshgrid(np.arange(n) * 2 * np.pi / n, np.arange(m) * 2 * np.pi / m, indexing="ij")
    V = np.stack([(2 + np.cos(v)) * np.cos(u), (2 + np.cos(v)) * np.sin(u), np.sin(v)], -1).reshape(-1, 3)
    idx = lambda i, j: (i % n) * m + (j % m)
    F = [[idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)] for i in range(n) for j in range(m)]
    F += [[idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)] for i in range(n) for j in range(m)]
    return V, np.array(F)


def with_a(pair, VA=None, FA=None, landmarks=None):
    VA0, FA0, VB, FB, L0 = pair
    return (VA0 if VA is None else VA, FA0 if FA is None else FA, VB, FB, L0 if landmarks is None else landmarks)


def nan_vertex(V):
    V = V.copy()
    V[5, 1] = np.nan
    return V


def face_index(F, value, dtype=None):
    F = F.astype(dtype or F.dtype)
    F[3, 1] = value
    return F


def non_manifold(V, F):
    """A fourth vertex and a face on edge (F[0][0], F[0][1]), which then has three faces."""
    V = np.vstack([V, V[F[0]].mean(0) + 0.1])
    return V, np.vstack([F, [[F[0][1], F[0][0], len(V) - 1]]])


def landmarks_with(L, row, value):
    L = L.copy()
    L[row] = value
    return L


CASES = {
    "vertices shape": (lambda p: with_a(p, VA=p[0][:, :2]), liftmap.InvalidInputError, r"VA: expected an array of shape \(#V, 3\), got shape \(812, 2\)"),
    "vertices dtype": (lambda p: with_a(p, VA=p[0].astype(np.int64)), liftmap.InvalidInputError, r"VA: expected float64 or float32 vertices, got int64"),
    "vertices not an array": (lambda p: with_a(p, VA="vertices"), liftmap.InvalidInputError, r"VA: expected float64 or float32"),
    "faces dtype": (lambda p: with_a(p, FA=p[1].astype(np.float64)), liftmap.InvalidInputError, r"FA: expected int32 or int64 faces, got float64"),
    "faces shape": (lambda p: with_a(p, FA=p[1].ravel()), liftmap.InvalidInputError, r"FA: expected an array of shape \(#F, 3\), got shape \(4860,\)"),
    "NaN": (lambda p: with_a(p, VA=nan_vertex(p[0])), liftmap.InvalidInputError, r"mesh A: cannot be mapped: vertex 5 has a non-finite coordinate"),
    "index out of range": (lambda p: with_a(p, FA=face_index(p[1], 10**6)), liftmap.InvalidInputError, r"face 3 references a vertex outside 0..811"),
    "negative index": (lambda p: with_a(p, FA=face_index(p[1], -1)), liftmap.InvalidInputError, r"face 3 references a vertex outside 0..811"),
    "index beyond int32": (lambda p: with_a(p, FA=face_index(p[1], 2**40, np.int64)), liftmap.InvalidInputError, r"FA: face 3 has index 1099511627776, beyond the int32 range"),
    "non-manifold": (lambda p: with_a(p, *non_manifold(p[0], p[1])), liftmap.InvalidInputError, r"mesh A: cannot be mapped: .*edge \(\d+, \d+\) is shared by 3 faces"),
    "genus 1": (lambda p: with_a(p, *torus(), landmarks=np.array([[0, 117], [50, 138]])), liftmap.InvalidInputError, r"mesh A: cannot be mapped: .*genus 1"),
    "landmark out of range": (lambda p: with_a(p, landmarks=landmarks_with(p[4], 2, [9999, 0])), liftmap.InvalidInputError, r"landmarks: row 2: vertex 9999 is out of range for mesh A \(812 vertices\)"),
    "landmark negative": (lambda p: with_a(p, landmarks=landmarks_with(p[4], 1, [3, -4])), liftmap.InvalidInputError, r"landmarks: row 1: negative vertex index '-4' for mesh B"),
    "landmark twice": (lambda p: with_a(p, landmarks=landmarks_with(p[4], 3, p[4][0])), liftmap.InvalidInputError, r"landmarks: row 3: vertex 286 of mesh A is already a landmark \(row 0\)"),
    "one landmark": (lambda p: with_a(p, landmarks=p[4][:1]), liftmap.InvalidInputError, r"landmarks: 1 landmark pair\(s\); at least 2 are needed"),
    "landmarks shape": (lambda p: with_a(p, landmarks=p[4].ravel()), liftmap.InvalidInputError, r"landmarks: expected an array of shape \(k, 2\)"),
    "landmarks dtype": (lambda p: with_a(p, landmarks=p[4].astype(float)), liftmap.InvalidInputError, r"landmarks: expected int32 or int64"),
}


@pytest.mark.parametrize("case", CASES)
def test_bad_input_raises(pair, case):
    make, error, message = CASES[case]
    with pytest.raises(error, match=message):
        liftmap.map(*make(pair), max_iterations=0)


OPTIONS = {
    "p": ({"p": 3}, r"p: '3' is not one of 2, inf"),
    "h": ({"h": "eq4"}, r"h: 'eq4' is not one of eq3, eq2"),
    "solver": ({"solver": "newton"}, r"solver: 'newton' is not one of auto, barrier, primal-dual"),
    "tree": ({"tree": "star"}, r"tree: 'star' is not one of mst, path"),
    "tolerance": ({"tolerance": float("nan")}, r"tolerance: value nan is not a finite number > 0"),
    "max_iterations": ({"max_iterations": -1}, r"max_iterations: value -1 not in range 0 to 10000"),
    "samples": ({"samples": 11}, r"samples: value 11 not in range 1 to 10"),
    "start_relaxation": ({"start_relaxation": -1}, r"start_relaxation: value -1 not in range 0 to 10000"),
    "threads": ({"threads": 0}, r"threads: value 0 not in range 1 to \d+"),
    "progress": ({"progress": 3}, r"progress: expected a callable"),
}


@pytest.mark.parametrize("option", OPTIONS)
def test_bad_option_raises_usage_error(pair, option):
    keywords, message = OPTIONS[option]
    with pytest.raises(liftmap.UsageError, match=message):
        liftmap.map(*pair, **keywords)


def test_exceptions_mirror_the_cpp_types():
    for name, builtin in (("ReadError", OSError), ("InvalidInputError", ValueError), ("UsageError", ValueError),
                          ("PipelineError", RuntimeError)):
        error = getattr(liftmap, name)
        assert issubclass(error, liftmap.Error) and issubclass(error, builtin)


def test_read_errors_name_the_file(tmp_path):
    with pytest.raises(liftmap.ReadError, match=re.escape(str(tmp_path / "missing.off"))):
        liftmap.read_mesh(str(tmp_path / "missing.off"))
    bad = tmp_path / "landmarks.txt"
    bad.write_text("1 2\n3 x\n")
    with pytest.raises(liftmap.InvalidInputError, match=re.escape(str(bad)) + r":2: 'x' is not a vertex index"):
        liftmap.read_landmarks(str(bad))
    with pytest.raises(liftmap.InvalidInputError, match=r":1: vertex 1 is out of range for mesh A \(1 vertices\)"):
        liftmap.read_landmarks(str(bad), 1, 10)


def test_check_reports_problems_without_raising(pair):
    VA, FA = pair[0], pair[1]
    report = liftmap.check(nan_vertex(VA), FA)
    assert not report["mappable"]
    assert report["problems"][0]["kind"] == "non-finite coordinate"
    assert "vertex 5" in report["problems"][0]["examples"][0]
    with pytest.raises(liftmap.InvalidInputError, match="F: expected int32 or int64"):
        liftmap.check(VA, FA.astype(np.float32))


def test_evaluate_and_transfer_check_their_arrays(sphere_map):
    with pytest.raises(liftmap.InvalidInputError, match=r"faces: row 1: face 5000 is out of range \(1620 faces\)"):
        sphere_map.evaluate(np.array([0, 5000]), np.full((2, 3), 1 / 3))
    with pytest.raises(liftmap.InvalidInputError, match=r"barycentric: row 0: .* are not barycentric coordinates"):
        sphere_map.evaluate(np.array([0]), np.array([[0.5, 0.6, -0.1]]))
    with pytest.raises(liftmap.InvalidInputError, match=r"values: 3 rows, but mesh A has 812 vertices"):
        sphere_map.transfer(np.zeros((3, 2)))
    with pytest.raises(liftmap.UsageError, match=r"source: 'C' is not one of A, B"):
        sphere_map.transfer(np.zeros(812), source="C")


def test_an_exception_in_the_progress_callback_propagates(pair):
    def fail(stage, message):
        raise KeyError("stop at " + stage)

    with pytest.raises(KeyError, match="stop at cut"):
        liftmap.map(*pair, progress=fail)


def test_save_to_an_unwritable_folder_raises_read_error(sphere_map, tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    with pytest.raises(liftmap.ReadError, match=re.escape(str(blocker))):
        sphere_map.save(str(blocker))
