"""Every command shown in the README's shell blocks runs as written (issue 19): the
README cannot drift from the program. Blocks that install the package or run the test
suite and benchmarks are what CI itself runs, and are left to it."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.helpers import ROOT

BLOCKS = re.findall(r"```sh\n(.*?)```", (ROOT / "README.md").read_text(), flags=re.S)
RUNNABLE = [block for block in BLOCKS
            if not re.search(r"pip install|pytest|python tests/", block)]


def test_the_readme_shows_commands():
    assert len(RUNNABLE) >= 4 and all("dyade" in block for block in RUNNABLE)


@pytest.mark.parametrize("block", RUNNABLE, ids=lambda b: b.split()[1] + "…")
def test_readme_block_runs_as_written(block, tmp_path):
    """Run in a fresh folder with the shipped mechanisms, the installed `dyade` first on
    the PATH: exit 0, no traceback, no "failed:" from the README's own loops."""
    shutil.copytree(ROOT / "mechanisms", tmp_path / "mechanisms")
    env = dict(os.environ, PATH=f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}",
               COLUMNS="100")
    run = subprocess.run(["bash", "-e", "-o", "pipefail", "-c", block], cwd=tmp_path, env=env,
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr[-2000:]
    assert "Traceback" not in run.stderr and "failed:" not in run.stdout, run.stderr[-2000:]
