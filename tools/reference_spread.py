"""Spread of the reference tests' values across CPU targets: the numbers behind their tolerances.

The reference tests (``tests/model/test_reference_values.py``, ``tests/model/test_rhs_reference.py``,
``tests/envs/test_env_reference.py``) compare against values recorded on one machine. Another machine runs other
machine code: numba compiles for its CPU (``NUMBA_CPU_NAME``), and OpenBLAS picks kernels for its core type
(``OPENBLAS_CORETYPE``), which sum in another order. This script runs the reference cases once per target, each in
a fresh interpreter (numba's cache of another CPU name in its own ``NUMBA_CACHE_DIR``), and prints each test's
largest difference from its recorded data, and, for the environments, the largest spread between the targets.

Run (from the repository root; the first run of each numba target compiles for 1-2 CPU-minutes)::

    python tools/reference_spread.py [--cores Haswell Zen Sandybridge SkylakeX Prescott] [--out DIR]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]


def measure(out: Path) -> None:
    """The differences of this interpreter's target, written to ``out``.json and its observations to ``out``.npz."""
    sys.path.insert(0, str(ROOT))
    sys.path.insert(0, str(ROOT / "tests" / "envs" / "data"))
    from record_env_reference import CASES, run_case

    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.model.aircraft_model import AircraftModel
    from flexsim.sim.disturbances import OneMinusCosineGust
    from tests.model import reference_cases as cases
    from tests.model.test_rhs_reference import _cases

    def rel(a, b):
        a, b = np.asarray(a, float), np.asarray(b, float)
        return float(np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300))

    gtm = load_aircraft("gtm")
    data = json.loads((ROOT / "tests/model/data/reference_values.json").read_text())
    res: dict = {}
    new = cases.rhs_values(gtm, data["rhs_inputs"])
    res["rhs"] = max(rel(new[n][w][s], o) for n, by in data["rhs"].items() for w, rows in by.items() for s, o in enumerate(rows))
    lay = AircraftModel(gtm, aero="quasi-steady").layout
    parts = {"x": (lay.position, lay.euler, lay.q, lay.xi, lay.velocity), "u": (slice(0, 1), slice(1, 4))}
    trims = cases.trim_values(gtm)
    res["trim"] = max(rel(np.asarray(trims[n][k])[p], np.asarray(o[k])[p]) for n, o in data["trims"].items()
                      for k, ps in parts.items() for p in ps)
    fl = cases.flutter_values(gtm)
    res["flutter"] = max(abs(fl[n][k] - o[k]) / abs(o[k]) for n, o in data["flutter"].items() for k in ("mach", "frequency_rad_s"))
    ref = np.load(ROOT / "tests/model/data/rhs_reference.npz")
    gust = OneMinusCosineGust(5.0, 25.0, front_position_ned_m=[-8.0, 0.0, 0.0])
    whole = accel = 0.0
    for name, model in _cases().items():
        vs = model.layout.velocity
        for s in range(ref[f"{name}_x"].shape[0]):
            old = ref[f"{name}_dx"][s]
            x_dot = model.rhs(0.0, ref[f"{name}_x"][s], ref[f"{name}_u"][s], gust if s == 3 else None)
            whole, accel = max(whole, rel(x_dot, old)), max(accel, rel(x_dot[vs], old[vs]))
    res["rhs_dense_whole"], res["rhs_dense_accel"] = whole, accel
    env_ref = np.load(ROOT / "tests/envs/data/env_reference.npz")
    observations, res["env"] = {}, {}
    for name, env_id, num_envs, kwargs in CASES:
        obs, reward = run_case(env_id, num_envs, kwargs)
        ro, rr = env_ref[f"{name}/obs"], env_ref[f"{name}/reward"]
        scale = np.abs(ro).reshape(-1, ro.shape[-1]).max(axis=0).astype(float)
        d = np.abs(obs.astype(float) - ro.astype(float))
        res["env"][name] = {"obs_of_scale": float((d / np.where(scale > 0, scale, 1.0)).max()),
                            "reward_rel": float(np.max(np.abs(reward - rr) / np.maximum(np.abs(rr), 1e-300)))}
        observations[f"{name}/obs"] = obs
    np.savez(out.with_suffix(".npz"), **observations)
    out.with_suffix(".json").write_text(json.dumps(res, indent=1))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cores", nargs="+", default=["Haswell", "Zen", "Sandybridge", "SkylakeX", "Prescott"],
                        help="OpenBLAS core types (OPENBLAS_CORETYPE) besides the machine's own")
    parser.add_argument("--out", type=Path, default=None, help="folder for the per-target results [a temporary one]")
    parser.add_argument("--measure", type=Path, help=argparse.SUPPRESS)  # one target, in this interpreter
    args = parser.parse_args()
    if args.measure:
        measure(args.measure)
        return
    out = args.out or Path(tempfile.mkdtemp(prefix="reference-spread-"))
    out.mkdir(parents=True, exist_ok=True)
    generic_cache = out / "numba-generic-cache"
    targets = {"native": {}, "numba-generic": {"NUMBA_CPU_NAME": "generic", "NUMBA_CACHE_DIR": str(generic_cache)}}
    targets.update({f"blas-{c}": {"OPENBLAS_CORETYPE": c} for c in args.cores})
    for name, env in targets.items():
        print(f"measuring {name} ...", file=sys.stderr, flush=True)
        subprocess.run([sys.executable, __file__, "--measure", str(out / name)], check=True, cwd=ROOT,
                       env={**os.environ, "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", **env})
    res = {n: json.loads((out / f"{n}.json").read_text()) for n in targets}
    print(f"{'largest difference from the recorded data':<44}" + "".join(f"{n[-12:]:>13}" for n in targets))
    for key in ("rhs", "trim", "flutter", "rhs_dense_whole", "rhs_dense_accel"):
        print(f"{key:<44}" + "".join(f"{res[n][key]:13.2e}" for n in targets))
    obs = {n: np.load(out / f"{n}.npz") for n in targets}
    ref = np.load(ROOT / "tests/envs/data/env_reference.npz")
    for case in res["native"]["env"]:
        y = ref[f"{case}/obs"].astype(float)
        scale = np.abs(y).reshape(-1, y.shape[-1]).max(axis=0)
        stack = np.stack([obs[n][f"{case}/obs"].astype(float) for n in targets])
        spread = float(((stack.max(0) - stack.min(0)) / np.where(scale > 0, scale, 1.0)).max())
        print(f"{case[-44:]:<44}" + "".join(f"{res[n]['env'][case]['obs_of_scale']:13.2e}" for n in targets)
              + f"   spread {spread:.2e}, reward {max(res[n]['env'][case]['reward_rel'] for n in targets):.1e}")


if __name__ == "__main__":
    main()
