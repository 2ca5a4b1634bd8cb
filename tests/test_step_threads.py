"""The pieces of a reproduction step on threads (crankgen.experiments.threads) and the one-thread
BLAS block the continuations hold while they run side by side."""

import threading

import pytest

from crankgen.analyses import blas as _blas
from crankgen.experiments.threads import Stopped, map_in_threads, stopping


def test_results_come_back_in_order_as_run_one_by_one():
    items = list(range(7))
    assert map_in_threads(lambda x: x * x, items, workers=2) == [x * x for x in items]
    assert map_in_threads(lambda x: x * x, items, workers=1) == [x * x for x in items]


def test_a_failing_piece_stops_the_others_at_their_next_log_line_and_its_error_goes_on():
    stop, started = threading.Event(), threading.Event()
    seen = {}

    def piece(k):
        if k == 0:
            assert started.wait(timeout=60), "piece 1 never started"
            raise ValueError("piece 0 failed")
        started.set()
        assert stop.wait(timeout=60), "the failure of piece 0 never set the stop event"
        try:
            stopping(stop)                  # what Context.log does before it writes a line
        except Stopped:
            seen["stopped"] = True
            raise
        seen["went on"] = True

    with pytest.raises(ValueError, match="piece 0 failed"):
        map_in_threads(piece, [0, 1], workers=2, stop=stop)
    assert seen == {"stopped": True}


def test_the_main_thread_is_never_stopped_by_the_event():
    stop = threading.Event()
    stop.set()
    stopping(stop)                          # no exception: the main thread logs on


def test_a_new_step_clears_the_stop_of_an_earlier_one():
    stop = threading.Event()
    stop.set()
    assert map_in_threads(lambda x: (stopping(stop), x)[1], [1, 2], workers=2, stop=stop) == [1, 2]


def test_one_blas_thread_while_any_block_is_open_in_any_thread():
    lib = _blas._lib()
    if not lib:
        pytest.skip("NumPy's OpenBLAS not found: single_thread does nothing here")
    getter, setter = lib
    before = getter()
    setter(2)
    try:
        a_in, b_in, a_out = threading.Event(), threading.Event(), threading.Event()
        counts = {}

        def a():
            with _blas.single_thread():
                a_in.set()
                b_in.wait(timeout=60)
            a_out.set()

        def b():
            a_in.wait(timeout=60)
            with _blas.single_thread():
                b_in.set()
                a_out.wait(timeout=60)
                counts["after the first block closed"] = getter()
            counts["after both closed"] = getter()

        threads = [threading.Thread(target=a), threading.Thread(target=b)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        assert counts == {"after the first block closed": 1, "after both closed": 2}
    finally:
        setter(before)

