"""examples/python/map_pair.py runs and writes the CLI's files and B coloured by A."""

import os
import subprocess
import sys

from conftest import EXAMPLES, PATH_A, PATH_B, PATH_LANDMARKS


def test_map_pair_example(tmp_path):
    out = tmp_path / "out"
    run = subprocess.run([sys.executable, os.path.join(EXAMPLES, "python", "map_pair.py"), PATH_A, PATH_B,
                          PATH_LANDMARKS, str(out)], check=True, capture_output=True, text=True)
    assert run.stdout.startswith("distortion of f: mean ")
    assert (out / "report.json").exists()
    lines = (out / "B_coloured.off").read_text().splitlines()
    assert lines[0] == "COFF" and lines[1].split()[:2] == ["162", "320"]
