"""Every command shown in the shell blocks of the README and of the documentation
(docs/**/*.md) runs as written (issues 19, 30): they cannot drift from the program.
Blocks that install the package, build the docs or run the test suite and benchmarks
are what CI itself runs, and are left to it. The documentation's blocks are in the slow
set (`pytest -m slow`, run by CI)."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.helpers import ROOT

PAGES = [ROOT / "README.md"] + sorted(
    (page for page in (ROOT / "docs").glob("**/*.md") if "_build" not in page.parts),
    key=lambda page: (page.name == "gallery.md", page))  # the gallery repeats the guide's
BLOCKS = [(page, block) for page in PAGES
          for block in re.findall(r"```sh\n(.*?)```", page.read_text(), flags=re.S)]


def commands(block: str) -> frozenset[str]:
    """The commands of a shell block, continuation lines joined, comments and spacing
    left out."""
    lines = block.replace("\\\n", " ").splitlines()
    return frozenset(" ".join(re.sub(r"(^|\s)#.*$", "", line).split()) for line in lines) - {""}


def runnable() -> list[tuple[Path, str]]:
    """The blocks to run: not those that install, build the docs or run the tests (CI
    does), nor a block whose every command an earlier block runs."""
    seen: set[str] = set()
    out = []
    for page, block in BLOCKS:
        if re.search(r"pip install|pytest|python tests/|sphinx-build", block):
            continue
        if commands(block) <= seen:
            continue
        seen |= commands(block)
        out.append((page, block))
    return out


RUNNABLE = runnable()


def test_the_readme_shows_commands():
    readme = [block for page, block in RUNNABLE if page.name == "README.md"]
    assert len(readme) >= 1 and len(RUNNABLE) >= 15
    assert all("dyade" in block for _, block in RUNNABLE)


def _name(case) -> str:
    page, block = case
    return f"{page.relative_to(ROOT)}:{block.split()[1]}…"


def _marked(case):
    """The README's own blocks run in the default run (its quick start is what a user
    tries first); the documentation's many blocks, a subprocess per command, run with the
    slow set that CI runs too."""
    page, _ = case
    return case if page.name == "README.md" else pytest.param(*[case], marks=pytest.mark.slow)


@pytest.mark.parametrize("case", [_marked(case) for case in RUNNABLE], ids=_name)
def test_readme_block_runs_as_written(case, tmp_path):
    """Run in a fresh folder with the shipped mechanisms, the installed `dyade` first on
    the PATH: exit 0, no traceback, no "failed:" from the README's own loops."""
    _, block = case
    shutil.copytree(ROOT / "mechanisms", tmp_path / "mechanisms")
    env = dict(os.environ, PATH=f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}",
               COLUMNS="100")
    run = subprocess.run(["bash", "-e", "-o", "pipefail", "-c", block], cwd=tmp_path, env=env,
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr[-2000:]
    assert "Traceback" not in run.stderr and "failed:" not in run.stdout, run.stderr[-2000:]


# -- the README tells the whole product (issue 42) ----------------------------------------
README = (ROOT / "README.md").read_text()
QUICK_START = re.findall(r"```sh\n(.*?)\n```", README, flags=re.S)[:2]


def test_the_readme_is_short_and_names_every_command_page_and_study():
    from dyade.cli import SUBCOMMANDS

    assert len(README.encode()) < 12_000
    missing = [name for name in SUBCOMMANDS if f"`dyade {name} " not in README]
    assert not missing, f"commands the README does not name: {missing}"
    pages = [page.relative_to(ROOT).as_posix()
             for folder in ("guide", "reference") for page in (ROOT / "docs" / folder).glob("*.md")
             if page.name != "index.md"]
    unlinked = [page for page in pages if f"]({page})" not in README]
    assert not unlinked, f"pages the README does not link: {unlinked}"
    studies = [path.name for path in (ROOT / "mechanisms" / "studies").glob("*.toml")]
    assert studies and all(name in README for name in studies) and "mechanisms/studies/" in README


def test_ci_runs_the_readmes_two_commands_verbatim():
    assert len(QUICK_START) == 2 and all(len(block.splitlines()) == 1 for block in QUICK_START)
    ci = (ROOT / ".ci" / "run").read_text().splitlines()
    assert all(command in ci for command in QUICK_START), QUICK_START


IMPORTED_BY_TESTS = {  # a module the default tests import or skip without -> its distribution
    "pandas": "pandas", "matplotlib": "matplotlib", "scipy": "scipy", "numpydoc": "numpydoc",
    "docutils.core": "numpydoc", "pyarrow.parquet": "pyarrow", "distributed": "distributed",
    "hypothesis": "hypothesis", "pytest_benchmark": "pytest-benchmark", "ezdxf": "ezdxf",
    "scipy.integrate": "scipy", "scipy.special": "scipy",
}
SITE_ONLY = {"sphinx", "myst_nb"}  # the site's build: tests/test_docs.py, slow, docs extra


def test_the_readmes_test_command_installs_what_every_default_test_needs():
    """No default test skips after the quick start's second command: each module a test
    skips without (pytest.importorskip) comes with the extras that command installs."""
    import tomllib

    extras = re.search(r'pip install "\.\[([\w,]+)\]"', QUICK_START[1])[1].split(",")
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    installed = {re.split(r"[<>=\[ ]", requirement)[0].lower()
                 for extra in extras for requirement in project["optional-dependencies"][extra]}
    needed = set()
    for path in (ROOT / "tests").rglob("*.py"):
        needed |= set(re.findall(r'importorskip\("([\w.]+)"\)', path.read_text()))
    unknown = needed - set(IMPORTED_BY_TESTS) - SITE_ONLY
    assert not unknown, f"name the distribution of {unknown} in IMPORTED_BY_TESTS"
    lacking = {IMPORTED_BY_TESTS[module] for module in needed - SITE_ONLY} - installed
    assert not lacking, f"the README's test command does not install {lacking}"


def test_the_test_extra_brings_the_plugins_the_pytest_options_need():
    """``pytest`` as the README runs it takes its options from pyproject.toml: ``-n`` (the
    tests on every core) needs pytest-xdist, ``--benchmark-disable`` pytest-benchmark,
    both in the test extra the quick start installs."""
    import tomllib

    project = tomllib.loads((ROOT / "pyproject.toml").read_text())
    addopts = project["tool"]["pytest"]["ini_options"]["addopts"].split()
    test = {re.split(r"[<>=\[ ]", requirement)[0].lower()
            for requirement in project["project"]["optional-dependencies"]["test"]}
    assert "test" in re.search(r'pip install "\.\[([\w,]+)\]"', QUICK_START[1])[1].split(",")
    needs = {"-n": "pytest-xdist", "--dist": "pytest-xdist",
             "--benchmark-disable": "pytest-benchmark"}
    assert {needs[option] for option in addopts if option in needs} <= test
