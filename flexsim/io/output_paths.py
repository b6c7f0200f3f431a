"""Output files that never lose earlier work: fresh names reserved atomically, no writing through symbolic links.

* :func:`reserve_new` creates a new, empty file under a name no other run holds (``stem.ext``, else ``stem-2.ext``,
  ``stem-3.ext``, ...; ``O_CREAT | O_EXCL``, atomic also between processes): two runs started in the same second, or
  four calls in one, get four files.
* :func:`check_not_link` refuses a path that is a symbolic link, dangling or not: writing through it would create or
  replace the link's target (a link planted as ``run.mcap -> ~/.ssh/authorized_keys``).
* :func:`open_output` opens a file for writing without following a link (``O_NOFOLLOW``), creating it or replacing
  an existing regular file that its caller has decided may be replaced.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import BinaryIO

__all__ = ["check_not_link", "reserve_new", "open_output", "unique_names"]

_NOFOLLOW = getattr(os, "O_NOFOLLOW", 0)


def check_not_link(name: str, path: str | os.PathLike) -> Path:
    """``path`` as a Path, or a ValueError naming ``name`` when it is a symbolic link (flexsim writes no output
    through a link)."""
    p = Path(path)
    if p.is_symlink():
        raise ValueError(f"{name} = {str(p)!r}: is a symbolic link (to {os.readlink(p)!r}); flexsim does not write "
                         "through links (that would create or replace the link's target): give the real path")
    return p


def reserve_new(directory: str | os.PathLike, stem: str, suffix: str) -> Path:
    """A new empty file ``directory/stem+suffix``, or ``stem-k+suffix`` with the smallest k >= 2 that is free,
    created atomically (no other process or call gets the same name); ``directory`` is created if missing."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    for k in range(1, 100_000):
        path = directory / (f"{stem}{suffix}" if k == 1 else f"{stem}-{k}{suffix}")
        try:
            fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL | _NOFOLLOW, 0o666)
        except FileExistsError:
            continue
        os.close(fd)
        return path
    raise FileExistsError(f"{directory}: no free name {stem}-k{suffix} for k < 100000")


def open_output(path: str | os.PathLike) -> BinaryIO:
    """``path`` opened for binary writing without following a symbolic link: a new file, or an existing regular
    file emptied (its caller decided it may be replaced). A link at ``path`` raises ValueError."""
    p = check_not_link("path", path)
    try:
        fd = os.open(p, os.O_WRONLY | os.O_CREAT | os.O_EXCL | _NOFOLLOW, 0o666)
    except FileExistsError:
        try:
            fd = os.open(p, os.O_WRONLY | os.O_TRUNC | _NOFOLLOW)
        except OSError as exc:
            if p.is_symlink():  # planted between the check and the open
                check_not_link("path", p)
            raise exc
    return os.fdopen(fd, "wb")


def unique_names(paths: list[Path]) -> list[Path]:
    """``paths`` with repeated names made distinct (``a.png, a.png`` -> ``a.png, a-2.png``), in order: outputs
    derived from values that print alike (altitudes 9144 and 9144.4 m, both ``_9144m``) never share a file."""
    seen: dict[Path, int] = {}
    out = []
    for p in paths:
        k = seen.get(p, 0) + 1
        seen[p] = k
        out.append(p if k == 1 else p.with_name(f"{p.stem}-{k}{p.suffix}"))
    return out
