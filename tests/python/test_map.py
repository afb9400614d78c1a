"""liftmap.map on sphere-ellipsoid: the same map and files as `liftmap map`, and the Map's arrays."""

import filecmp
import json
import os
import subprocess

import numpy as np
import pytest

import liftmap
from conftest import CLI, PATH_A, PATH_B, PATH_LANDMARKS, THREADS


def read_map_file(path):
    """(faces, barycentric) of a map file: 'face b0 b1 b2' per line, '#' comments."""
    rows = [line.split() for line in open(path) if line.strip() and not line.startswith("#")]
    return np.array([int(r[0]) for r in rows]), np.array([[float(x) for x in r[1:]] for r in rows])


def without_seconds(report):
    """The report without its wall times and how the process ran ("run": the CLI's OpenMP wait policy), which
    differ between runs and decide no result."""
    if isinstance(report, dict):
        return {k: without_seconds(v) for k, v in report.items() if k not in ("seconds", "run")}
    if isinstance(report, list):
        return [without_seconds(v) for v in report]
    return report


@pytest.fixture(scope="module")
def cli_out(tmp_path_factory):
    out = tmp_path_factory.mktemp("cli")
    subprocess.run([CLI, "map", PATH_A, PATH_B, "-l", PATH_LANDMARKS, "-o", str(out), "--threads", str(THREADS),
                    "--quiet"], check=True)
    return out


@pytest.mark.parametrize("name,attribute", [("A_to_B.txt", "a_to_b"), ("B_to_A.txt", "b_to_a"),
                                            ("cut_A_to_B.txt", "cut_a_to_b"), ("cut_B_to_A.txt", "cut_b_to_a")])
def test_maps_equal_the_cli_files(sphere_map, cli_out, name, attribute):
    faces, bary = read_map_file(cli_out / name)
    m = getattr(sphere_map, attribute)
    assert m.faces.shape == faces.shape and m.barycentric.shape == (len(faces), 3)
    np.testing.assert_array_equal(m.faces, faces)
    np.testing.assert_allclose(m.barycentric, bary, rtol=0, atol=1e-15)


def test_report_equals_report_json(sphere_map, cli_out):
    cli_report = json.load(open(cli_out / "report.json"))
    assert without_seconds(sphere_map.report) == without_seconds(cli_report)
    assert sphere_map.verified and sphere_map.report["verification"]["passed"]


def test_save_writes_the_cli_files(sphere_map, cli_out, tmp_path):
    sphere_map.save(str(tmp_path))
    names = sorted(os.listdir(cli_out))
    assert sorted(os.listdir(tmp_path)) == names
    different = [n for n in names if n != "report.json" and not filecmp.cmp(cli_out / n, tmp_path / n, shallow=False)]
    assert different == []
    assert without_seconds(json.load(open(tmp_path / "report.json"))) == without_seconds(sphere_map.report)


def test_save_without_pictures_writes_every_other_file(sphere_map, cli_out, tmp_path):
    (tmp_path / "render.png").write_bytes(b"a previous run's picture")
    sphere_map.save(str(tmp_path), pictures=False)
    names = sorted(n for n in os.listdir(cli_out) if n not in ("render.png", "distortion.png"))
    assert sorted(os.listdir(tmp_path)) == names
    different = [n for n in names if n != "report.json" and not filecmp.cmp(cli_out / n, tmp_path / n, shallow=False)]
    assert different == []


def test_points_lie_on_the_target(sphere_map, pair):
    VA, FA, VB, FB, landmarks = pair
    points = sphere_map.a_to_b.points()
    corners = VB[FB[sphere_map.a_to_b.faces]]
    np.testing.assert_allclose(points, np.einsum("ik,ikj->ij", sphere_map.a_to_b.barycentric, corners), atol=1e-14)
    np.testing.assert_allclose(points[landmarks[:, 0]], VB[landmarks[:, 1]], atol=1e-12)


def test_evaluate_round_trip(sphere_map, pair):
    VA = pair[0]
    f, b = sphere_map.evaluate(sphere_map.a_to_b.faces, sphere_map.a_to_b.barycentric, source="B")
    VAf = pair[1]
    back = np.einsum("ik,ikj->ij", b, VA[VAf[f]])
    assert np.abs(back - VA).max() < 1e-9 * np.sqrt(4 * np.pi)


def test_transfer_any_width(sphere_map, pair):
    VA, FA, VB, FB, _ = pair
    assert sphere_map.transfer(VA[:, 0]).shape == (len(VB),)
    colours = np.asfortranarray(np.random.default_rng(1).random((len(VA), 5)).astype(np.float32))
    on_b = sphere_map.transfer(colours)
    assert on_b.shape == (len(VB), 5) and on_b.dtype == np.float64
    # Transferring A's positions gives B's vertices' images on A.
    np.testing.assert_allclose(sphere_map.transfer(VA), sphere_map.b_to_a.points(), atol=1e-14)
    assert sphere_map.transfer(np.ones(len(VB)), source="B").shape == (len(VA),)


