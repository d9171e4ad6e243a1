"""The examples in the docstrings, the README and the documentation's pages run, and
give the numbers they show (doctest): the documentation cannot drift from the program."""

from __future__ import annotations

import doctest
import importlib
import pkgutil
from pathlib import Path

import pytest

import dyade

ROOT = Path(__file__).resolve().parent.parent
MODULES = sorted(name for _, name, _ in pkgutil.walk_packages(dyade.__path__, "dyade.")
                 if not name.startswith("dyade.cli"))


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name, monkeypatch):
    monkeypatch.chdir(ROOT)  # the examples read the shipped mechanisms by relative path
    if name.startswith("dyade.plot."):
        pytest.importorskip("matplotlib")  # the optional plot extra
    module = importlib.import_module(name)
    failures, _ = doctest.testmod(module, optionflags=doctest.NORMALIZE_WHITESPACE)
    assert failures == 0


PAGES = [ROOT / "README.md"] + sorted(page for page in (ROOT / "docs").glob("**/*.md")
                                      if "_build" not in page.parts
                                      and "\n>>> " in page.read_text())


@pytest.mark.parametrize("page", PAGES, ids=lambda page: str(page.relative_to(ROOT)))
def test_python_sessions_of_the_readme_and_the_docs(page, monkeypatch):
    """The ``>>>`` sessions of the README and of the documentation's pages run and give
    what they show."""
    monkeypatch.chdir(ROOT)
    failures, tried = doctest.testfile(str(page), module_relative=False,
                                       optionflags=doctest.NORMALIZE_WHITESPACE)
    assert tried >= 3 and failures == 0


def test_the_api_has_examples():
    """Every function re-exported by ``dyade`` documents itself with an example or
    parameters (numpydoc), so that ``help(dyade.x)`` teaches."""
    for name in dyade.__all__:
        if name.startswith("__"):
            continue
        doc = getattr(dyade, name).__doc__ or ""
        assert len(doc) > 40, name


def test_the_package_docstring_names_every_export():
    """``help(dyade)`` lists the whole re-exported API (the gear API was once left out)."""
    missing = [name for name in dyade.__all__
               if not name.startswith("__") and f"``{name}" not in dyade.__doc__]
    assert not missing, f"dyade/__init__.py exports these without naming them: {missing}"
