"""Landmarks anywhere on the surfaces from Python: read_surface_landmarks and map() with a dict of face points."""

import warnings

import numpy as np
import pytest

import liftmap
from conftest import PATH_LANDMARKS, THREADS


def points(V, F, faces, barycentric):
    return np.einsum("ik,ikj->ij", barycentric, V[F[faces]])


def corner_face_points(F, vertices):
    """Each vertex as a face point: a corner of its first face in F, coordinate 1 there."""
    faces, barycentric = [], []
    for v in vertices:
        f, k = np.argwhere(F == v)[0]
        b = np.zeros(3)
        b[k] = 1
        faces.append(f)
        barycentric.append(b)
    return np.array(faces), np.array(barycentric)


def face_landmarks(pair):
    """Six landmarks inside faces next to the example's vertex landmarks: (0.6, 0.25, 0.15) of a face around each."""
    VA, FA, VB, FB, landmarks = pair
    d = {}
    for side, F, column in (("A", FA, 0), ("B", FB, 1)):
        faces = np.array([np.argwhere((F == v).any(axis=1))[0][0] for v in landmarks[:, column]])
        d["faces_" + side] = faces
        d["barycentric_" + side] = np.tile([0.6, 0.25, 0.15], (len(faces), 1))
    return d


def test_read_surface_landmarks_reads_every_token_form(pair, tmp_path):
    VA, FA, VB, FB, landmarks = pair
    d = liftmap.read_surface_landmarks(PATH_LANDMARKS, VA, FA, VB, FB)
    assert sorted(d) == ["barycentric_A", "barycentric_B", "faces_A", "faces_B"]
    assert d["faces_A"].dtype == np.int32 and d["barycentric_A"].shape == (len(landmarks), 3)
    np.testing.assert_array_equal(points(VA, FA, d["faces_A"], d["barycentric_A"]), VA[landmarks[:, 0]])
    np.testing.assert_array_equal(points(VB, FB, d["faces_B"], d["barycentric_B"]), VB[landmarks[:, 1]])
    # A face point, a 3D point (B's vertex 5 itself) and a vertex on one file.
    x = VB[5]
    path = tmp_path / "lm.txt"
    path.write_text(f"f10:0.2,0.3,0.5 {x[0]!r},{x[1]!r},{x[2]!r}\n7 f20:0.5,0.25,0.25\n")
    d = liftmap.read_surface_landmarks(str(path), VA, FA, VB, FB)
    assert d["faces_A"].tolist()[0] == 10 and d["barycentric_A"][0].tolist() == [0.2, 0.3, 0.5]
    np.testing.assert_allclose(points(VB, FB, d["faces_B"][:1], d["barycentric_B"][:1])[0], x, atol=1e-15)
    np.testing.assert_array_equal(points(VA, FA, d["faces_A"][1:], d["barycentric_A"][1:])[0], VA[7])
    with pytest.raises(liftmap.InvalidInputError, match=r"lm.txt:1: face 10000 is out of range for mesh A"):
        path.write_text("f10000:0.2,0.3,0.5 1\n2 3\n")
        liftmap.read_surface_landmarks(str(path), VA, FA, VB, FB)


def test_vertex_landmarks_as_face_points_give_the_same_map(sphere_map, pair):
    VA, FA, VB, FB, landmarks = pair
    fa, ba = corner_face_points(FA, landmarks[:, 0])
    fb, bb = corner_face_points(FB, landmarks[:, 1])
    d = {"faces_A": fa, "barycentric_A": ba, "faces_B": fb, "barycentric_B": bb}
    m = liftmap.map(VA, FA, VB, FB, d, threads=THREADS)
    np.testing.assert_array_equal(m.a_to_b.faces, sphere_map.a_to_b.faces)
    np.testing.assert_array_equal(m.a_to_b.barycentric, sphere_map.a_to_b.barycentric)


def test_face_point_landmarks_are_interpolated(pair):
    VA, FA, VB, FB, _ = pair
    d = face_landmarks(pair)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no landmark is near a side: no warning
        m = liftmap.map(VA, FA, VB, FB, d, threads=THREADS, max_iterations=2)
    assert m.verified
    for source, target in (("A", "B"), ("B", "A")):
        V, F = (VB, FB) if target == "B" else (VA, FA)
        f, b = m.evaluate(d["faces_" + source], d["barycentric_" + source], source=source)
        expected = points(V, F, d["faces_" + target], d["barycentric_" + target])
        assert np.abs(points(V, F, f, b) - expected).max() < 1e-9, source
    assert len(m.cut["A"]["landmarks"]) == len(d["faces_A"])


def test_face_point_near_a_side_is_moved_with_a_warning(pair):
    VA, FA, VB, FB, _ = pair
    d = face_landmarks(pair)
    d["barycentric_B"][2] = [0.5995, 0.4, 0.0005]
    with pytest.warns(UserWarning, match=r"landmarks: row 2: the landmark on mesh B is within 0.001"):
        m = liftmap.map(VA, FA, VB, FB, d, threads=THREADS, max_iterations=0)
    assert m.verified


