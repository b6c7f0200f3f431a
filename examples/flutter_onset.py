"""Flutter onset of the Goland wing clamped in a sea-level wind tunnel at 1.05 times its
flutter speed: released undeformed under gravity, its bending-torsion oscillation grows until the
structural-limit event (|tip deflection| = 0.25 x span) stops the run.

Run (headless; writes logs/flutter-onset-<time>.mcap unless --log is given):

    python examples/flutter_onset.py [--duration S] [--log PATH.mcap] [--aero unsteady|quasi-steady]
    flexsim view logs/flutter-onset-<time>.mcap          # look at it in Rerun

The same run: ``flexsim simulate flutter-onset``.
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # before numpy: BLAS threads only slow the small dense algebra

from flexsim.cli.sim_commands import script_arguments  # noqa: E402
from flexsim.sim.manoeuvres import build_manoeuvre  # noqa: E402
from flexsim.sim.recording import default_log_path  # noqa: E402
from flexsim.sim.run_settings import OutputSettings


def main(argv=None) -> None:
    args = script_arguments(__doc__, argv)
    setup = build_manoeuvre("flutter-onset", aero=args.aero, duration_s=args.duration)
    print(f"{setup.name}: {setup.description}")
    result = setup.simulate(output=OutputSettings(log_path=args.log or default_log_path(setup.name)))
    print(result.summary())
    print(f"flutter speed {setup.metadata['flutter_speed_m_s']} m/s, tunnel speed {setup.metadata['tunnel_speed_m_s']} m/s; "
          f"stopped at t = {result.t[-1]:.3f} s ({result.status})")


if __name__ == "__main__":
    main()
