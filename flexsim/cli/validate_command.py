"""`flexsim validate [CASE ...] [--json]`: verification cases against published values (flexsim.sim.validation)."""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

__all__ = ["add_validate_command"]


def _validate(args: argparse.Namespace) -> int:
    from flexsim.sim.validation import builtin_cases, load_case, run_case

    builtin = builtin_cases()
    cases = []
    for name in args.cases or list(builtin):
        if name in builtin:
            cases.append(builtin[name])
        elif Path(name).suffix == ".toml" or Path(name).is_file():
            if not Path(name).is_file():
                raise FileNotFoundError(f"case {name!r}: no such case file")
            cases.append(load_case(name))
        else:
            raise ValueError(f"case {name!r}: neither a built-in case ({', '.join(builtin)}) nor a case file (.toml)")
    start, cpu = time.perf_counter(), time.process_time()
    results = []
    for case in cases:
        res = run_case(case)
        results.append(res)
        if not args.json:
            _print(res)
    total, total_cpu = time.perf_counter() - start, time.process_time() - cpu
    ok = all(r.passed for r in results)
    if args.json:
        print(json.dumps({"passed": ok, "seconds": total, "cpu_seconds": total_cpu, "cases": [
            {"case": r.name, "description": r.description, "passed": r.passed, "seconds": r.seconds,
             "cpu_seconds": r.cpu_seconds, "error": r.error,
             "checks": [c.as_dict() for c in r.checks]} for r in results]}, indent=2))
    else:
        n_ok = sum(r.passed for r in results)
        print(f"\n{n_ok}/{len(results)} cases passed in {total:.1f} s ({total_cpu:.1f} s CPU)")
    return 0 if ok else 1


def _print(res) -> None:
    if res.error:
        print(f"{res.name:<34} FAIL  {res.error}")
        return
    for c in res.checks:
        err = f"{c.error:+.2e}" if c.absolute else f"{100 * c.error:+.3f} %"
        tol = f"{c.tolerance:.0e}" if c.absolute else f"{100 * c.tolerance:g} %"
        print(f"{res.name:<34} {c.quantity:<38} ref {c.reference:>11.5g} {c.unit:<5} flexsim {c.value:>11.5g}  "
              f"error {err:>10}  tol {tol:>6}  {'pass' if c.passed else 'FAIL'}")


def add_validate_command(sub: argparse._SubParsersAction) -> None:
    """Register ``validate`` on the CLI's subparsers."""
    p = sub.add_parser("validate", help="run the verification cases against published values and closed forms")
    p.add_argument("cases", nargs="*", metavar="CASE",
                   help="built-in case names or case files (.toml: aircraft file + reference values) [all built-in]")
    p.add_argument("--json", action="store_true", help="print machine-readable JSON")
    p.set_defaults(func=_validate)