@pytest.mark.parametrize("change,message", [
    (lambda d: d.pop("faces_B"), r"landmarks: the dict has no 'faces_B'"),
    (lambda d: d.update(faces_C=d["faces_A"]), r"landmarks: unknown key 'faces_C'"),
    (lambda d: d["faces_B"].__setitem__(0, 10 ** 6), r"landmarks\['faces_B'\]: row 0: face 1000000 is out of range"),
    (lambda d: d["barycentric_A"].__setitem__(3, [0.5, 0.5, 0.5]),
     r"landmarks: row 3: barycentric coordinates sum to 1.5, not 1 \(mesh A\)"),
    (lambda d: d["barycentric_B"].__setitem__(1, [0.7, 0.3 + 1e-6, -1e-6]),
     r"landmarks: row 1: barycentric coordinate -1e-06 is negative: the point is outside face \d+ \(mesh B\)"),
    (lambda d: d["barycentric_B"].__setitem__(4, [np.nan, 0.5, 0.5]),
     r"landmarks: row 4: barycentric coordinate nan is not finite \(mesh B\)"),
    (lambda d: d.update(faces_A=d["faces_A"][:5], barycentric_A=d["barycentric_A"][:5]),
     r"landmarks: 5 landmarks on mesh A but 6 on mesh B"),
    (lambda d: d.update(faces_A=d["faces_A"].astype(float)), r"landmarks\['faces_A'\]: expected a 1-D int32 or int64"),
    (lambda d: d["faces_A"].__setitem__(1, d["faces_A"][0]),
     r"landmarks: row 1: the landmark f\d+:0.6,0.25,0.15 of mesh A is at the same point as the one of row 0"),
])
def test_bad_face_point_landmarks_name_the_row(pair, change, message):
    VA, FA, VB, FB, _ = pair
    d = face_landmarks(pair)
    change(d)
    with pytest.raises(liftmap.InvalidInputError, match=message):
        liftmap.map(VA, FA, VB, FB, d, threads=THREADS)


def test_face_points_take_a_landmark_files_tolerance(pair, tmp_path):
    """A coordinate of -5e-10 (within a landmark file's 1e-9) is accepted from a dict as from a file, and gives the
    same map: one rule for both."""
    VA, FA, VB, FB, _ = pair
    d = face_landmarks(pair)
    d["barycentric_A"][0] = [0.6, 0.4 + 5e-10, -5e-10]
    lines = []
    for i in range(len(d["faces_A"])):
        tokens = [f"f{d['faces_' + s][i]}:" + ",".join(repr(float(x)) for x in d["barycentric_" + s][i]) for s in "AB"]
        lines.append(" ".join(tokens))
    path = tmp_path / "landmarks.txt"
    path.write_text("\n".join(lines) + "\n")
    from_file = liftmap.read_surface_landmarks(str(path), VA, FA, VB, FB)
    with warnings.catch_warnings(record=True):
        warnings.simplefilter("always")
        a = liftmap.map(VA, FA, VB, FB, d, threads=THREADS, max_iterations=0)
        b = liftmap.map(VA, FA, VB, FB, from_file, threads=THREADS, max_iterations=0)
    assert a.verified and b.verified
    np.testing.assert_array_equal(a.a_to_b.faces, b.a_to_b.faces)
    np.testing.assert_array_equal(a.a_to_b.barycentric, b.a_to_b.barycentric)


def test_face_points_on_a_mesh_with_bad_faces_are_an_error_not_a_crash(pair):
    VA, FA, VB, FB, _ = pair
    d = face_landmarks(pair)
    bad = FA.copy()
    bad[d["faces_A"][0], 1] = 10 ** 6
    with pytest.raises(liftmap.InvalidInputError, match=r"FA: face \d+ has vertex index 1000000, out of range"):
        liftmap.map(VA, bad, VB, FB, d, threads=THREADS)


def test_face_points_keep_the_given_corner_order_with_fix_orientation(pair):
    VA, FA, VB, FB, _ = pair
    d = face_landmarks(pair)
    inside_out = FA[:, [0, 2, 1]]
    with pytest.warns(UserWarning, match="mesh A is inside-out"):
        m = liftmap.map(VA, inside_out, VB, FB, d, threads=THREADS, max_iterations=0, fix_orientation=True)
    f, b = m.evaluate(d["faces_B"], d["barycentric_B"], source="B")
    expected = points(VA, inside_out, d["faces_A"], d["barycentric_A"])
    assert np.abs(points(VA, inside_out, f, b) - expected).max() < 1e-9


def test_read_surface_landmarks_on_bad_faces_is_an_error_not_a_crash(pair):
    VA, FA, VB, FB, _ = pair
    bad = FB.copy()
    bad[7, 2] = -3
    with pytest.raises(liftmap.InvalidInputError, match=r"FB: face 7 has vertex index -3, out of range"):
        liftmap.read_surface_landmarks(PATH_LANDMARKS, VA, FA, VB, bad)
