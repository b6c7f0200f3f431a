"""Install layout: the top-level folder ``envs/`` installs as ``flexsim.envs`` and as nothing else, the tests run
against the installed package, and ``flexsim`` is a plain package.

``envs`` is a generic name already taken on the public package index, so the distribution claims only the
top-level import name ``flexsim``; ``pyproject.toml`` maps the folder onto ``flexsim.envs`` (for an editable install,
setuptools' own finder does). There is no import machinery in ``flexsim/__init__.py``: a source tree that is not
installed has no ``flexsim.envs``, so the tests import the installed package (tests/installed.py).
"""

from __future__ import annotations

import ast
import importlib.metadata
import json
import re
import subprocess
import sys
import tomllib
import urllib.parse
import zipfile
from pathlib import Path

import pytest

from tests.installed import ROOT, child_env


def _setuptools_config() -> dict:
    return tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["tool"]["setuptools"]


def _package_dir(name: str, mapping: dict[str, str]) -> Path:
    """Source folder of package ``name`` under setuptools' package-dir rules (longest mapped prefix)."""
    parts = name.split(".")
    for cut in range(len(parts), 0, -1):
        prefix = ".".join(parts[:cut])
        if prefix in mapping:
            return ROOT / mapping[prefix] / Path(*parts[cut:])
    return ROOT / Path(*parts)


def test_pyproject_lists_every_package_and_claims_only_flexsim():
    config = _setuptools_config()
    packages, mapping = config["packages"], config.get("package-dir", {})
    assert {name.split(".")[0] for name in packages} == {"flexsim"}
    assert mapping == {"flexsim.envs": "envs"}
    listed = {name: _package_dir(name, mapping) for name in packages}
    for name, folder in listed.items():
        # a code package has its __init__.py; a data folder (listed so that setuptools ships it without warning)
        # holds no Python source
        assert (folder / "__init__.py").is_file() or not list(folder.glob("*.py")), \
            f"pyproject package {name!r}: no {folder}/__init__.py"
    on_disk = {p.parent for top in ("flexsim", "envs") for p in (ROOT / top).rglob("__init__.py")}
    missing = sorted(str(p.relative_to(ROOT)) for p in on_disk - set(listed.values()))
    assert not missing, f"packages not listed in pyproject.toml [tool.setuptools] packages: {missing}"


def test_no_code_imports_top_level_envs():
    """A stray ``import envs`` would load the same files a second time as another module (two class identities)."""
    pattern = re.compile(r"^\s*(import envs\b|from envs\b)|[\"']envs[.:]", re.MULTILINE)
    offenders = []
    for top in ("flexsim", "envs", "tests", "examples", "benchmarks", "tools", "studies"):
        for path in (ROOT / top).rglob("*.py"):
            if pattern.search(path.read_text(encoding="utf-8")):
                offenders.append(str(path.relative_to(ROOT)))
    for path in [ROOT / "README.md", *(ROOT / "docs").glob("*.md")]:
        if pattern.search(path.read_text(encoding="utf-8")):
            offenders.append(str(path.relative_to(ROOT)))
    assert not offenders, f"use flexsim.envs, not the top-level name envs: {offenders}"


def _installed_source() -> tuple[Path, bool]:
    """(where the installed distribution's ``flexsim`` package lives, whether it is an editable install)."""
    # the first installed one on sys.path (pip records its files, RECORD); not a build's flexsim.egg-info in a checkout
    dist = next(d for d in importlib.metadata.distributions(name="flexsim") if d.read_text("RECORD") is not None)
    direct = dist.read_text("direct_url.json")
    info = json.loads(direct) if direct else {}
    if info.get("dir_info", {}).get("editable"):
        return Path(urllib.parse.unquote(urllib.parse.urlparse(info["url"]).path)).resolve() / "flexsim", True
    return Path(dist.locate_file("flexsim")).resolve(), False


def test_the_tests_run_against_the_installed_flexsim():
    """``python3 -m pytest`` from the checkout tests the installed package (tests/conftest.py), its ``flexsim.envs``
    from the top-level ``envs/`` as pyproject.toml installs it; an editable install must be this checkout's."""
    import flexsim
    import flexsim.envs

    package, editable = _installed_source()
    assert Path(flexsim.__file__).resolve() == package / "__init__.py", (
        f"the tests imported {flexsim.__file__}, not the installed flexsim ({package}): install this checkout "
        '(python3 -m pip install ".[test]", or -e for an editable install)')
    if editable:
        assert package == ROOT / "flexsim", f"the editable install is of another checkout, {package.parent}"
        assert Path(flexsim.envs.__file__).resolve() == ROOT / "envs" / "__init__.py"
    else:
        assert Path(flexsim.envs.__file__).resolve() == package / "envs" / "__init__.py"
        assert ROOT not in Path(flexsim.__file__).resolve().parents


def test_a_child_interpreter_imports_the_same_flexsim(tmp_path):
    """A child started in the checkout's root (its working directory first on sys.path without PYTHONSAFEPATH) with
    :func:`tests.installed.child_env` imports the flexsim and flexsim.envs the tests import."""
    import flexsim
    import flexsim.envs

    code = "import flexsim, flexsim.envs; print(flexsim.__file__); print(flexsim.envs.__file__)"
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, env=child_env(safe_path=True), capture_output=True, text=True,
                         check=True).stdout.splitlines()
    assert [Path(p).resolve() for p in out] == [Path(flexsim.__file__).resolve(), Path(flexsim.envs.__file__).resolve()]


#: Markers of the one block of flexsim/__init__.py that keeps the function ``fs.trim`` beside a subpackage of the
#: same name (it goes when the subpackage is renamed).
_CLASH = re.compile(r"^# >>> the name clash.*?^# <<< the name clash[^\n]*$", re.DOTALL | re.MULTILINE)


def test_the_package_holds_no_import_machinery():
    """``flexsim/__init__.py`` is a plain package: lazy names by module ``__getattr__`` (PEP 562), no meta-path finder,
    no import specs, no module-class swap (but for the marked block of the name clash, until the subpackage is renamed)."""
    source = _CLASH.sub("", (ROOT / "flexsim" / "__init__.py").read_text(encoding="utf-8"))
    tree = ast.parse(source)
    imported = {alias.name for node in ast.walk(tree) if isinstance(node, ast.Import) for alias in node.names}
    imported |= {node.module for node in ast.walk(tree) if isinstance(node, ast.ImportFrom) and node.module}
    assert not imported & {"importlib.abc", "importlib.util", "importlib.machinery", "sys", "types"}, imported
    for word in ("meta_path", "path_hooks", "spec_from_file_location", "__class__", "__path__"):
        assert word not in source, word


@pytest.mark.slow
def test_built_wheel_has_flexsim_envs_and_no_top_level_envs(tmp_path):
    """Build the wheel as ``pip install .`` would (isolated build, ~20 s) and list its top-level names."""
    subprocess.run([sys.executable, "-m", "pip", "wheel", str(ROOT), "--no-deps", "-q", "-w", str(tmp_path)],
                   check=True, capture_output=True, cwd=tmp_path)
    (wheel,) = tmp_path.glob("flexsim-*.whl")
    names = zipfile.ZipFile(wheel).namelist()
    assert {n.split("/")[0] for n in names if not n.split("/")[0].endswith(".dist-info")} == {"flexsim"}
    envs_files = {Path(n).name for n in names if n.startswith("flexsim/envs/")}
    assert envs_files == {p.name for p in (ROOT / "envs").glob("*.py")}
