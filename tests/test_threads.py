"""The library limits BLAS to one thread in-process (flexsim/_threads.py), whatever the environment says."""

import numpy as np
from threadpoolctl import threadpool_info, threadpool_limits

from flexsim._threads import single_blas_thread
from flexsim.linear.flutter import FlutterAnalysis, wind_tunnel
from flexsim.linear.stability import spectrum
from flexsim.model.jacobian import jacobian
from flexsim.sim.simulate import simulate
from flexsim.trimming import trim


def _blas_threads() -> set[int]:
    return {lib["num_threads"] for lib in threadpool_info() if lib["user_api"] == "blas"}


def test_single_blas_thread_inside_and_restored_after():
    seen = []

    @single_blas_thread
    def work():
        seen.append(_blas_threads())
        np.linalg.solve(np.eye(30) * 2.0, np.ones(30))
        return inner()

    @single_blas_thread
    def inner():  # nested: passes through, still one thread
        seen.append(_blas_threads())
        return 1

    with threadpool_limits(2, user_api="blas"):
        before = _blas_threads()
        assert work() == 1
        assert _blas_threads() == before
    assert seen == [{1}, {1}]


def test_public_entry_points_are_limited():
    for fn in (trim, spectrum, jacobian, simulate, wind_tunnel, FlutterAnalysis.search, FlutterAnalysis.evaluate):
        assert hasattr(fn, "__wrapped__"), fn.__qualname__
