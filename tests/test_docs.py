"""The documentation a newcomer learns from (issue 30): the API reference lists every
public name, each with a numpydoc Parameters section (where it takes parameters) and an
example; the getting-started notebook session runs as written; the site builds with
warnings as errors (slow: CI runs it in .ci/run as well)."""

from __future__ import annotations

import importlib
import inspect
import re
import subprocess
import sys

import pytest

import dyade
from tests.helpers import ROOT

DOCS = ROOT / "docs"
API_PAGE = (DOCS / "api.md").read_text()


def documented() -> list[str]:
    """The names the API reference lists (its autosummary entries), fully qualified."""
    names, module = [], "dyade"
    for line in API_PAGE.splitlines():
        if match := re.match(r"\.\. currentmodule:: (\S+)", line):
            module = match.group(1)
        elif match := re.match(r"   ([A-Za-z_][\w.]*)$", line):
            names.append(f"{module}.{match.group(1)}")
    return names


def resolve(name: str):
    module, _, attribute = name.rpartition(".")
    try:
        return getattr(importlib.import_module(module), attribute)
    except ModuleNotFoundError:  # dyade.plot.curves.figure: a module's attribute
        parent, _, child = module.rpartition(".")
        return getattr(getattr(importlib.import_module(parent), child), attribute)


def test_the_api_reference_lists_every_export():
    listed = set(documented())
    missing = [name for name in dyade.__all__
               if not name.startswith("__") and f"dyade.{name}" not in listed]
    assert not missing
    assert len(listed) == len(documented())  # each once


def _takes_parameters(obj) -> bool:
    if inspect.isclass(obj):
        return False  # results and errors: constructed by the API (fields documented)
    parameters = inspect.signature(obj).parameters.values()
    return any(p.kind not in (p.VAR_KEYWORD, p.VAR_POSITIONAL) for p in parameters)


@pytest.mark.parametrize("name", documented())
def test_every_documented_name_has_parameters_and_an_example(name):
    if name.startswith("dyade.plot."):
        pytest.importorskip("matplotlib")
    doc = inspect.getdoc(resolve(name)) or ""
    assert ">>>" in doc, f"{name}: no example"
    if _takes_parameters(resolve(name)):
        assert re.search(r"^Parameters\n-{10}", doc, flags=re.M), f"{name}: no Parameters"


@pytest.mark.parametrize("name", documented())
def test_every_documented_docstring_is_valid_restructured_text(name):
    """What the site's build would fail on (-W), found without building it: numpydoc's
    reST of each docstring parses without errors (a bare ``|μ|`` is an undefined
    substitution). Needs the docs extra."""
    pytest.importorskip("numpydoc")
    docutils_core = pytest.importorskip("docutils.core")
    from io import StringIO

    from numpydoc.docscrape_sphinx import get_doc_object

    if name.startswith("dyade.plot."):
        pytest.importorskip("matplotlib")
    text = str(get_doc_object(resolve(name), config={"show_class_members": False}))
    stream = StringIO()
    tree = docutils_core.publish_doctree(text, settings_overrides={
        "report_level": 3, "halt_level": 5, "warning_stream": stream})
    errors = [node.astext() for node in tree.findall()
              if node.tagname == "system_message" and int(node["level"]) >= 3]
    assert not errors and not stream.getvalue(), (errors, stream.getvalue())


def test_the_gallery_shows_every_figure_of_make_figures():
    """Each figure ``docs/make_figures.py`` makes is on the gallery page, with its code
    (literalinclude of its function) and shown (a cell or its file)."""
    source = (DOCS / "make_figures.py").read_text()
    gallery = (DOCS / "gallery.md").read_text()
    figures = re.findall(r'^    "([\w.-]+\.(?:png|gif))": (\w+),$', source, flags=re.M)
    assert len(figures) >= 9
    for name, function in figures:
        assert f":pyobject: {function}\n" in gallery, function
        assert f'show("{name}")' in gallery or f"]({name})" in gallery, name


def _session() -> list[str]:
    """The code cells of the getting-started page that a reader sees (not the hidden
    ones that set the page up)."""
    text = (DOCS / "getting-started.md").read_text()
    cells = re.findall(r"```\{code-cell\} ipython3\n(.*?)```", text, flags=re.S)
    return [cell for cell in cells if "remove-cell" not in cell]


def test_the_getting_started_session_runs_as_written(monkeypatch):
    """Read a shipped mechanism, analyse it, a table with pandas, a column and the values
    at an angle, a figure: the dozen lines of the notebook session, as the page shows
    them."""
    pytest.importorskip("pandas")
    pytest.importorskip("matplotlib")
    cells = _session()
    lines = [line for cell in cells for line in cell.splitlines() if line.strip()]
    assert 6 <= len(lines) <= 12
    monkeypatch.chdir(ROOT)
    space: dict = {}
    for cell in cells:
        exec(compile(cell, "getting-started.md", "exec"), space)
    assert space["frame"].index.name == "angle_deg"
    assert space["row"]["angle_deg"] == 37.0 and space["between"]["angle_deg"] == 37.25
    assert space["row"]["F_2_3"] == space["frame"].loc[37.0, "F_2_3"]
    png = space["fig"]._repr_png_()  # what the notebook shows
    assert png[:4] == b"\x89PNG" and len(png) > 10_000
    summary = space["summary"]
    assert isinstance(summary["M_drive_max"], float) and summary["mu_2_min_deg"] > 0


@pytest.mark.slow
def test_the_site_builds_with_warnings_as_errors(tmp_path):
    """sphinx-build -W: every page, the executed getting-started page and gallery, the
    API reference."""
    pytest.importorskip("sphinx")
    pytest.importorskip("myst_nb")
    run = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-b", "html",
                          "-d", str(tmp_path / "doctrees"), str(DOCS), str(tmp_path / "html")],
                         capture_output=True, text=True, timeout=900)
    assert run.returncode == 0, run.stderr[-3000:]
    page = (tmp_path / "html" / "getting-started.html").read_text()
    assert "<img" in page  # the session's figure, executed
    assert len(list((tmp_path / "html" / "generated").glob("*.html"))) == len(documented())
