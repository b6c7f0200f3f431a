"""Whether a Rerun viewer window can open here (no rerun import: the envs ask this on construction).

Used by :mod:`flexsim.io.rerun_view` (``flexsim view``) and by the environments' ``render_mode="human"``.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Mapping

__all__ = ["HEADLESS_HINT", "ViewerUnavailableError", "viewer_unavailable_reason"]

#: What to do instead where no viewer can open (appended to every :class:`ViewerUnavailableError`).
HEADLESS_HINT = ("save the recording instead (flexsim view LOG --save run.rrd, then `rerun run.rrd` where there is a "
                 "display), or stream to a viewer running elsewhere (flexsim view LOG --connect rerun+http://HOST:9876/proxy)")


class ViewerUnavailableError(RuntimeError):
    """No Rerun viewer can be opened or reached here; the message names the headless alternatives."""


def viewer_unavailable_reason(environ: Mapping[str, str] | None = None, platform: str | None = None) -> str | None:
    """Why a Rerun viewer window cannot open on this machine, or None if it may.

    Rerun's native viewer (winit) needs an X11 or Wayland display on Linux and the BSDs; macOS and Windows
    have one for a logged-in user. ``environ`` and ``platform`` default to ``os.environ`` and ``sys.platform``.
    """
    environ = os.environ if environ is None else environ
    platform = sys.platform if platform is None else platform
    if platform.startswith(("linux", "freebsd", "openbsd", "netbsd")) and not any(
            environ.get(name) for name in ("DISPLAY", "WAYLAND_DISPLAY", "WAYLAND_SOCKET")):
        return "no display (neither DISPLAY nor WAYLAND_DISPLAY is set: a headless machine or ssh without X forwarding)"
    return None
