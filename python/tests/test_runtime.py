"""How the binding behaves around the computation: results handed over
without a copy, the GIL released while the library computes, Ctrl-C
cancelling a long call, and the scene reusable afterwards."""

import _thread
import signal
import threading
import time

import numpy as np

import softshadow


def floor_points(n, seed=1):
    rng = np.random.default_rng(seed)
    return np.column_stack([rng.uniform(-2.5, 2.5, n), np.full(n, 1e-3), rng.uniform(-2.5, 2.5, n)])


def test_results_are_moved_into_numpy_without_a_copy():
    scene = softshadow.Scene.builtin("default")
    v = scene.visibility(floor_points(100))
    # The array views the library's own buffer (rust-numpy's container),
    # not a copy numpy owns.
    assert not v.flags.owndata and type(v.base).__name__ == "PySliceContainer"
    assert v.flags.c_contiguous and v.flags.writeable
    g = scene.gbuffer(16, 12)
    for key in ["position", "normal", "object", "exact"]:
        a = g[key]
        assert not a.flags.owndata and a.flags.c_contiguous, key
        # A reshaped view of the moved buffer.
        assert type(a.base.base if isinstance(a.base, np.ndarray) else a.base).__name__ == "PySliceContainer"


def test_float32_input_is_widened_exactly():
    scene = softshadow.Scene.builtin("default")
    p = floor_points(300).astype(np.float32)
    assert np.array_equal(scene.visibility(p), scene.visibility(p.astype(np.float64)))


def misaligned(a):
    """A copy of `a` at an odd address (as dask.distributed deserialises
    arrays): C-contiguous but not aligned."""
    buf = np.zeros(a.nbytes + 1, np.uint8)
    out = np.frombuffer(buf[1:].data, dtype=a.dtype).reshape(a.shape)
    out[...] = a
    assert not out.flags.aligned and out.flags.c_contiguous
    return out


def test_misaligned_arrays_are_read_right():
    scene = softshadow.Scene.builtin("default")
    p = floor_points(500)
    n = np.tile([0.0, 1.0, 0.0], (500, 1))
    o = np.zeros(500, np.int64)
    want = scene.visibility(p, n, o, method="single-sample")
    got = scene.visibility(misaligned(p), misaligned(n), misaligned(o), method="single-sample")
    assert np.array_equal(got, want)


def long_receivers(scene):
    """The depth-complexity scene's camera receivers, repeated: about
    250 000 receivers at about 0.3 ms each for the exact reference, over a
    minute on two cores."""
    g = scene.gbuffer(64, 48)
    p = g["position"][g["object"] >= 0]
    return np.ascontiguousarray(np.tile(p, (100, 1)))


def test_the_gil_is_released_while_the_library_computes():
    """Another Python thread runs all through a call of half a second or
    more: the longest pause between its loop's turns is a small part of the
    call (with the GIL held through the call, one pause would be the whole
    call). The call is lengthened, doubling its receivers, until it lasts
    half a second on this machine, so that a fast machine cannot make it
    too short to tell."""
    scene = softshadow.Scene.builtin("depth-complexity")
    every = long_receivers(scene)
    n = 8000
    while True:
        p = np.ascontiguousarray(every[:n])
        span = []

        def call():
            t = time.perf_counter()
            scene.visibility(p)
            span.append(time.perf_counter() - t)

        worker = threading.Thread(target=call)
        last = time.perf_counter()
        worker.start()
        gap = 0.0
        while worker.is_alive():
            now = time.perf_counter()
            gap = max(gap, now - last)
            last = now
        worker.join()
        print(f"{n} receivers: call {span[0]:.2f} s, longest pause of the other thread {gap * 1e3:.1f} ms")
        if span[0] > 0.5 or n >= len(every):
            break
        n = min(2 * n, len(every))
    assert span[0] > 0.5, "the call is too short to tell, even with every receiver"
    assert gap < 0.25 * span[0]


def test_ctrl_c_cancels_a_long_call_and_the_scene_computes_again():
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    scene = softshadow.Scene.builtin("depth-complexity")
    p = long_receivers(scene)
    fired = []
    timer = threading.Timer(0.5, lambda: (fired.append(time.perf_counter()), _thread.interrupt_main(signal.SIGINT)))
    timer.start()
    start = time.perf_counter()
    returned = False
    try:
        scene.visibility(p)
        returned = True  # a broken cancel: the signal is raised only here
        time.sleep(1)
    except KeyboardInterrupt:
        pass
    end = time.perf_counter()
    timer.join()
    assert fired and not returned, "the call ran to its end before the interrupt was raised"
    latency = end - fired[0]
    print(f"KeyboardInterrupt {latency:.3f} s after the signal ({end - start:.2f} s into the call)")
    # The whole call would take a minute or more; cancelled, it stops
    # within a chunk of 256 receivers (a fraction of a second here).
    assert latency < 5.0
    # Nothing is left cancelled: the same scene computes again, and right.
    q = floor_points(200, seed=2)
    assert np.array_equal(scene.visibility(q), softshadow.Scene.builtin("depth-complexity").visibility(q))
