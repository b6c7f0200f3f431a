"""flexsim: flexible aircraft in manoeuvring flight.

Implements the whole-aircraft flexible multibody model of Tuzcu & Nguyen, *Flutter of Maneuvering
Aircraft*, J. Aerosp. Eng. 28(4), 2015 (accepted manuscript 2014), built on Meirovitch & Tuzcu's unified
formulation (Lagrange's equations in quasi-coordinates).

Conventions (SI units and radians inside the library, body axes x forward / y right / z down) are in
``docs/conventions.md``.

The top-level API, one import for a script::

    import flexsim as fs

    model = fs.AircraftModel(fs.load_aircraft("gtm"), aero="unsteady")
    level = fs.trim(model, fs.SteadyManoeuvre.level(9144.0, mach=0.75))
    point = fs.flutter(model, fs.SteadyManoeuvre.level(0.0, mach=0.6))

The names below are loaded on first use (module ``__getattr__``, PEP 562), so ``import flexsim`` stays cheap and
a command pays only for what it uses; ``import flexsim.envs`` registers the gymnasium environments.
"""

from __future__ import annotations

import importlib.abc
import importlib.util
import sys
import types
from pathlib import Path

__version__ = "0.1.0"

#: Public name -> module that defines it (loaded on first attribute access).
_API: dict[str, str] = {
    "load_aircraft": "flexsim.aircraft.toml_loader",
    "Aircraft": "flexsim.aircraft.definition",
    "AircraftModel": "flexsim.model.aircraft_model",
    "AeroOptions": "flexsim.model.coupling",
    "SteadyManoeuvre": "flexsim.trim",
    "TrimPoint": "flexsim.trim",
    "TrimError": "flexsim.trim",
    "EquilibriumStability": "flexsim.trim",
    "trim": "flexsim.trim",
    "LinearModel": "flexsim.linear.linearize",
    "linearize": "flexsim.linear.linearize",
    "Mode": "flexsim.linear.stability",
    "Spectrum": "flexsim.linear.stability",
    "spectrum": "flexsim.linear.stability",
    "flutter": "flexsim.linear.flutter",
    "FlutterAnalysis": "flexsim.linear.flutter",
    "FlutterPoint": "flexsim.linear.flutter",
    "FlutterNotFound": "flexsim.linear.flutter",
    "wind_tunnel": "flexsim.linear.flutter",
    "nonlinear_wing_tunnel": "flexsim.linear.beam_flutter",
    "WindTunnelResult": "flexsim.linear.flutter",
    "SearchRange": "flexsim.linear.envelope",
    "search_range": "flexsim.linear.envelope",
    "vg_diagram": "flexsim.linear.vg",
    "VgDiagram": "flexsim.linear.vg",
    "VgTrack": "flexsim.linear.vg",
    "linear_system": "flexsim.linear.control",
    "LinearSystem": "flexsim.linear.control",
    "state_space": "flexsim.linear.control",
    "record_flutter_mode": "flexsim.linear.mode_animation",
    "simulate": "flexsim.sim.simulate",
    "SimulationResult": "flexsim.sim.result",
    "OneMinusCosineGust": "flexsim.sim.disturbances",
    "DrydenTurbulence": "flexsim.sim.disturbances",
}

__all__ = ["__version__", *_API]
#: Public functions named like a subpackage (kept by :class:`_Package`).
_SHADOWED = frozenset({"trim"})


def __getattr__(name: str):
    """The public API of :data:`_API`, imported when first asked for (PEP 562)."""
    module = _API.get(name)
    if module is None:
        raise AttributeError(f"module 'flexsim' has no attribute {name!r}")
    import importlib

    value = getattr(importlib.import_module(module), name)
    if name not in _SHADOWED:
        globals()[name] = value  # later look-ups do not come here
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_API))


class _SubpackageShadowed:
    """A public function named like a subpackage (``flexsim.trim``, the function, and ``flexsim.trim``, the package).

    Importing a subpackage binds it as an attribute of its parent; a data descriptor on the package's module type
    takes precedence over that binding, so ``flexsim.trim`` stays the function whatever was imported before, and
    ``from flexsim.trim import TrimPoint`` still finds the subpackage (in ``sys.modules``).
    """

    def __init__(self, name: str) -> None:
        self.name = name

    def __get__(self, package, owner=None):
        return self if package is None else __getattr__(self.name)

    def __set__(self, package, value) -> None:
        if not isinstance(value, types.ModuleType):
            raise AttributeError(f"flexsim.{self.name} is the public function; it cannot be replaced")


class _Package(types.ModuleType):
    """The module type of ``flexsim``: see :class:`_SubpackageShadowed`."""

    trim = _SubpackageShadowed("trim")


sys.modules[__name__].__class__ = _Package


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
    """Put :class:`_SourceTreeEnvsFinder` first on ``sys.meta_path`` when this ``flexsim`` is a source checkout.

    First, so that the checkout's own ``envs/`` wins over a finder that maps ``flexsim.envs`` elsewhere (the
    editable install of another checkout, whose ``envs`` would otherwise be paired with this checkout's
    ``flexsim``); for an installed flexsim it is not registered and finds nothing.
    """
    if _checkout_envs_dir(Path(__file__).resolve().parent) is None:
        return
    if not any(isinstance(finder, _SourceTreeEnvsFinder) for finder in sys.meta_path):
        sys.meta_path.insert(0, _SourceTreeEnvsFinder())


_source_tree_envs()
