"""Install layout: the top-level folder ``envs/`` installs as ``flexsim.envs`` and as nothing else.

``envs`` is a generic name already taken on the public package index, so the distribution claims only the
top-level import name ``flexsim``. A source checkout that is not installed finds ``flexsim.envs``
through ``flexsim._SourceTreeEnvsFinder``; these tests check both routes lead to the checkout's ``envs/``.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
import tomllib
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


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
        assert (folder / "__init__.py").is_file(), f"pyproject package {name!r}: no {folder}/__init__.py"
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


def test_source_checkout_maps_flexsim_envs_onto_the_envs_folder(tmp_path):
    """Run as the helpers do: not installed, PYTHONPATH = checkout, from another directory."""
    code = ("import gymnasium as gym, flexsim, flexsim.envs, flexsim.envs.base as b; "
            "print(flexsim.__file__); print(flexsim.envs.__file__); print(b.__file__); "
            "print(sorted(k for k in gym.registry if k.startswith('FlexSim/')))")
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    out = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env=env, capture_output=True, text=True,
                         check=True).stdout.splitlines()
    assert Path(out[0]) == ROOT / "flexsim" / "__init__.py"
    assert Path(out[1]) == ROOT / "envs" / "__init__.py"
    assert Path(out[2]) == ROOT / "envs" / "base.py"
    assert out[3] == str(sorted(["FlexSim/GTM-LevelHold-v0", "FlexSim/GTM-LevelHold-v1", "FlexSim/GTM-Turn-v0", "FlexSim/GTM-GustAlleviation-v0",
                                 "FlexSim/GTM-FlutterMargin-v0", "FlexSim/GTM-FlutterMargin-v1"]))


def test_a_checkouts_flexsim_gets_its_own_envs_beside_another_checkouts_editable_install(tmp_path):
    """A finder that maps ``flexsim.envs`` to another folder (what the editable install of another checkout
    registers) does not pair that folder with this checkout's ``flexsim``."""
    checkout, other = tmp_path / "checkout", tmp_path / "other"
    (checkout / "flexsim").mkdir(parents=True)
    (checkout / "flexsim" / "__init__.py").write_text((ROOT / "flexsim" / "__init__.py").read_text(encoding="utf-8"))
    (checkout / "envs").mkdir()
    (checkout / "envs" / "__init__.py").write_text("WHERE = 'checkout'\n")
    (checkout / "pyproject.toml").write_text('[project]\nname = "flexsim"\n')
    (other / "envs").mkdir(parents=True)
    (other / "envs" / "__init__.py").write_text("WHERE = 'other'\n")
    code = ("import sys, importlib.abc, importlib.util\n"
            "class Editable(importlib.abc.MetaPathFinder):\n"
            "    def find_spec(self, name, path=None, target=None):\n"
            "        if name == 'flexsim.envs':\n"
            f"            return importlib.util.spec_from_file_location(name, {str(other / 'envs' / '__init__.py')!r}, "
            f"submodule_search_locations=[{str(other / 'envs')!r}])\n"
            "sys.meta_path.insert(0, Editable())\n"
            "import flexsim, flexsim.envs\n"
            "print(flexsim.envs.WHERE)\n")
    out = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env={**os.environ, "PYTHONPATH": str(checkout)},
                         capture_output=True, text=True, check=True).stdout.split()
    assert out == ["checkout"]


def test_installed_layout_is_not_touched_by_the_source_finder(tmp_path):
    """An installed flexsim (``flexsim/envs`` present) never gets the checkout finder."""
    fake = tmp_path / "site" / "flexsim"
    (fake / "envs").mkdir(parents=True)
    (fake / "__init__.py").write_text((ROOT / "flexsim" / "__init__.py").read_text(encoding="utf-8"))
    (fake / "envs" / "__init__.py").write_text("WHERE = 'installed'\n")
    code = ("import sys, flexsim, flexsim.envs; "
            "print(flexsim.envs.WHERE, any(type(f).__name__ == '_SourceTreeEnvsFinder' for f in sys.meta_path))")
    out = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env={**os.environ, "PYTHONPATH": str(fake.parent)},
                         capture_output=True, text=True, check=True).stdout.split()
    assert out == ["installed", "False"]


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
