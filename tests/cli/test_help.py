"""`dyade help TOPIC` (issue 42): the file references and the user guide come with the
package (dyade/pages, links to docs/reference and docs/guide that a wheel holds as
files), and no help text or message sends a pip user to a docs/...md file that an
installed dyade does not have."""

from __future__ import annotations

import ast
import re

from dyade.cli.help import pages
from tests.helpers import ROOT
from tests.hostile_common import expect

DOCS = sorted(page for folder in ("reference", "guide")
              for page in (ROOT / "docs" / folder).glob("*.md") if page.name != "index.md")


def test_every_reference_and_guide_page_is_a_topic_with_the_pages_text():
    topics = pages()
    assert sorted(topics) == sorted(page.stem for page in DOCS)
    for page in DOCS:
        shipped = ROOT / "dyade" / "pages" / page.name
        assert shipped.read_text() == page.read_text(), page.name
    assert topics["mechanism-file"] == "Mechanism files"


def test_the_topics_and_a_page():
    listing = expect(["help"], 0, "mechanism-file", "study-file", "drive-line").output
    assert "Mechanism files" in listing
    text = expect(["help", "gear-file"], 0, "# Gear-drive files").output
    assert text == (ROOT / "docs" / "reference" / "gear-file.md").read_text()


def test_a_notebook_pages_header_is_left_out():
    text = expect(["help", "studies"], 0).output
    assert not text.startswith("---")


def test_an_unknown_topic_is_refused_with_the_close_ones():
    expect(["help", "mechanism"], 2, "no help topic 'mechanism'", "mechanism-file")


def _user_strings(path):
    """The strings of a module a user reads: every string of a command module (its
    docstrings are the --help texts), the other modules' strings but their docstrings."""
    tree = ast.parse(path.read_text())
    docstrings = set()
    if "/cli/" not in str(path):
        for node in ast.walk(tree):
            if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef,
                                 ast.AsyncFunctionDef)) and ast.get_docstring(node) is not None:
                docstrings.add(id(node.body[0].value))
        for node in ast.walk(tree):  # the attribute docstrings: a string statement
            if isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant):
                docstrings.add(id(node.value))
    for node in ast.walk(tree):
        if isinstance(node, ast.Constant) and isinstance(node.value, str) \
                and id(node) not in docstrings:
            yield node.lineno, node.value


PAGE_FILE = re.compile(r"docs/(reference|guide)/[\w-]+\.md")


def test_no_message_names_a_documentation_file():
    found = [(path.relative_to(ROOT).as_posix(), line, text)
             for path in sorted((ROOT / "dyade").rglob("*.py"))
             if PAGE_FILE.search(path.read_text())  # parse only the few that name one
             for line, text in _user_strings(path) if PAGE_FILE.search(text)]
    assert not found, f"name the page as `dyade help TOPIC`: {found}"
