"""read_mesh, read_landmarks and check against the CLI's `liftmap check --json`."""

import json
import subprocess

import numpy as np

import liftmap
from conftest import CLI, PATH_A, PATH_B, PATH_LANDMARKS


def test_read_mesh_shapes(pair):
    VA, FA = pair[0], pair[1]
    assert VA.shape == (812, 3) and VA.dtype == np.float64
    assert FA.shape == (1620, 3) and FA.dtype == np.int32


def test_read_landmarks(pair):
    assert pair[4].tolist() == [[286, 117], [276, 138], [294, 0], [314, 11], [304, 70], [280, 46]]


def test_check_equals_cli_check_json(pair):
    cli = json.loads(subprocess.run([CLI, "check", PATH_A, PATH_B, "--json"], check=True, capture_output=True,
                                    text=True).stdout)
    assert liftmap.check(pair[0], pair[1], name=PATH_A) == cli["meshes"][0]
    assert liftmap.check(pair[2], pair[3], name=PATH_B) == cli["meshes"][1]


def test_help_documents_every_argument():
    doc = liftmap.map.__doc__
    for word in ["VA", "FA", "VB", "FB", "landmarks", "(#VA, 3)", "(k, 2)", "p:", "h:", "normalize", "tolerance",
                 "max_iterations", "start_relaxation", "solver", "tree", "samples", "threads", "fix_orientation", "progress",
                 "InvalidInputError", "PipelineError"]:
        assert word in doc, word
    for f in (liftmap.read_mesh, liftmap.read_landmarks, liftmap.read_surface_landmarks, liftmap.check,
              liftmap.Map.evaluate, liftmap.Map.transfer,
              liftmap.Map.save):
        assert f.__doc__ and "Raises" in f.__doc__
