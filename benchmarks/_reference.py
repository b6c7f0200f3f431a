"""The reference checkout of the side-by-side benchmarks (``--against`` / ``--compare`` / ``--reference``).

``reference_tree(rev)`` extracts ``rev`` with ``git archive`` into ``$XDG_CACHE_HOME/flexsim-bench/<sha>`` (default
``~/.cache``), kept between runs with numba's cache of its kernels. numba's cache files of this tree are copied
into it for every module whose source file is byte-identical in both trees (numba keys a cache entry on its
module's source), so that the reference does not recompile kernels it shares with this tree; the others compile
on the reference's first run. The reference's top-level ``envs/`` is linked as ``flexsim/envs`` in its checkout, so
that it imports its own environments, not this checkout's (installed as ``flexsim.envs``).
"""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

HERE = Path(__file__).resolve().parents[1]


def reference_tree(rev: str) -> Path:
    """The checkout of ``rev`` (module docstring); raises ``subprocess.CalledProcessError`` for an unknown revision."""
    sha = subprocess.run(["git", "-C", str(HERE), "rev-parse", "--short=12", rev], check=True, capture_output=True,
                         text=True).stdout.strip()
    tree = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "flexsim-bench" / sha
    if not (tree / "flexsim" / "__init__.py").is_file():
        tree.mkdir(parents=True, exist_ok=True)
        archive = subprocess.run(["git", "-C", str(HERE), "archive", sha], check=True, capture_output=True).stdout
        subprocess.run(["tar", "-x", "-C", str(tree)], input=archive, check=True)
    # the top-level envs/ is installed as flexsim.envs: without this link the reference's ``import flexsim.envs`` would
    # find this checkout's envs through the editable install (revisions since the meta-path finder was removed)
    envs, inside = tree / "envs", tree / "flexsim" / "envs"
    if envs.is_dir() and not inside.exists():
        inside.symlink_to(Path("..") / "envs", target_is_directory=True)
    for index in (HERE / "flexsim").glob("**/__pycache__/*.nb[ic]"):
        module = index.parent.parent / (index.name.split(".")[0] + ".py")
        theirs = tree / module.relative_to(HERE)
        target = theirs.parent / "__pycache__" / index.name
        if theirs.is_file() and not target.exists() and module.read_bytes() == theirs.read_bytes():
            target.parent.mkdir(exist_ok=True)
            shutil.copy2(index, target)
    return tree
