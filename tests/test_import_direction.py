"""The package import graph is one-way (docs/design.md, "Software design").

Every ``import`` in ``flexsim/`` and ``envs/`` — module level and function-local, parsed with ``ast`` — may only
go to the importing package itself or to a package of a lower layer::

    errors, _arrays, _threads, threads  <  _kernels  <  atmosphere, kinematics, io  <  aircraft  <  structure  <  aero  <  model
        <  trimming  <  linear  <  sim  <  cli, envs

``io`` (file formats: the flight log, depending on ``errors`` only) is a leaf library that ``sim`` writes its logs
with. ``aero`` is 2-D/strip aerodynamics and may not import ``structure`` although it sits above it: the
strip–structure coupling lives in ``flexsim.model``. A reverse import (say ``flexsim.aero`` importing ``flexsim.structure``) fails the test with the file, line
and the two layers named. The checker itself is tested on a synthetic reverse import, so the test can fail.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

#: Layer of every package (top-level modules of flexsim count as packages); lower may not import higher.
LAYERS: dict[str, int] = {
    "errors": 0, "_arrays": 0, "_threads": 0, "threads": 0, "_immutable": 0, "_numba_cache": 0,
    "_kernels": 1,
    "atmosphere": 2, "kinematics": 2, "io": 2,
    "aircraft": 3,
    "structure": 4,
    "aero": 5,
    "model": 6,
    "trimming": 7,
    "linear": 8,
    "sim": 9,
    "cli": 10, "envs": 10,
}
#: Downward imports that are still not allowed, with the reason.
FORBIDDEN: dict[tuple[str, str], str] = {
    ("aero", "structure"): "the strip-structure coupling lives in flexsim.model (aero is pure 2-D/strip aerodynamics)",
}


def _package(module: str) -> str | None:
    """The layer name of a dotted module path (``flexsim.aero.vlm`` -> ``aero``, ``envs.base`` -> ``envs``)."""
    parts = module.split(".")
    if parts[0] == "envs":
        return "envs"
    if parts[0] == "flexsim" and len(parts) > 1:
        return parts[1]
    return None


def _imports(source: str, module: str) -> list[tuple[int, str]]:
    """(line, imported module) of every absolute or relative import in ``source``."""
    out = []
    package_parts = module.split(".")[:-1]
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            out += [(node.lineno, alias.name) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package_parts[: len(package_parts) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            out.append((node.lineno, target))
    return out


def reverse_imports(files: dict[str, str]) -> list[str]:
    """Violations in ``{dotted module name: source}``: one line per import of a higher or unknown layer."""
    problems = []
    for module, source in sorted(files.items()):
        src = _package(module)
        if src is None or module in ("flexsim", "envs"):
            continue
        for line, target in _imports(source, module):
            dst = _package(target)
            if dst is None or dst == src:
                continue
            if src not in LAYERS or dst not in LAYERS:
                problems.append(f"{module}:{line} imports {target}: package {src if src not in LAYERS else dst!r} has no layer in LAYERS")
            elif (src, dst) in FORBIDDEN:
                problems.append(f"{module}:{line} imports {target}: {src} may not import {dst}: {FORBIDDEN[src, dst]}")
            elif LAYERS[dst] >= LAYERS[src]:
                problems.append(f"{module}:{line} imports {target}: layer {src} ({LAYERS[src]}) may not import {dst} ({LAYERS[dst]})")
    return problems


def _sources() -> dict[str, str]:
    files = {}
    for top in ("flexsim", "envs"):
        for path in sorted((ROOT / top).rglob("*.py")):
            parts = path.relative_to(ROOT).with_suffix("").parts
            module = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
            files[module] = path.read_text(encoding="utf-8")
    return files


def test_package_imports_go_one_way_down_the_layers():
    files = _sources()
    assert len(files) > 50  # the whole tree was read
    assert reverse_imports(files) == []


@pytest.mark.parametrize(("module", "source", "expected"), [
    ("flexsim.aero.strips", "from flexsim.structure.model import StructuralModel\n", "aero may not import structure: the strip-structure"),
    ("flexsim.model.coupling", "from flexsim.sim.outputs import OutputMaps\n", "layer model (6) may not import sim (9)"),
    ("flexsim.aircraft.definition", "def f():\n    from flexsim.structure import shapes\n", "flexsim.aircraft.definition:2"),
    ("flexsim.sim.outputs", "from ..cli import main\n", "imports flexsim.cli: layer sim (9) may not import cli (10)"),
    ("flexsim.trimming.solver", "import flexsim.linear.flutter\n", "layer trimming (7) may not import linear (8)"),
    ("flexsim.newpkg.thing", "import flexsim.model\n", "'newpkg' has no layer"),
])
def test_checker_reports_reverse_imports(module, source, expected):
    problems = reverse_imports({module: source})
    assert len(problems) == 1 and expected in problems[0]


def test_checker_accepts_downward_and_internal_imports():
    ok = {"flexsim.model.strips": "from flexsim.aero.lift_slopes import strip_lift_slopes\nfrom flexsim.model import layout\n"
                                  "from . import coupling\nimport numpy as np\n"}
    assert reverse_imports(ok) == []
