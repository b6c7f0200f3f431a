"""``tools/make_gtm_toml.py`` regenerates the three bundled GTM files from the repository alone.

The tool is run from a copy of the tool alone in ``tmp_path`` (so that nothing outside the repository, such as
a sibling ``shared/`` folder, can be read through a relative path), with the calibration file of the
repository; its output must equal the bundled files byte for byte.
"""

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "flexsim" / "aircraft" / "data"


@pytest.mark.parametrize(("bundled", "options"), [
    ("gtm_uncalibrated.toml", []),
    ("gtm.toml", ["--calibration", str(ROOT / "tools" / "gtm_calibration.toml")]),
    ("gtm_paper.toml", ["--calibration", str(ROOT / "tools" / "gtm_calibration.toml"), "--paper"]),
])
def test_bundled_gtm_regenerates_from_the_repository(tmp_path, bundled, options):
    tool = tmp_path / "make_gtm_toml.py"
    shutil.copy(ROOT / "tools" / "make_gtm_toml.py", tool)
    out = subprocess.run([sys.executable, str(tool), *options], cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout == (DATA / bundled).read_text(encoding="utf-8")


def test_gtm_sources_are_in_the_repository():
    sources = DATA / "sources"
    for name in ("gtm-notional.md", "gtm_notional_params.json", "wing_stations_optionA_n4.csv"):
        assert (sources / name).stat().st_size > 1000
