"""The GIL is released while C++ steps: a second Python thread progresses during a long run (with
the GIL held through the run, its counter would not move between the run's start and end)."""
import threading
import time

import nsbench


def test_a_second_thread_progresses_during_a_long_run():
    count = 0
    stop = threading.Event()

    def spin():
        nonlocal count
        while not stop.is_set():
            count += 1

    thread = threading.Thread(target=spin)
    thread.start()
    try:
        time.sleep(0.05)  # the thread is running
        before = count
        start = time.perf_counter()
        r = nsbench.run("bouncing-bar", "cd-lagrange", dt=1e-5, t_end=2.0, N=400, states=False, sample_every=1000)
        elapsed = time.perf_counter() - start
        during = count - before
    finally:
        stop.set()
        thread.join()
    assert r.status == "ok"
    assert elapsed > 0.2, "the run is too short to tell"
    assert during > 1000, f"the other thread counted {during} in a {elapsed:.2f} s run: the GIL was held"
