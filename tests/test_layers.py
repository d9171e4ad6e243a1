"""Layers (STYLE §2): imports point one way only.

    cli  ->  report, plot  ->  API (linkage, clearance, vibration)  ->  files, units, errors, arrays

matplotlib only in dyade/plot/ (the optional extra): the API never imports it.

Every module under dyade/ is read with ``ast`` (not imported): every ``import`` and
``from … import`` (relative ones resolved, those inside functions and ``if TYPE_CHECKING``
blocks included), ``importlib.import_module`` by name, and strings naming a dyade module
(the lazy re-exports of ``dyade/__init__.py``). Each rule lists the offending module,
line and import.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path
from typing import NamedTuple

import pytest

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "dyade"
MODULE_NAME = re.compile(r"dyade(\.\w+)*")


class Import(NamedTuple):
    target: str  # the imported module, or "sys.stdout" for a write to a standard stream
    line: int
    in_function: bool


def module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


FILES = {module_name(path): path for path in sorted(PACKAGE.rglob("*.py"))}


class Reader(ast.NodeVisitor):
    """Collects one module's imports, print() calls and uses of sys.stdout/sys.stderr."""

    def __init__(self, name: str) -> None:
        self.name = name
        self.package = name if FILES[name].name == "__init__.py" else name.rpartition(".")[0]
        self.imports: list[Import] = []
        self.writes: list[Import] = []
        self.depth = 0  # function nesting

    def add(self, target: str, node: ast.AST) -> None:
        self.imports.append(Import(target, node.lineno, self.depth > 0))

    def nested(self, node: ast.AST) -> None:
        self.depth += 1
        self.generic_visit(node)
        self.depth -= 1

    visit_FunctionDef = visit_AsyncFunctionDef = visit_Lambda = nested

    def visit_Import(self, node: ast.Import) -> None:
        for alias in node.names:
            self.add(alias.name, node)

    def visit_ImportFrom(self, node: ast.ImportFrom) -> None:
        base = node.module or ""
        if node.level:  # relative: from the module's package, one level up per extra dot
            parts = self.package.split(".")
            parts = parts[:len(parts) - (node.level - 1)]
            base = ".".join(parts + ([node.module] if node.module else []))
        for alias in node.names:
            submodule = f"{base}.{alias.name}"
            # `from dyade.linkage import dyads` imports the module dyade.linkage.dyads
            self.add(submodule if submodule in FILES else base, node)
            if base == "sys" and alias.name in ("stdout", "stderr"):
                self.writes.append(Import(submodule, node.lineno, self.depth > 0))

    def visit_Constant(self, node: ast.Constant) -> None:
        # a string that names a dyade module is imported by name (importlib, lazy exports)
        if isinstance(node.value, str) and node.value in FILES:
            self.add(node.value, node)

    def visit_JoinedStr(self, node: ast.JoinedStr) -> None:
        # f"dyade.cli.{name}" imports a module of the package dyade.cli
        first = node.values[0] if node.values else None
        if isinstance(first, ast.Constant) and isinstance(first.value, str):
            prefix = first.value.removesuffix(".")
            if first.value.endswith(".") and MODULE_NAME.fullmatch(prefix) and prefix in FILES:
                self.add(prefix, node)
        self.generic_visit(node)

    def visit_Call(self, node: ast.Call) -> None:
        if isinstance(node.func, ast.Name) and node.func.id == "print":
            self.writes.append(Import("print()", node.lineno, self.depth > 0))
        self.generic_visit(node)

    def visit_Attribute(self, node: ast.Attribute) -> None:
        if (isinstance(node.value, ast.Name) and node.value.id == "sys"
                and node.attr in ("stdout", "stderr", "__stdout__", "__stderr__")):
            self.writes.append(Import(f"sys.{node.attr}", node.lineno, self.depth > 0))
        self.generic_visit(node)


def _read(name: str) -> Reader:
    reader = Reader(name)
    reader.visit(ast.parse(FILES[name].read_text(encoding="utf-8"), str(FILES[name])))
    return reader


MODULES = {name: _read(name) for name in FILES}


def within(name: str, *packages: str) -> bool:
    """``name`` is one of ``packages`` or a module inside one."""
    return any(name == p or name.startswith(p + ".") for p in packages)


CLI = ("dyade.cli",)
REPORT = ("dyade.report",)
PLOT = ("dyade.plot",)
BASE = ("dyade.files", "dyade.units", "dyade.errors", "dyade.arrays")
ABOVE_BASE = ("dyade.linkage", "dyade.clearance", "dyade.vibration", "dyade.machine",
              "dyade.report", "dyade.plot", "dyade.cli")
PLOTTING = ("matplotlib",)

ENTRY_POINT = "dyade.__main__"
"""``python -m dyade``: the command line's second door, one line forwarding to
``dyade.cli.main``; it may import dyade.cli and nothing else does."""

