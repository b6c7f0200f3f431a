"""flexsim: flexible aircraft in manoeuvring flight.

Implements the whole-aircraft flexible multibody model of Tuzcu & Nguyen, *Flutter of Maneuvering
Aircraft*, J. Aerosp. Eng. 28(4), 2015 (accepted manuscript 2014), built on Meirovitch & Tuzcu's unified
formulation (Lagrange's equations in quasi-coordinates).

Conventions (SI units and radians inside the library, body axes x forward / y right / z down) are in
``docs/conventions.md``.
"""

from __future__ import annotations

import importlib.abc
import importlib.util
import sys
from pathlib import Path

__version__ = "0.1.0"


def _checkout_envs_dir(package_dir: Path) -> Path | None:
    """``<checkout>/envs`` when ``package_dir`` is the ``flexsim/`` folder of a source checkout, else None.

    A checkout is recognised by ``envs/__init__.py`` and a ``pyproject.toml`` naming the project ``flexsim`` beside
    ``flexsim/``, which itself has no ``envs`` subpackage; an installed flexsim (``site-packages/flexsim/envs``)
    never matches.
    """
    root = package_dir.parent
    if (package_dir / "envs").exists() or not (root / "envs" / "__init__.py").is_file():
        return None
    pyproject = root / "pyproject.toml"
    if not pyproject.is_file() or 'name = "flexsim"' not in pyproject.read_text(encoding="utf-8"):
        return None
    return root / "envs"


class _SourceTreeEnvsFinder(importlib.abc.MetaPathFinder):
    """Find ``flexsim.envs`` in the top-level ``envs/`` folder of a source checkout (and nothing else).

    An installed flexsim carries the environments as the subpackage ``flexsim/envs`` (``pyproject.toml`` maps
    the folder ``envs/`` onto ``flexsim.envs``). A source checkout run without installing (``PYTHONPATH`` set to the
    checkout, or ``python3 -m pytest`` from its root, which puts the root on ``sys.path`` ahead of any installed
    copy) has ``flexsim/`` without an ``envs`` subfolder; this finder then maps exactly the one name
    ``flexsim.envs`` onto ``<checkout>/envs`` of the checkout whose ``flexsim`` is imported (looked up at import
    time, so it can never pair one checkout's ``flexsim`` with another's ``envs``). Submodules
    (``flexsim.envs.base`` ...) are then found through the package's ``__path__`` as usual.
    """

    def find_spec(self, fullname, path=None, target=None):  # noqa: D102 (importlib protocol)
        if fullname != "flexsim.envs":
            return None
        package = sys.modules.get("flexsim")
        envs_dir = _checkout_envs_dir(Path(package.__file__).resolve().parent) if package is not None else None
        if envs_dir is None:
            return None
        return importlib.util.spec_from_file_location(
            fullname, envs_dir / "__init__.py", submodule_search_locations=[str(envs_dir)])


def _source_tree_envs() -> None:
    """Append :class:`_SourceTreeEnvsFinder` to ``sys.meta_path`` when this ``flexsim`` is a source checkout.

    Appended last, so a regular finder that knows ``flexsim.envs`` (an installed or editable flexsim) wins.
    """
    if _checkout_envs_dir(Path(__file__).resolve().parent) is None:
        return
    if not any(isinstance(finder, _SourceTreeEnvsFinder) for finder in sys.meta_path):
        sys.meta_path.append(_SourceTreeEnvsFinder())


_source_tree_envs()
