"""The flexsim the tests run against, and the environment of a child interpreter that runs the same.

The tests run against the installed package, as the README installs it (``python3 -m pip install ".[test]" &&
python3 -m pytest``, or an editable install, ``pip install -e``): ``tests/conftest.py`` takes the checkout's root off
``sys.path`` before flexsim is first imported, so that ``python3 -m pytest`` from the root does not import the source
tree's ``flexsim/`` (which has no ``flexsim.envs``: the top-level folder ``envs/`` installs as that subpackage,
``pyproject.toml``). A child interpreter (a docs block, an example, a script) gets :func:`child_env`: the folder of the
imported flexsim first on ``PYTHONPATH`` (and, for ``python -c`` in the checkout's root, ``PYTHONSAFEPATH``), so that it
imports the same flexsim.
"""

from __future__ import annotations

import os
from pathlib import Path

#: The checkout the tests belong to.
ROOT = Path(__file__).resolve().parents[1]


def flexsim_site() -> Path:
    """The folder that holds the imported ``flexsim`` package: site-packages, or the checkout of an editable install."""
    import flexsim

    return Path(flexsim.__file__).resolve().parents[1]


def child_env(*extra_paths: str | Path, base: dict | None = None, safe_path: bool = False) -> dict:
    """``base`` (default ``os.environ``) with ``PYTHONPATH`` = the imported flexsim's folder, then ``extra_paths`` (e.g.
    a folder of modules the child imports), then the caller's ``PYTHONPATH``. ``safe_path``: also ``PYTHONSAFEPATH=1``
    (Python >= 3.11), for ``python -c`` or ``-m`` in the checkout's root, whose working directory would otherwise come
    first on ``sys.path``; a script run by its path gets its own folder first (an example's siblings), which is safe
    as long as that folder is not the checkout's root."""
    env = dict(os.environ if base is None else base)
    paths = [str(flexsim_site()), *(str(p) for p in extra_paths), env.get("PYTHONPATH", "")]
    env["PYTHONPATH"] = os.pathsep.join(p for p in paths if p)
    if safe_path:
        env["PYTHONSAFEPATH"] = "1"
    return env
