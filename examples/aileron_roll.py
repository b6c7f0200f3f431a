"""Aileron roll of the notional GTM in level flight at 9144 m, M 0.75: aileron -3 deg (right
trailing edge up, rolls right) for 2 s, then neutral.

Run (headless; writes logs/aileron-roll-<time>.mcap unless --log is given):

    python examples/aileron_roll.py [--duration S] [--log PATH.mcap] [--aero unsteady|quasi-steady]
    flexsim view logs/aileron-roll-<time>.mcap          # look at it in Rerun

The same run: ``flexsim simulate aileron-roll``.
"""

import math
import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # before numpy: BLAS threads only slow the small dense algebra

from flexsim.cli.sim_commands import script_arguments  # noqa: E402
from flexsim.sim.manoeuvres import build_manoeuvre  # noqa: E402
from flexsim.sim.recording import default_log_path  # noqa: E402
from flexsim.sim.run_settings import OutputSettings


def main(argv=None) -> None:
    args = script_arguments(__doc__, argv)
    setup = build_manoeuvre("aileron-roll", aero=args.aero, duration_s=args.duration)
    print(f"{setup.name}: {setup.description}")
    result = setup.simulate(output=OutputSettings(log_path=args.log or default_log_path(setup.name)))
    print(result.summary())
    p = math.degrees(result.signal("omega_x_rad_s").max())
    print(f"peak roll rate {p:.2f} deg/s, bank angle at the end {math.degrees(result.signal('phi_rad')[-1]):.2f} deg")


if __name__ == "__main__":
    main()
