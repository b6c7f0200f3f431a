"""Elevator doublet of the notional GTM in level flight at 9144 m, M 0.75: +2 deg then -2 deg,
0.5 s each; shows the short-period response and the wing bending it drives.

Run (headless; writes logs/elevator-doublet-<time>.mcap unless --log is given):

    python examples/elevator_doublet.py [--duration S] [--log PATH.mcap] [--aero unsteady|quasi-steady]
    flexsim view logs/elevator-doublet-<time>.mcap          # look at it in Rerun

The same run: ``flexsim simulate elevator-doublet``.
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # before numpy: BLAS threads only slow the small dense algebra

from flexsim.cli.sim_commands import script_arguments  # noqa: E402
from flexsim.sim.manoeuvres import build_manoeuvre  # noqa: E402
from flexsim.sim.recording import default_log_path  # noqa: E402
from flexsim.sim.run_settings import OutputSettings


def main(argv=None) -> None:
    args = script_arguments(__doc__, argv)
    setup = build_manoeuvre("elevator-doublet", aero=args.aero, duration_s=args.duration)
    print(f"{setup.name}: {setup.description}")
    result = setup.simulate(output=OutputSettings(log_path=args.log or default_log_path(setup.name)))
    print(result.summary())
    n = result.load_factor
    tip = result.tip_deflection_m()
    print(f"load factor {n.min():.3f} .. {n.max():.3f}, right-wing tip deflection {tip.min():+.3f} .. {tip.max():+.3f} m")


if __name__ == "__main__":
    main()
