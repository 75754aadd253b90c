"""Tracing releases the GIL: two Python threads trace at once, and their
answers are those of one thread alone. No timing is asserted: the evidence is
that one thread completes traces while the other is inside its own."""
import threading

import numpy as np

import passtrace
from conftest import NO_HIT


def test_two_threads_trace_at_once(scene, random_rays):
    accel = passtrace.build(scene, "bvh8", threads=1)
    origins, directions = random_rays
    # A long trace: the random rays many times over (about a second).
    many_o, many_d = np.tile(origins, (300, 1)), np.tile(directions, (300, 1))
    small_o, small_d = origins[:64], directions[:64]
    expected_small = accel.intersect(small_o, small_d)
    long_running, long_done = threading.Event(), threading.Event()
    result = {}

    def long_trace():
        long_running.set()
        result["long"] = accel.intersect(many_o, many_d)
        long_done.set()

    thread = threading.Thread(target=long_trace)
    thread.start()
    long_running.wait()
    # Traces in this thread while the other is inside intersect(): with the
    # GIL held by that call, none could complete before it returns.
    completed = 0
    while not long_done.is_set():
        got = accel.intersect(small_o, small_d)
        np.testing.assert_array_equal(got["id"], expected_small["id"])
        completed += 1
    thread.join()
    assert completed >= 10, f"only {completed} traces completed beside the long one: the GIL was held"
    alone = accel.intersect(origins, directions)
    np.testing.assert_array_equal(result["long"]["id"].reshape(300, -1), np.tile(alone["id"], (300, 1)))
    assert (alone["id"] != NO_HIT).any()


def test_gpu_structures_serve_several_threads(scene, random_rays):
    """GPU work runs on the module's GL thread, one job at a time: calls from
    several Python threads all get their own answers."""
    accel = passtrace.build(scene, "kd-restart", "gpu")
    origins, directions = random_rays
    expected = accel.intersect(origins, directions)["id"]
    answers = [None] * 4

    def trace(k):
        answers[k] = accel.intersect(origins[k::4], directions[k::4])["id"]

    threads = [threading.Thread(target=trace, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for k in range(4):
        np.testing.assert_array_equal(answers[k], expected[k::4])
