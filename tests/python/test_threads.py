"""Maps in two Python threads at once equal the same maps made one after the other, and a call leaves the
interpreter's thread settings as they were."""

import ctypes
import os
import sys
import threading

import numpy as np

import liftmap


def snapshot_of(m):
    return m.a_to_b.faces, m.a_to_b.barycentric, m.b_to_a.faces, m.b_to_a.barycentric


def test_two_threads_equal_sequential(pair):
    jobs = [dict(tree="mst", max_iterations=3), dict(tree="path", max_iterations=2)]
    sequential = [snapshot_of(liftmap.map(*pair, threads=1, **kw)) for kw in jobs]
    start = threading.Barrier(2)

    def run(i, results):
        start.wait()
        results[i] = snapshot_of(liftmap.map(*pair, threads=1, **jobs[i]))

    # Several rounds: a race between the two (Debian's serial OpenBLAS has none of its own locks) shows in some.
    for _ in range(3):
        results = [None, None]
        threads = [threading.Thread(target=run, args=(i, results)) for i in range(2)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        for got, expected in zip(results, sequential):
            assert got is not None
            for g, e in zip(got, expected):
                np.testing.assert_array_equal(g, e)


def omp_settings():
    """OpenMP's settings of the calling thread and of the process, from the libgomp the module loaded."""
    gomp = ctypes.CDLL("libgomp.so.1")
    return gomp.omp_get_max_threads(), gomp.omp_get_max_active_levels(), gomp.omp_get_dynamic()


def test_thread_settings_untouched(pair):
    before = (dict(os.environ), sys.getswitchinterval(), threading.active_count(), os.sched_getaffinity(0),
              omp_settings())
    liftmap.map(*pair, threads=1, max_iterations=1)
    liftmap.map(*pair, threads=3, max_iterations=1)
    after = (dict(os.environ), sys.getswitchinterval(), threading.active_count(), os.sched_getaffinity(0),
             omp_settings())
    assert after == before
