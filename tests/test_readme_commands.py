"""The README's shell commands work when run in the order given, as on a fresh install.

Every line of every ```` ```bash ```` block of README.md is run, in order, in one empty directory under
``tmp_path`` (so a command may use what an earlier one wrote, e.g. ``flexsim view`` the log that ``flexsim
simulate`` wrote), with the installed ``flexsim`` the tests import (:func:`tests.installed.child_env`) and the
``examples/`` folder of the checkout beside it. Each must exit 0. Comments are dropped; ``a && b`` runs ``a`` then ``b``.

What the test does not run as written, and why:

* ``python3 -m pip install ...``: the environment running the tests is that install;
* ``python3 -m pytest``: the test suite itself;
* the flutter searches are reduced with their documented options (``REDUCE``): ``flexsim flutter`` to one
  altitude (unless the command names its altitudes), ``flexsim sweep`` to one altitude, one model and the two ends of its radius or angle range. The
  reduced commands exercise the same code paths, output folders and the order of the commands (a second sweep
  into a folder that holds finished points would stop with "give --resume").
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
import time
from pathlib import Path

from tests.installed import child_env

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
COMMAND_TIMEOUT_S = 600.0

#: Command prefix -> the documented options appended to make the command short.
REDUCE: dict[str, str] = {
    "flexsim flutter": "--altitudes 9144",
    "flexsim sweep --turn": "--altitudes 9144 --models US --radii-m 5000 12000",
    "flexsim sweep --climb": "--altitudes 9144 --models US --angles-deg -15 15",
}
#: Commands that are the environment or the suite itself (see the module docstring).
NOT_RUN = (re.compile(r"^python3? -m pip install\b"), re.compile(r"^python3? -m pytest\b"))


def readme_commands(text: str) -> list[str]:
    """The commands of the ```bash blocks of ``text``, in order, comments dropped and ``&&`` chains split."""
    commands = []
    for block in re.findall(r"^```bash\n(.*?)^```", text, re.DOTALL | re.MULTILINE):
        for line in block.splitlines():
            line = re.sub(r"(^|\s)#.*$", "", line).strip()
            commands += [part.strip() for part in line.split("&&") if part.strip()]
    return commands


def runnable(command: str) -> str | None:
    """The command as the test runs it (reduced per ``REDUCE``), or None for one in ``NOT_RUN``."""
    if any(p.match(command) for p in NOT_RUN):
        return None
    for prefix, options in REDUCE.items():
        if prefix == "flexsim flutter" and " --altitudes " in command:
            continue  # already at the altitudes it names
        if command == prefix or command.startswith(prefix + " "):
            return f"{command} {options}"
    return command


def test_the_readme_has_commands():
    """The parser finds the README's commands (guards against a pattern that silently matches nothing)."""
    commands = readme_commands(README.read_text(encoding="utf-8"))
    assert len(commands) >= 10 and "flexsim flutter" in commands
    assert readme_commands("```bash\na --x 1   # note\nb && c\n```\n```python\nd\n```\n") == ["a --x 1", "b", "c"]
    assert runnable("python3 -m pip install .") is None
    assert runnable("flexsim sweep --turn --out x") == "flexsim sweep --turn --out x " + REDUCE["flexsim sweep --turn"]
    assert runnable("flexsim flutter x.toml --altitudes 0") == "flexsim flutter x.toml --altitudes 0"


def test_the_readme_commands_run_in_order(tmp_path):
    (tmp_path / "examples").symlink_to(ROOT / "examples", target_is_directory=True)
    env = child_env(base={**os.environ, "MPLBACKEND": "Agg", "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"})
    env.pop("DISPLAY", None)
    env.pop("WAYLAND_DISPLAY", None)
    # `flexsim` and `python` are this interpreter with this checkout, whatever else is on PATH
    prelude = (f'flexsim() {{ "{sys.executable}" -m flexsim.cli.main "$@"; }}\n'
               f'python() {{ "{sys.executable}" "$@"; }}\npython3() {{ "{sys.executable}" "$@"; }}\n')
    failures, timings = [], []
    for command in readme_commands(README.read_text(encoding="utf-8")):
        run_as = runnable(command)
        if run_as is None:
            continue
        start = time.perf_counter()
        run = subprocess.run(["bash", "-c", prelude + run_as], cwd=tmp_path, env=env, capture_output=True, text=True,
                             timeout=COMMAND_TIMEOUT_S)
        timings.append(f"{time.perf_counter() - start:6.1f} s  exit {run.returncode}  {run_as}")
        if run.returncode != 0:
            failures.append(f"{run_as}: exit {run.returncode}\n{run.stderr[-2000:]}")
    print("\n" + "\n".join(timings))
    assert not failures, "README commands that failed:\n" + "\n".join(failures)
