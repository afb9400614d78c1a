"""liftmap.batch (issue 30): on a dask.distributed LocalCluster with 2 workers and on threads of this process, the
same folders and summary as `liftmap batch`; resumed, only the failed pair is mapped again; a shard maps its pairs."""

import csv
import filecmp
import json
import os
import subprocess

import pytest

import liftmap
from conftest import CLI, PATH_A, PATH_B, PATH_LANDMARKS

BAD_LANDMARKS = os.path.join(os.path.dirname(__file__), "..", "data", "bad", "lm_duplicate_a.txt")
GOOD = ["sphere-ellipsoid", "path-tree"]


@pytest.fixture(scope="module")
def manifest(tmp_path_factory):
    """Three pairs: two that map (one with per-pair options), one with a bad landmark file."""
    folder = tmp_path_factory.mktemp("in")
    pairs = [l.split("#")[0].split() for l in open(PATH_LANDMARKS)]
    pairs = [p for p in pairs if p]
    (folder / "se.txt").write_text("".join(f"{a} {b}\n" for a, b in pairs))
    path = folder / "manifest.csv"
    path.write_text("name,mesh_a,mesh_b,landmarks,tree,max_iterations\n"
                    f"sphere-ellipsoid,{PATH_A},{PATH_B},se.txt,,\n"
                    f"path-tree,{PATH_A},{PATH_B},se.txt,path,2\n"
                    f"bad-landmarks,{PATH_A},{PATH_B},{os.path.abspath(BAD_LANDMARKS)},,\n")
    return path


@pytest.fixture(scope="module")
def cli_out(manifest, tmp_path_factory):
    """`liftmap batch`'s folder: two pairs at a time, one thread each."""
    out = tmp_path_factory.mktemp("cli") / "out"
    run = subprocess.run([CLI, "batch", str(manifest), "-o", str(out), "--jobs", "2", "--threads", "2", "-q"])
    assert run.returncode == 6  # the bad pair failed
    return out


def without_seconds(x):
    if isinstance(x, dict):
        return {k: without_seconds(v) for k, v in x.items() if k not in ("seconds", "run")}  # timings, policy
    return [without_seconds(v) for v in x] if isinstance(x, list) else x


def summary_rows(out):
    """summary.csv without its seconds column (wall times differ between runs)."""
    return [r[:3] + r[4:] for r in csv.reader(open(out / "summary.csv"))]


def assert_same_folders(out, expected):
    assert sorted(os.listdir(out)) == sorted(os.listdir(expected))
    for name in GOOD:
        files = sorted(os.listdir(expected / name))
        assert sorted(os.listdir(out / name)) == files
        match, mismatch, errors = filecmp.cmpfiles(out / name, expected / name,
                                                   [f for f in files if f != "report.json"], shallow=False)
        assert not mismatch and not errors, (name, mismatch, errors)
        reports = [json.load(open(d / name / "report.json")) for d in (out, expected)]
        assert without_seconds(reports[0]) == without_seconds(reports[1])
    assert summary_rows(out) == summary_rows(expected)


def check_counts(result, mapped, skipped):
    assert (result["pairs"], result["ok"], result["failed"], result["pending"]) == (3, 2, 1, 0)
    assert (result["mapped"], result["skipped"]) == (mapped, skipped)
    assert [f["name"] for f in result["failures"]] == ["bad-landmarks"]
    assert result["failures"][0]["exit_code"] == 4
    assert "lm_duplicate_a.txt:2: vertex 0 of mesh A is already a landmark" in result["failures"][0]["message"]


def test_dask_local_cluster_equals_cli(manifest, cli_out, tmp_path):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            result = liftmap.batch(manifest, tmp_path / "out", client, threads=1, progress=False)
    check_counts(result, mapped=3, skipped=0)
    assert_same_folders(tmp_path / "out", cli_out)


def test_threads_equal_cli_and_resume(manifest, cli_out, tmp_path, capsys):
    out = tmp_path / "out"
    check_counts(liftmap.batch(str(manifest), out, jobs=2, threads=2), mapped=3, skipped=0)
    assert_same_folders(out, cli_out)
    try:
        import tqdm  # noqa: F401  (its bar instead of the lines)
        assert "liftmap batch" in capsys.readouterr().err
    except ImportError:
        assert "liftmap: batch: [3/3]" in capsys.readouterr().err
    # Resumed: the complete pairs are skipped, the failed one is tried again.
    check_counts(liftmap.batch(manifest, out, jobs=2, threads=2, progress=False), mapped=1, skipped=2)
    assert_same_folders(out, cli_out)


def test_shard_maps_its_pairs(manifest, cli_out, tmp_path):
    out = tmp_path / "out"
    result = liftmap.batch(manifest, out, shard="1/2", threads=1, progress=False)  # path-tree
    assert (result["mapped"], result["ok"], result["pending"]) == (1, 1, 2)
    for name in ("path-tree",):
        assert sorted(os.listdir(out / name)) == sorted(os.listdir(cli_out / name))
        for f in os.listdir(cli_out / name):
            assert f == "report.json" or filecmp.cmp(out / name / f, cli_out / name / f, shallow=False), f
    assert [r[:2] for r in summary_rows(out)][1:] == [["sphere-ellipsoid", "pending"], ["path-tree", "ok"],
                                                      ["bad-landmarks", "pending"]]


def test_pictures_false_draws_none(manifest, cli_out, tmp_path):
    out = tmp_path / "out"
    result = liftmap.batch(manifest, out, shard="1/2", threads=1, progress=False, pictures=False)  # path-tree
    assert (result["mapped"], result["ok"]) == (1, 1)
    files = sorted(os.listdir(cli_out / "path-tree"))
    assert "render.png" in files and "distortion.png" in files
    assert sorted(os.listdir(out / "path-tree")) == [f for f in files if f not in ("render.png", "distortion.png")]


@pytest.mark.parametrize("keywords,error,message", [
    ({"max_iterations": -1}, liftmap.UsageError, r"max_iterations: value -1 not in range 0 to 10000"),
    ({"tolerance": float("nan")}, liftmap.UsageError, r"tolerance: value nan is not a finite number > 0"),
    ({"shard": "2/2"}, liftmap.UsageError, r"shard: '2/2' is not i/n"),
    ({"jobs": 0}, liftmap.UsageError, r"jobs: 0 is not an integer >= 1"),
    ({"colour": "red"}, TypeError, r"unexpected keyword argument 'colour'"),
    ({"pictures": "sometimes"}, liftmap.UsageError, r"pictures: "),
])
def test_bad_options_raise(manifest, tmp_path, keywords, error, message):
    with pytest.raises(error, match=message):
        liftmap.batch(manifest, tmp_path / "out", progress=False, **keywords)
    assert not (tmp_path / "out").exists()


def test_missing_manifest_raises_read_error(tmp_path):
    with pytest.raises(liftmap.ReadError, match="missing.csv: cannot open manifest"):
        liftmap.batch(tmp_path / "missing.csv", tmp_path / "out")
