"""Fixtures of the Python module's tests: the sphere-ellipsoid example (README, "Examples") and its map.

ctest sets PYTHONPATH to the module's folder and LIFTMAP_CLI, LIFTMAP_DATA_DIR, LIFTMAP_EXAMPLES
(tests/python/CMakeLists.txt)."""

import os

import pytest

import liftmap

DATA = os.environ.get("LIFTMAP_DATA_DIR", "data/meshes")
EXAMPLES = os.environ.get("LIFTMAP_EXAMPLES", "examples")
CLI = os.environ.get("LIFTMAP_CLI", "build/app/liftmap")

PATH_A = os.path.join(DATA, "larger_sphere.off")
PATH_B = os.path.join(DATA, "ellipsoid.off")
PATH_LANDMARKS = os.path.join(EXAMPLES, "sphere-ellipsoid", "landmarks.txt")
# The CLI's default is every hardware thread; both sides run with the same count so that sums agree bit for bit.
THREADS = 2


@pytest.fixture(scope="session")
def pair():
    """(VA, FA, VB, FB, landmarks) of sphere-ellipsoid, as read by the module."""
    VA, FA = liftmap.read_mesh(PATH_A)
    VB, FB = liftmap.read_mesh(PATH_B)
    landmarks = liftmap.read_landmarks(PATH_LANDMARKS, len(VA), len(VB))
    return VA, FA, VB, FB, landmarks


@pytest.fixture(scope="session")
def sphere_map(pair):
    """The map of sphere-ellipsoid with the CLI's defaults, named as the CLI names its inputs."""
    return liftmap.map(*pair, threads=THREADS, name_a=PATH_A, name_b=PATH_B)
