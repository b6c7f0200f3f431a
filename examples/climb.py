"""Climb of the notional GTM: from level flight at 9144 m, M 0.75, the elevator and thrust ramp
to the 3 deg climb trim's values over 2 s and the aircraft is left to settle (open loop).

Run (headless; writes logs/climb-<time>.mcap unless --log is given):

    python examples/climb.py [--duration S] [--log PATH.mcap] [--aero unsteady|quasi-steady]
    flexsim view logs/climb-<time>.mcap          # look at it in Rerun

The same run: ``flexsim simulate climb``.
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # before numpy: BLAS threads only slow the small dense algebra

import numpy as np  # noqa: E402

from flexsim.cli.sim_commands import script_arguments  # noqa: E402
from flexsim.sim.manoeuvres import build_manoeuvre  # noqa: E402
from flexsim.sim.recording import default_log_path  # noqa: E402
from flexsim.sim.run_settings import OutputSettings


def main(argv=None) -> None:
    args = script_arguments(__doc__, argv)
    setup = build_manoeuvre("climb", aero=args.aero, duration_s=args.duration)
    print(f"{setup.name}: {setup.description}")
    result = setup.simulate(output=OutputSettings(log_path=args.log or default_log_path(setup.name)))
    print(result.summary())
    gamma = np.degrees(result.signal("theta_rad") - result.signal("alpha_rad"))
    print(f"altitude gained {result.altitude_m[-1] - result.altitude_m[0]:+.2f} m, "
          f"flight-path angle at the end {gamma[-1]:.2f} deg (approximate: wings level)")


if __name__ == "__main__":
    main()
