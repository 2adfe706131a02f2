"""The GIL is released while C++ steps: a second Python thread progresses during a long run. It
notes the time as it spins; with the GIL held through the C++ part it could run only at the run's
edges (the Python code around it), never in the middle half of the run."""
import sys
import threading
import time

import nsbench


def test_a_second_thread_progresses_during_a_long_run():
    stamps = []
    stop = threading.Event()

    def spin():
        while not stop.is_set():
            stamps.append(time.perf_counter())

    thread = threading.Thread(target=spin)
    thread.start()
    try:
        time.sleep(0.05)  # the thread is running
        start = time.perf_counter()
        r = nsbench.run("bouncing-bar", "cd-lagrange", dt=1e-5, t_end=8.0, N=400, states=False, sample_every=1000)
        end = time.perf_counter()
    finally:
        stop.set()
        thread.join()
    assert r.status == "ok"
    elapsed = end - start
    # The middle half must span many of Python's thread switch intervals (5 ms) to tell. The run
    # took 0.73 s on a quiet core (t_end = 2 took 0.17 s there, under the 0.2 s this once asked).
    assert elapsed > 40 * sys.getswitchinterval(), "the run is too short to tell"
    middle = [s for s in stamps if start + 0.25 * elapsed < s < end - 0.25 * elapsed]
    assert len(middle) > 1000, f"the other thread made {len(middle)} steps in the middle half of a {elapsed:.2f} s run"
