"""The GIL is released during long calls: two threads solve at the same time."""

import threading
import time

import numpy as np

import tribo


def gap(n):
    L, R = 1e-3, 0.01
    x = (np.arange(n) + 0.5) * L / n - L / 2
    X, Y = np.meshgrid(x, x)
    return (X**2 + Y**2) / (2 * R)


def test_two_threads_overlap_in_the_solver():
    # While one thread is inside the solver, the main thread keeps running Python: it counts
    # loop turns. With the GIL held for the whole solve, the counter could not advance while
    # the solve is running. Timing-free: the evidence is the interleaving itself.
    g = gap(192)
    inside = threading.Event()
    done = threading.Event()
    results = {}

    def solve(key):
        inside.set()
        results[key] = tribo.normal_contact(g, size=(1e-3, 1e-3), composite_modulus=1.15e11,
                                            load=100.0)
        done.set()

    t = threading.Thread(target=solve, args=("a",))
    t.start()
    inside.wait()
    turns = 0
    while not done.is_set():
        turns += 1
        time.sleep(0)
    t.join()
    # Thousands of turns in practice (the solve takes ~0.1 s); a held GIL gives at most a
    # few (the switch interval is 5 ms and the thread would hold the GIL throughout).
    assert turns > 50, turns

    # Two solves in two threads give the results of one each (no shared state).
    threads = [threading.Thread(target=solve, args=(k,)) for k in ("b", "c")]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    np.testing.assert_array_equal(results["b"].pressure, results["a"].pressure)
    np.testing.assert_array_equal(results["c"].pressure, results["a"].pressure)


def test_case_runs_in_threads():
    case = tribo.Case.example("sphere-on-flat")
    out = [None, None]

    def go(i):
        out[i] = tribo.run(case).summary["contact"]["max_pressure"]

    ts = [threading.Thread(target=go, args=(i,)) for i in range(2)]
    for t in ts:
        t.start()
    for t in ts:
        t.join()
    assert out[0] == out[1] and out[0] > 0
