"""Cost of classifying a trim's equilibrium (``TrimPoint.stability``) on the bundled GTM.

Side by side in one run, CPU medians of this thread (time.thread_time) over --repeats calls:

* ``trim(classify=False)`` and ``trim()`` (the default classifies: linearisation, eig, root classification and the
  static margin), cold and from a neighbouring trim, with their ratio, for the quasi-steady model (60 states) and
  the finite-state one (252 states: the inflow states are in its linearisation);
* what a flutter search adds per evaluation: :func:`flexsim.trimming.equilibrium.with_stability` on the spectrum the
  search computes anyway (the static margin and the verdict), beside one ``FlutterAnalysis.evaluate`` (QS and US)
  without it.

Run: python benchmarks/bench_trim_classification.py [--repeats 15]
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

from flexsim.aircraft.toml_loader import load_aircraft  # noqa: E402
from flexsim.linear.flutter import FlutterAnalysis  # noqa: E402
from flexsim.trimming import SteadyManoeuvre, trim  # noqa: E402
from flexsim.trimming.equilibrium import with_stability  # noqa: E402


def _cpu_median(fn, repeats: int) -> float:
    fn()  # warm-up
    times = []
    for _ in range(repeats):
        t0 = time.thread_time()
        fn()
        times.append(time.thread_time() - t0)
    return statistics.median(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeats", type=int, default=15)
    args = parser.parse_args()
    analysis = FlutterAnalysis(load_aircraft("gtm"), "theodorsen")
    model = analysis.qs
    man = SteadyManoeuvre.level(9144.0, mach=0.78)
    neighbour = trim(model, SteadyManoeuvre.level(9144.0, mach=0.77), check_limits=False, classify=False)
    rows = []
    for name, trim_model in (("QS", model), ("FS", analysis.fs)):
        for label, kw in (("cold", {}), ("from a neighbour", {"guess": neighbour})):
            bare = _cpu_median(lambda: trim(trim_model, man, check_limits=False, classify=False, **kw), args.repeats)
            full = _cpu_median(lambda: trim(trim_model, man, check_limits=False, **kw), args.repeats)
            rows.append((f"{name} trim {label}", bare, full))
    print(f"GTM, 9144 m, M 0.78; CPU medians of {args.repeats} calls [ms]")
    print(f"  {'':<24} {'classify=False':>14} {'classify=True':>14} {'extra':>8} {'ratio':>6}")
    for label, bare, full in rows:
        print(f"  {label:<24} {1e3 * bare:14.2f} {1e3 * full:14.2f} {1e3 * (full - bare):8.2f} {full / bare:6.2f}")
    point = trim(model, man, check_limits=False, classify=False)
    print("flutter search, per evaluation (trim + eigen-analysis; the classification reuses its roots):")
    for name in ("quasi-steady", "theodorsen"):
        _, spec = analysis.evaluate(man, neighbour, aero_model=name)
        t_eval = _cpu_median(lambda: analysis.evaluate(man, neighbour, aero_model=name), args.repeats)
        t_cls = _cpu_median(lambda: with_stability(model, point, spec), args.repeats)
        print(f"  {name:<14} evaluate {1e3 * t_eval:8.2f} ms, of which with_stability {1e3 * t_cls:6.3f} ms "
              f"({100 * t_cls / t_eval:.1f} %)")


if __name__ == "__main__":
    main()