def test_overlay_tiles_both_meshes_and_matches_overlay_obj(sphere_map, pair, cli_out):
    VA, FA, VB, FB, _ = pair
    o = sphere_map.overlay
    n, m = len(o["V_A"]), len(o["F"])
    assert o["V_B"].shape == (n, 3) and o["F"].shape == (m, 3) and m > len(FA) + len(FB)
    # Every vertex is its points on A and on B.
    for side, V, F in (("A", VA, FA), ("B", VB, FB)):
        points = np.einsum("ik,ikj->ij", o["barycentric_" + side], V[F[o["faces_" + side]]])
        np.testing.assert_allclose(points, o["V_" + side], atol=1e-14)
        # The triangles tile the mesh: per input face, their areas sum to its area.
        T = o["V_" + side][o["F"]]
        area = 0.5 * np.linalg.norm(np.cross(T[:, 1] - T[:, 0], T[:, 2] - T[:, 0]), axis=1)
        per_face = np.bincount(o["face_" + side], weights=area, minlength=len(F))
        C = V[F]
        face_area = 0.5 * np.linalg.norm(np.cross(C[:, 1] - C[:, 0], C[:, 2] - C[:, 0]), axis=1)
        np.testing.assert_allclose(per_face, face_area, rtol=1e-9, atol=1e-15)
    # The same mesh as the CLI's overlay.obj.
    rows = [line.split() for line in open(cli_out / "overlay.obj") if line[:2] in ("v ", "f ")]
    V = np.array([[float(x) for x in r[1:]] for r in rows if r[0] == "v"])
    F = np.array([[int(x) - 1 for x in r[1:]] for r in rows if r[0] == "f"])
    np.testing.assert_array_equal(V, o["V_A"])
    np.testing.assert_array_equal(F, o["F"])


def test_no_overlay(pair):
    m = liftmap.map(*pair, overlay=False, threads=THREADS)
    assert len(m.overlay["F"]) == 0 and "overlay" not in m.report


def test_cut_and_flattenings(sphere_map):
    cut = sphere_map.cut
    k = len(cut["tree"]) + 1
    for side, uv in (("A", sphere_map.flattening_a), ("B", sphere_map.flattening_b)):
        c = cut[side]
        assert c["uv"].shape == uv.shape == (len(c["V_cut"]), 2)
        assert c["F_cut"].shape == c["F"].shape and len(c["face_to_input"]) == len(c["F"])
        np.testing.assert_array_equal(c["V_cut"], c["V"][c["cut_to_refined"]])
        assert len(c["paths"]) == k - 1 and len(c["landmarks"]) == k
    assert cut["boundary_map"].shape[1] == 2


def test_array_layouts_give_the_same_map(sphere_map, pair):
    VA, FA, VB, FB, landmarks = pair
    m = liftmap.map(np.asfortranarray(VA), FA.astype(np.int64), VB[::-1][::-1], np.asfortranarray(FB, np.int64),
                    landmarks.astype(np.int64), threads=THREADS)
    np.testing.assert_array_equal(m.a_to_b.faces, sphere_map.a_to_b.faces)
    np.testing.assert_array_equal(m.b_to_a.barycentric, sphere_map.b_to_a.barycentric)


def test_float32_vertices(pair):
    VA, FA, VB, FB, landmarks = pair
    m = liftmap.map(VA.astype(np.float32), FA, VB.astype(np.float32), FB, landmarks, max_iterations=1)
    assert m.verified and m.a_to_b.barycentric.dtype == np.float64


def test_progress_reports_every_stage(pair):
    stages = []
    liftmap.map(*pair, max_iterations=1, progress=lambda stage, message: stages.append(stage))
    assert {"cut", "flatten", "lift", "verify"} <= set(stages)


def test_fix_orientation_keeps_the_given_vertex_order(sphere_map, pair):
    VA, FA, VB, FB, landmarks = pair
    inside_out = FA[:, [0, 2, 1]]
    with pytest.raises(liftmap.InvalidInputError, match="mesh A: cannot be mapped: the faces are oriented inward"):
        liftmap.map(VA, inside_out, VB, FB, landmarks, threads=THREADS)
    with pytest.warns(UserWarning, match="mesh A is inside-out"):
        m = liftmap.map(VA, inside_out, VB, FB, landmarks, threads=THREADS, fix_orientation=True)
    assert m.report["input"]["A"]["faces_reversed"] and not m.report["input"]["B"]["faces_reversed"]
    np.testing.assert_array_equal(m.a_to_b.barycentric, sphere_map.a_to_b.barycentric)
    np.testing.assert_array_equal(m.b_to_a.faces, sphere_map.b_to_a.faces)
    np.testing.assert_array_equal(m.b_to_a.barycentric, sphere_map.b_to_a.barycentric[:, [0, 2, 1]])
    np.testing.assert_allclose(m.b_to_a.points(), sphere_map.b_to_a.points(), atol=1e-15)
