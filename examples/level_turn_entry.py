"""Turn entry of the notional GTM: from level flight at 9144 m, M 0.75, into a level turn of
radius 10 km (bank ~28 deg) with a bank-angle feedback on the aileron and the controls blended to the
turn trim.

Run (headless; writes logs/level-turn-entry-<time>.mcap unless --log is given):

    python examples/level_turn_entry.py [--duration S] [--log PATH.mcap] [--aero unsteady|quasi-steady]
    flexsim view logs/level-turn-entry-<time>.mcap          # look at it in Rerun

The same run: ``flexsim simulate level-turn-entry``.
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
    setup = build_manoeuvre("level-turn-entry", aero=args.aero, duration_s=args.duration)
    print(f"{setup.name}: {setup.description}")
    result = setup.simulate(output=OutputSettings(log_path=args.log or default_log_path(setup.name)))
    print(result.summary())
    k = result.t.size - 1
    print(f"bank angle {math.degrees(result.signal('phi_rad')[k]):.2f} deg (turn trim {setup.controls.turn.phi * 57.29578:.2f} deg), "
          f"heading change {math.degrees(result.signal('psi_rad')[k]):.2f} deg, load factor {result.load_factor[k]:.3f}")


if __name__ == "__main__":
    main()
