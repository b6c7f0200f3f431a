"""Gust encounter of the notional GTM in level flight at 9144 m, M 0.75: a 1-cos up-gust,
U_ds = 10 m/s, gradient length 60 m (CS-25.341), reached by the body origin at t = 1 s.

Run (headless; writes logs/gust-encounter-<time>.mcap unless --log is given):

    python examples/gust_encounter.py [--duration S] [--log PATH.mcap] [--aero unsteady|quasi-steady]
    flexsim view logs/gust-encounter-<time>.mcap          # look at it in Rerun

The same run: ``flexsim simulate gust-encounter``.
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # before numpy: BLAS threads only slow the small dense algebra

from flexsim.cli.sim_commands import script_arguments  # noqa: E402
from flexsim.sim.manoeuvres import build_manoeuvre  # noqa: E402
from flexsim.sim.recording import default_log_path  # noqa: E402
from flexsim.sim.run_settings import OutputSettings


def main(argv=None) -> None:
    args = script_arguments(__doc__, argv)
    setup = build_manoeuvre("gust-encounter", aero=args.aero, duration_s=args.duration)
    print(f"{setup.name}: {setup.description}")
    result = setup.simulate(output=OutputSettings(log_path=args.log or default_log_path(setup.name)))
    print(result.summary())
    n = result.load_factor
    root = result.root_bending_moment_n_m()
    print(f"peak load factor {n.max():.3f} at t = {result.t[n.argmax()]:.3f} s, "
          f"right-wing root bending moment {root.min() / 1e6:.3f} .. {root.max() / 1e6:.3f} MN m")


if __name__ == "__main__":
    main()