BASE_EXCEPTIONS = {
    # the mechanism reader builds the model it reads into: Mechanism, links, joints
    # (dyade.linkage.model), and finds the dyad kinds (dyade.linkage.dyads: the registry)
    # whose file keys it reads; it imports nothing that computes
    ("dyade.files.mechanism", "dyade.linkage.model"): "anywhere",
    ("dyade.files.mechanism.reader", "dyade.linkage.model"): "anywhere",
    ("dyade.files.mechanism.links", "dyade.linkage.model"): "anywhere",
    ("dyade.files.mechanism.dyads", "dyade.linkage.model"): "anywhere",
    ("dyade.files.mechanism.loads", "dyade.linkage.model"): "anywhere",
    ("dyade.files.mechanism.friction", "dyade.linkage.model"): "anywhere",
    ("dyade.files.mechanism.dyads", "dyade.linkage.dyads"): "anywhere",
    # ... and the drive of its [drive] table (dyade.machine.motor: dataclasses only)
    ("dyade.files.mechanism.drive", "dyade.machine.motor"): "anywhere",
    # the coupling reader returns the Coupling model; it imports it in read_coupling only,
    # so that reading the file's keys (load_data) does not load the model's numpy
    ("dyade.files.coupling", "dyade.vibration.coupling"): "in a function",
    # the gear-drive reader builds the drive it reads (dyade.vibration.gears.model: plain
    # dataclasses and the gear geometry, no numpy) and places bodies with that geometry
    ("dyade.files.gears", "dyade.vibration.gears.model"): "anywhere",
}


def _allowed_in_base(name: str, imp: Import) -> bool:
    where = BASE_EXCEPTIONS.get((name, imp.target))
    return where == "anywhere" or (where == "in a function" and imp.in_function)


# rule: (who is checked, which imports are wrong for it, why)
RULES = {
    "click only in cli": (
        lambda name: not within(name, *CLI),
        lambda name, imp: within(imp.target, "click"),
        "imports click, which only dyade/cli/ may"),
    "rich only in cli and report": (
        lambda name: not within(name, *CLI, *REPORT),
        lambda name, imp: within(imp.target, "rich"),
        "imports rich, which only dyade/cli/ and dyade/report/ may"),
    "nothing imports the cli": (
        lambda name: not within(name, *CLI) and name != ENTRY_POINT,
        lambda name, imp: within(imp.target, *CLI),
        "imports the command line (dyade.cli), which points the arrow upwards"),
    "matplotlib only in plot": (
        lambda name: not within(name, *PLOT),
        lambda name, imp: within(imp.target, *PLOTTING),
        "imports matplotlib, which only dyade/plot/ may (the optional plot extra)"),
    "the API plots nothing and reports nothing": (
        lambda name: not within(name, *CLI, *REPORT, *PLOT) and name != ENTRY_POINT,
        lambda name, imp: within(imp.target, *PLOTTING, *REPORT, *PLOT),
        "is API and imports a plotting library, dyade.plot or dyade.report"),
    "figures and tables side by side": (
        lambda name: within(name, *REPORT, *PLOT),
        lambda name, imp: (within(imp.target, *PLOT) and within(name, *REPORT)
                           or within(imp.target, *REPORT) and within(name, *PLOT)),
        "is in report or plot and imports the other (both read the API's results)"),
    "the dyad kinds know no file syntax": (
        lambda name: within(name, "dyade.linkage.dyads"),
        lambda name, imp: within(imp.target, "dyade.files"),
        "is a dyad kind (geometry and mechanics) and imports dyade.files; the keys of a "
        "kind are read by dyade.files.mechanism.dyads"),
    "files, units, errors, arrays import no layer above": (
        lambda name: within(name, *BASE),
        lambda name, imp: within(imp.target, *ABOVE_BASE) and not _allowed_in_base(name, imp),
        "is a base module and imports a layer above it"),
}


def _where(name: str, imp: Import) -> str:
    return f"{FILES[name].relative_to(ROOT)}:{imp.line}: {imp.target}"


@pytest.mark.parametrize("rule", RULES)
def test_imports_point_one_way(rule):
    checked, wrong, why = RULES[rule]
    offences = [_where(name, imp) for name, module in MODULES.items() if checked(name)
                for imp in module.imports if wrong(name, imp)]
    assert not offences, f"{rule}: each of these {why}:\n  " + "\n  ".join(offences)


def test_only_the_cli_prints():
    offences = [_where(name, imp) for name, module in MODULES.items()
                if not within(name, *CLI) for imp in module.writes]
    assert not offences, ("only dyade/cli/ prints or writes to sys.stdout/sys.stderr; the "
                          "API returns results and raises errors:\n  " + "\n  ".join(offences))


def test_the_reader_sees_every_kind_of_import():
    # the rules above pass vacuously if the reader misses imports: pin what it must find
    found = {name: {imp.target for imp in module.imports} for name, module in MODULES.items()}
    assert "click" in found["dyade.cli"]                                   # import x
    assert "dyade.linkage.dyads" in found["dyade.files.mechanism.dyads"]  # from pkg import module
    assert "rich.progress" in found["dyade.cli.output"]                    # inside a function
    assert "matplotlib.figure" in found["dyade.plot.polar"]                # a plot module
    assert "dyade.cli" in found["dyade.cli"]                               # importlib f-string
    assert "dyade.linkage.sweep" in found["dyade"]                         # lazy export by name
    coupling = [imp for imp in MODULES["dyade.files.coupling"].imports
                if imp.target == "dyade.vibration.coupling"]
    assert coupling and all(imp.in_function for imp in coupling)
    assert any(imp.target == "sys.stdout" for imp in MODULES["dyade.cli.output"].writes)


def test_relative_imports_are_resolved():
    reader = Reader("dyade.linkage.dyads")
    reader.visit(ast.parse("from . import rrr\nfrom ..model import Dyad\nfrom .. import sweep\n"
                           "from ...errors import InputError\n"))
    assert [imp.target for imp in reader.imports] == [
        "dyade.linkage.dyads.rrr", "dyade.linkage.model", "dyade.linkage.sweep", "dyade.errors"]
