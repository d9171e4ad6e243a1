"""Layers (STYLE §2): imports point one way only.

    cli  ->  report, plot, study  ->  analyses  ->  engine (linkage, machine, vibration,
    clearance) and readers (files), side by side  ->  model  ->  units, errors, arrays

(dyade.report.html, the design report, composes report's tables and plot's figures: it
sits above both, and neither imports it.) The engine reads no file and runs no analysis;
a reader computes nothing (it builds the model's objects); the model imports only the
base. No exceptions.

matplotlib only in dyade/plot/ (the optional extra): the API never imports it.

Every module under dyade/ is read with ``ast`` (not imported): every ``import`` and
``from … import`` (relative ones resolved, those inside functions and ``if TYPE_CHECKING``
blocks included), ``importlib.import_module`` by name, and strings naming a dyade module
(the lazy re-exports of ``dyade/__init__.py``). Each rule lists the offending module,
line and import.

Two more rules keep each package a one-way street (issue 25):

- **No circle inside a package.** The graph is every import between modules of dyade/
  (each module a node, a package's ``__init__.py`` the node of the package's own name;
  imports in functions and ``if TYPE_CHECKING`` blocks count like the others, and so does
  a module importing its own package's ``__init__``). Every circle of it is reported under
  the innermost package that holds all its modules (a package holds its ``__init__``, its
  modules and, through them, its sub-packages), as its modules in order with the file and
  line of each import; for each import that closes a circle the shortest such circle is
  shown, so that every import to cut is listed. Importing ``dyade.a.b`` also runs
  ``dyade/a/__init__.py`` first, but only imports written in a file are edges: Python
  handles a package whose ``__init__`` imports its modules while they import each other.
- **No private import across modules.** A name with a leading underscore (``_x``,
  ``__x``; dunders such as ``__version__`` are public) is private to the module that
  defines it, period: no other module imports it (``from dyade.a import _x``) or reads it
  from an imported module (``a._x`` or ``getattr(a, "_x")``, where ``a`` is bound to a
  dyade module by ``import``, ``from … import`` or ``importlib.import_module``). A
  package's ``__init__`` is a module like any other: it re-exports no private name of its
  own modules. A private *module* (``dyade/a/_b.py``) is private to its package: modules
  inside ``dyade.a`` may import it, no module outside may. Private attributes of classes
  and objects are out of reach of a reader that does not run the code.
"""

from __future__ import annotations

import ast
import re
from collections import deque
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


class Private(NamedTuple):
    owner: str  # the module (or, for a private module, the package) the name belongs to
    name: str   # the private name: "_x", or "_b" for the private module owner._b
    line: int


def module_name(path: Path, root: Path = ROOT) -> str:
    parts = list(path.relative_to(root).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def tree_files(root: Path, package: Path) -> dict[str, Path]:
    """Module name -> file, for every module of the package directory ``package``."""
    return {module_name(path, root): path for path in sorted(package.rglob("*.py"))}


FILES = tree_files(ROOT, PACKAGE)


def within(name: str, *packages: str) -> bool:
    """``name`` is one of ``packages`` or a module inside one."""
    return any(name == p or name.startswith(p + ".") for p in packages)


def is_private(name: str) -> bool:
    """``_x`` and ``__x`` are private; dunders (``__version__``) and ``_`` are not."""
    dunder = len(name) > 4 and name.startswith("__") and name.endswith("__")
    return name.startswith("_") and not dunder and name.strip("_") != ""


class Reader(ast.NodeVisitor):
    """Collects one module's imports, print() calls and uses of sys.stdout/sys.stderr,
    and the private names it takes from other modules."""

    def __init__(self, name: str, files: dict[str, Path] | None = None) -> None:
        self.name = name
        self.files = FILES if files is None else files
        self.package = (name if self.files[name].name == "__init__.py"
                        else name.rpartition(".")[0])
        self.imports: list[Import] = []
        self.writes: list[Import] = []
        self.privates: list[Private] = []
        self.aliases: dict[str, str] = {}  # local name -> the dyade module bound to it
        self.uses: list[tuple[ast.expr, str, int]] = []  # (module expression, "_x", line)
        self.depth = 0  # function nesting

    def read(self, source: str, filename: str = "<module>") -> Reader:
        """Visit the module's source, then resolve the private names it reads from
        module aliases (an alias may be bound below its use, e.g. in another function)."""
        self.visit(ast.parse(source, filename))
        for expression, name, line in self.uses:
            module = self.module_of(expression)
            if module is not None:
                self.take(module, name, line)
        return self

    def add(self, target: str, node: ast.AST) -> None:
        self.imports.append(Import(target, node.lineno, self.depth > 0))

    def private_module(self, module: str) -> Private | None:
        """The first private part of a module's name, unless this module is inside the
        package that owns it."""
        parts = module.split(".")
        for k, part in enumerate(parts):
            if is_private(part):
                owner = ".".join(parts[:k])
                return None if within(self.name, owner) else Private(owner, part, 0)
        return None

    def take(self, module: str, name: str, line: int) -> None:
        """This module takes ``name`` from the dyade module ``module``."""
        if f"{module}.{name}" in self.files:  # a module of a package
            found = self.private_module(f"{module}.{name}")
            if found is not None:
                self.privates.append(found._replace(line=line))
        elif is_private(name) and module != self.name:
            self.privates.append(Private(module, name, line))

    def module_of(self, node: ast.expr) -> str | None:
        """The dyade module an expression names (``sweep``, ``dyade.linkage.sweep``)."""
        if isinstance(node, ast.Name):
            return self.aliases.get(node.id)
        if isinstance(node, ast.Attribute):
            base = self.module_of(node.value)
            if base is not None and f"{base}.{node.attr}" in self.files:
                return f"{base}.{node.attr}"
        return None

    def nested(self, node: ast.AST) -> None:
        self.depth += 1
        self.generic_visit(node)
        self.depth -= 1

    visit_FunctionDef = visit_AsyncFunctionDef = visit_Lambda = nested

    def visit_Import(self, node: ast.Import) -> None:
        for alias in node.names:
            self.add(alias.name, node)
            if alias.name in self.files:
                found = self.private_module(alias.name)
                if found is not None:
                    self.privates.append(found._replace(line=node.lineno))
            # `import a.b.c` binds a, `import a.b.c as d` binds d
            bound = alias.name if alias.asname else alias.name.partition(".")[0]
            if bound in self.files:
                self.aliases[alias.asname or bound] = bound

    def visit_ImportFrom(self, node: ast.ImportFrom) -> None:
        base = node.module or ""
        if node.level:  # relative: from the module's package, one level up per extra dot
            parts = self.package.split(".")
            parts = parts[:len(parts) - (node.level - 1)]
            base = ".".join(parts + ([node.module] if node.module else []))
        if base in self.files:
            found = self.private_module(base)
            if found is not None:
                self.privates.append(found._replace(line=node.lineno))
        for alias in node.names:
            submodule = f"{base}.{alias.name}"
            # `from dyade.linkage import dyads` imports the module dyade.linkage.dyads
            self.add(submodule if submodule in self.files else base, node)
            if submodule in self.files:
                self.aliases[alias.asname or alias.name] = submodule
            if base in self.files:
                self.take(base, alias.name, node.lineno)
            if base == "sys" and alias.name in ("stdout", "stderr"):
                self.writes.append(Import(submodule, node.lineno, self.depth > 0))

    def visit_Assign(self, node: ast.Assign) -> None:
        # module = importlib.import_module("dyade.x") binds module to dyade.x
        call = node.value
        if (isinstance(call, ast.Call) and call.args and len(node.targets) == 1
                and isinstance(node.targets[0], ast.Name)
                and isinstance(call.args[0], ast.Constant) and call.args[0].value in self.files
                and (isinstance(call.func, ast.Attribute) and call.func.attr == "import_module"
                     or isinstance(call.func, ast.Name) and call.func.id == "import_module")):
            self.aliases[node.targets[0].id] = call.args[0].value
        self.generic_visit(node)

    def visit_Constant(self, node: ast.Constant) -> None:
        # a string that names a dyade module is imported by name (importlib, lazy exports)
        if isinstance(node.value, str) and node.value in self.files:
            self.add(node.value, node)

    def visit_JoinedStr(self, node: ast.JoinedStr) -> None:
        # f"dyade.cli.{name}" imports a module of the package dyade.cli
        first = node.values[0] if node.values else None
        if isinstance(first, ast.Constant) and isinstance(first.value, str):
            prefix = first.value.removesuffix(".")
            if first.value.endswith(".") and MODULE_NAME.fullmatch(prefix) and prefix in self.files:
                self.add(prefix, node)
        self.generic_visit(node)

    def visit_Call(self, node: ast.Call) -> None:
        if isinstance(node.func, ast.Name) and node.func.id == "print":
            self.writes.append(Import("print()", node.lineno, self.depth > 0))
        if (isinstance(node.func, ast.Name) and node.func.id == "getattr"
                and len(node.args) >= 2 and isinstance(node.args[1], ast.Constant)
                and isinstance(node.args[1].value, str) and is_private(node.args[1].value)):
            self.uses.append((node.args[0], node.args[1].value, node.lineno))
        self.generic_visit(node)

    def visit_Attribute(self, node: ast.Attribute) -> None:
        if (isinstance(node.value, ast.Name) and node.value.id == "sys"
                and node.attr in ("stdout", "stderr", "__stdout__", "__stderr__")):
            self.writes.append(Import(f"sys.{node.attr}", node.lineno, self.depth > 0))
        if is_private(node.attr):
            self.uses.append((node.value, node.attr, node.lineno))
        self.generic_visit(node)


def read_tree(root: Path, package: Path) -> dict[str, Reader]:
    """Every module of the package directory ``package`` (under ``root``), read."""
    files = tree_files(root, package)
    return {name: Reader(name, files).read(path.read_text(encoding="utf-8"), str(path))
            for name, path in files.items()}


MODULES = read_tree(ROOT, PACKAGE)


CLI = ("dyade.cli",)
REPORT = ("dyade.report",)
PLOT = ("dyade.plot",)
COMPOSER = "dyade.report.html"
"""the design report (issue 29) composes tables and figures: above report and plot both"""
BASE = ("dyade.units", "dyade.errors", "dyade.arrays", "dyade.limits")
"""the foundation: unit factors, errors, array types, size limits; they import each other only"""
MODEL = ("dyade.model",)
"""the data files describe (mechanism, drive, drive line, coupling, gear drive): imports only
units, errors, arrays and itself"""
READERS = ("dyade.files",)
"""the readers: import only the base and the model (no engine)"""
ENGINE = ("dyade.linkage", "dyade.machine", "dyade.vibration", "dyade.clearance",
          "dyade.motion")
SYNTHESIS = ("dyade.synthesis",)
"""dimensional synthesis: above the engine and the readers (it builds its candidates'
mechanisms from file data), below the analyses (the ``synthesis`` entry)"""
ANALYSES = ("dyade.analyses",)
"""the contract and its entries: above the engine and the readers, below cli, report, plot
and study"""
STUDY = ("dyade.study",)
REGISTRY = "dyade.registry"
"""the one registry of every command's entry: the analyses and the study's entry (which
evaluates the others); above the study, below cli, report and plot"""
PLOTTING = ("matplotlib",)

FACADE = "dyade"
"""``dyade/__init__.py``: re-exports the API (lazily, by name), so it sits above every
module it names; cli, report and plot may import it (``__version__``), nothing below."""

ENTRY_POINT = "dyade.__main__"
"""``python -m dyade``: the command line's second door, one line forwarding to
``dyade.cli.main``; it may import dyade.cli and nothing else does."""

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
        lambda name: within(name, *REPORT, *PLOT) and name != COMPOSER,
        lambda name, imp: (within(imp.target, *PLOT) and within(name, *REPORT)
                           or within(imp.target, *REPORT) and within(name, *PLOT)),
        "is in report or plot and imports the other (both read the API's results)"),
    "the dyad kinds know no file syntax": (
        lambda name: within(name, "dyade.linkage.dyads"),
        lambda name, imp: within(imp.target, "dyade.files"),
        "is a dyad kind (geometry and mechanics) and imports dyade.files; the keys of a "
        "kind are read by dyade.files.mechanism.dyads"),
    "units, errors, arrays, limits import only each other": (
        # every dyade module outside the base is above it: the package facade, the model,
        # the API, dyade.parallel and any module added later alike
        lambda name: within(name, *BASE),
        lambda name, imp: within(imp.target, FACADE) and not within(imp.target, *BASE),
        "is a base module and imports a layer above it"),
    "the model imports only units, errors, arrays and itself": (
        lambda name: within(name, *MODEL),
        lambda name, imp: (within(imp.target, FACADE) and not within(
            imp.target, "dyade.units", "dyade.errors", "dyade.arrays", *MODEL)),
        "is the model (the data files describe) and imports more than units, errors, arrays "
        "and the model: the engine computes on the model, never the other way"),
    "the readers import only the base and the model": (
        lambda name: within(name, *READERS),
        lambda name, imp: (within(imp.target, FACADE)
                           and not within(imp.target, *BASE, *MODEL, *READERS)),
        "is a reader (dyade.files) and imports a layer above the model: a reader builds "
        "the model's objects and computes nothing"),
    "the engine reads no file and runs no analysis": (
        lambda name: within(name, *ENGINE),
        lambda name, imp: within(imp.target, *READERS, *SYNTHESIS, *ANALYSES, *STUDY),
        "is the engine and imports a reader, an analysis entry or the study: the caller "
        "reads the file (dyade.files) and hands the engine the model"),
    "the synthesis sits above the engine and the readers, below the analyses": (
        lambda name: within(name, *SYNTHESIS),
        lambda name, imp: within(imp.target, *ANALYSES, *CLI, *REPORT, *PLOT, *STUDY),
        "is the synthesis and imports an analysis entry, the command line, a writer, a "
        "figure or the study, which are above it"),
    "analyses sit below cli, report, plot and study": (
        lambda name: within(name, *ANALYSES),
        lambda name, imp: within(imp.target, *CLI, *REPORT, *PLOT, *STUDY),
        "is an analysis entry and imports the command line, a writer, a figure or the "
        "study, which are above it"),
    "only cli, report, plot and the facade look up the registry": (
        lambda name: not within(name, *CLI, *REPORT, *PLOT) and name not in (
            FACADE, ENTRY_POINT, REGISTRY),
        lambda name, imp: imp.target == REGISTRY,
        "imports dyade.registry, which names every entry, the study's too: from below the "
        "study that points up (an analysis entry imports the module it needs)"),
    "the registry sits above the study and below cli, report and plot": (
        lambda name: name == REGISTRY,
        lambda name, imp: within(imp.target, *CLI, *REPORT, *PLOT),
        "is the registry and imports the command line, a writer or a figure"),
    "only cli, report and plot import the package facade": (
        lambda name: not within(name, *CLI, *REPORT, *PLOT) and name not in (FACADE, ENTRY_POINT),
        lambda name, imp: imp.target == FACADE,
        "imports dyade/__init__.py, the facade that re-exports the whole API: from below "
        "it, that points up (import the defining module instead)"),
}


def _where(name: str, imp: Import) -> str:
    inside = " (in a function)" if imp.in_function else ""
    return f"{FILES[name].relative_to(ROOT)}:{imp.line}: {imp.target}{inside}"


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
    assert "dyade.model.dyad_kinds" in found["dyade.files.mechanism.dyads"]  # from pkg import module
    assert "rich.progress" in found["dyade.cli.output"]                    # inside a function
    assert "matplotlib.figure" in found["dyade.plot.polar"]                # a plot module
    assert "dyade.cli" in found["dyade.cli"]                               # importlib f-string
    assert "dyade.linkage.dyads" in found["dyade.linkage.dyads"]           # ... of its own package
    assert "dyade.linkage.sweep" in found["dyade"]                         # lazy export by name
    assert "dyade.model.mechanism" in found["dyade"]
    # the model's types under TYPE_CHECKING count (the mechanism names its drive's data)
    assert {"dyade.model.drive", "dyade.model.drive_line"} <= found["dyade.model.mechanism"]
    coupling = [imp for imp in MODULES["dyade.files.coupling"].imports
                if imp.target == "dyade.model.coupling"]
    assert coupling and all(imp.in_function for imp in coupling)
    assert "dyade.files.torque_curve" in found["dyade.analyses.torque_curve"]
    assert any(imp.target == "sys.stdout" for imp in MODULES["dyade.cli.output"].writes)


def test_relative_imports_are_resolved():
    reader = Reader("dyade.linkage.dyads")
    reader.visit(ast.parse("from . import rrr\nfrom ..kinematics import Motion\n"
                           "from .. import sweep\nfrom ...errors import InputError\n"))
    assert [imp.target for imp in reader.imports] == [
        "dyade.linkage.dyads.rrr", "dyade.linkage.kinematics", "dyade.linkage.sweep",
        "dyade.errors"]


# -- circles and private imports (issue 25) -------------------------------------------------
Graph = dict[str, dict[str, list[int]]]
"""module -> {imported module: the lines that import it}"""


def import_graph(modules: dict[str, Reader]) -> Graph:
    """The imports between the modules read, a module's imports of itself left out."""
    graph: Graph = {name: {} for name in modules}
    for name, module in modules.items():
        for imp in module.imports:
            if imp.target in modules and imp.target != name:
                lines = graph[name].setdefault(imp.target, [])
                if imp.line not in lines:
                    lines.append(imp.line)
    return graph


def _path(graph: Graph, start: str, goal: str) -> list[str] | None:
    """The shortest chain of imports from ``start`` to ``goal`` (breadth first, in name
    order, so that the answer does not depend on the order of the files)."""
    before = {start: start}
    queue = deque([start])
    while queue:
        node = queue.popleft()
        if node == goal:
            path = [goal]
            while path[-1] != start:
                path.append(before[path[-1]])
            return path[::-1]
        for nxt in sorted(graph.get(node, ())):
            if nxt not in before:
                before[nxt] = node
                queue.append(nxt)
    return None


def circles(graph: Graph) -> list[tuple[str, ...]]:
    """The circles of an import graph: for every import ``a -> b`` that lies on one, the
    shortest circle through it, as its modules from the smallest name on (``(a, b)`` is
    ``a -> b -> a``); each circle once, shortest first."""
    found: set[tuple[str, ...]] = set()
    for a in graph:
        for b in graph[a]:
            back = _path(graph, b, a)
            if back is not None:
                cycle = [a] + back[:-1]
                k = cycle.index(min(cycle))
                found.add(tuple(cycle[k:] + cycle[:k]))
    return sorted(found, key=lambda cycle: (len(cycle), cycle))


def home(modules: dict[str, Reader], names) -> str:
    """The innermost package that holds all of ``names`` (a package's ``__init__`` is in
    the package itself)."""
    parts = [modules[n].package.split(".") for n in names]
    common = []
    for level in zip(*parts):
        if len(set(level)) > 1:
            break
        common.append(level[0])
    return ".".join(common)


def _file(modules: dict[str, Reader], name: str, root: Path) -> str:
    return str(modules[name].files[name].relative_to(root))


def circle_offences(modules: dict[str, Reader], root: Path = ROOT) -> dict[str, list[str]]:
    """Package -> its circles, each as ``a -> b -> a`` and the file:line of each import."""
    graph = import_graph(modules)
    out: dict[str, list[str]] = {}
    for cycle in circles(graph):
        edges = list(zip(cycle, cycle[1:] + cycle[:1]))
        text = " -> ".join(cycle + cycle[:1]) + "".join(
            f"\n      {_file(modules, a, root)}:{', '.join(map(str, sorted(graph[a][b])))}"
            f" imports {b}" for a, b in edges)
        out.setdefault(home(modules, cycle), []).append(text)
    return out


def private_offences(modules: dict[str, Reader], root: Path = ROOT) -> dict[str, list[str]]:
    """Package -> ``file:line: owner._name`` for each private name taken across modules,
    under the innermost package of the module that takes it."""
    out: dict[str, list[str]] = {}
    for name, module in sorted(modules.items()):
        for private in sorted(set(module.privates), key=lambda p: (p.line, p.owner, p.name)):
            out.setdefault(module.package, []).append(
                f"{_file(modules, name, root)}:{private.line}: {private.owner}.{private.name}")
    return out


PACKAGES = sorted(name for name, path in FILES.items() if path.name == "__init__.py")
CIRCLES = circle_offences(MODULES)
PRIVATES = private_offences(MODULES)


@pytest.mark.parametrize("package", PACKAGES)
def test_no_circle_inside_a_package(package):
    found = CIRCLES.get(package, [])
    assert not found, (f"{package}: {len(found)} import circle(s); cut one import of each "
                       "(a module that two need goes below both):\n  " + "\n  ".join(found))


@pytest.mark.parametrize("package", PACKAGES)
def test_no_private_import_across_modules(package):
    found = PRIVATES.get(package, [])
    assert not found, (f"{package}: {len(found)} private name(s) of another module taken "
                       "(make it public, or move the code that needs it into its module):\n  "
                       + "\n  ".join(found))


def test_every_circle_and_private_import_has_a_package():
    # the parametrised tests above see only the packages they are given
    assert set(CIRCLES) <= set(PACKAGES) and set(PRIVATES) <= set(PACKAGES)


# the checks on small trees: each finds what it must, and passes a clean tree
def test_circles_of_a_graph():
    assert circles({"a": {"b": [1]}, "b": {"c": [1]}, "c": {"a": [1]}, "d": {"a": [1]}}) \
        == [("a", "b", "c")]
    # two circles sharing a module; the import a -> d closes none
    assert circles({"a": {"b": [1], "d": [2]}, "b": {"a": [1], "c": [1]}, "c": {"b": [1]},
                    "d": {}}) == [("a", "b"), ("b", "c")]
    # a -> b closes the long circle only; c -> a and a -> c the short one
    assert circles({"a": {"b": [1], "c": [1]}, "b": {"c": [1]}, "c": {"a": [1]}}) \
        == [("a", "c"), ("a", "b", "c")]
    assert circles({"a": {"b": [1], "c": [1]}, "b": {"c": [1]}, "c": {}}) == []


def _tree(tmp_path: Path, files: dict[str, str]) -> dict[str, Reader]:
    for relative, text in files.items():
        path = tmp_path / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    return read_tree(tmp_path, tmp_path / "pkg")


CLEAN = {
    # the usual shape: the __init__ re-exports its modules, which import each other one
    # way (a -> b -> c), a sub-package imports up, privates stay home
    "pkg/__init__.py": "from pkg.a import run\nfrom pkg import b\n",
    "pkg/a.py": "from pkg.b import helper\nimport pkg.c\n\n\ndef run():\n"
                "    return helper() + pkg.c.VALUE + _own()\n\n\ndef _own():\n    return 1\n",
    "pkg/b.py": "from __future__ import annotations\nfrom typing import TYPE_CHECKING\n"
                "from . import c\nif TYPE_CHECKING:\n    from pkg.sub.d import D\n\n\n"
                "def helper(d: D | None = None):\n    return c.VALUE + c.__name__.count('.')\n",
    "pkg/c.py": "VALUE = 1\n__version__ = '1'\n_ = None\n",
    "pkg/sub/__init__.py": "",
    "pkg/sub/d.py": "from pkg.c import VALUE as _VALUE, __version__\nfrom ._e import f\n\n\n"
                    "class D:\n    _slot = _VALUE\n\n    def g(self):\n        return self._slot\n",
    "pkg/sub/_e.py": "def f():\n    return 2\n",
}


def test_a_clean_tree_passes(tmp_path):
    modules = _tree(tmp_path, CLEAN)
    assert circle_offences(modules, tmp_path) == {}
    assert private_offences(modules, tmp_path) == {}


def test_a_circle_is_found_with_file_and_line(tmp_path):
    modules = _tree(tmp_path, {
        **CLEAN,
        # c imports a in a function, a circle a -> c -> a beside a -> b -> c -> a
        "pkg/c.py": "VALUE = 1\n\n\ndef late():\n    from pkg.a import run\n    return run\n",
    })
    # one circle per import on one: a -> c, then a -> b and b -> c, then b -> sub.d and
    # sub.d -> c (b imports pkg.sub.d for annotations, d imports c)
    assert circle_offences(modules, tmp_path) == {"pkg": [
        "pkg.a -> pkg.c -> pkg.a\n      pkg/a.py:2 imports pkg.c\n      pkg/c.py:5 imports pkg.a",
        "pkg.a -> pkg.b -> pkg.c -> pkg.a\n      pkg/a.py:1 imports pkg.b\n"
        "      pkg/b.py:3 imports pkg.c\n      pkg/c.py:5 imports pkg.a",
        "pkg.a -> pkg.b -> pkg.sub.d -> pkg.c -> pkg.a\n      pkg/a.py:1 imports pkg.b\n"
        "      pkg/b.py:5 imports pkg.sub.d\n      pkg/sub/d.py:1 imports pkg.c\n"
        "      pkg/c.py:5 imports pkg.a"]}


def test_a_circle_through_the_package_init_is_found(tmp_path):
    # a module importing its own package's __init__, which imports it
    modules = _tree(tmp_path, {**CLEAN, "pkg/c.py": "from pkg import run\nVALUE = 1\n"})
    assert [text.partition("\n")[0] for text in circle_offences(modules, tmp_path)["pkg"]] \
        == ["pkg -> pkg.a -> pkg.c -> pkg", "pkg -> pkg.b -> pkg.c -> pkg",
            "pkg -> pkg.a -> pkg.b -> pkg.c -> pkg", "pkg -> pkg.b -> pkg.sub.d -> pkg.c -> pkg"]


def test_a_circle_of_type_checking_imports_across_a_sub_package_is_found(tmp_path):
    # pkg.sub.d -> pkg.c only for annotations, pkg.c -> pkg.sub.d at run time: a circle
    # that crosses the sub-package belongs to the package holding both, pkg
    modules = _tree(tmp_path, {
        **CLEAN,
        "pkg/c.py": "from pkg.sub.d import D\nVALUE = 1\n",
        "pkg/sub/d.py": "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n"
                        "    from pkg import c\n\n\nclass D:\n    pass\n",
    })
    found = circle_offences(modules, tmp_path)
    assert list(found) == ["pkg"]
    assert found["pkg"][0] == ("pkg.c -> pkg.sub.d -> pkg.c\n      pkg/c.py:1 imports pkg.sub.d"
                               "\n      pkg/sub/d.py:3 imports pkg.c")
    # ... and one inside the sub-package belongs to the sub-package
    modules = _tree(tmp_path, {**CLEAN, "pkg/sub/_e.py": "from pkg.sub import d\n"})
    assert [text.partition("\n")[0] for text in circle_offences(modules, tmp_path)["pkg.sub"]] \
        == ["pkg.sub._e -> pkg.sub.d -> pkg.sub._e"]


def test_private_imports_are_found_with_file_and_line(tmp_path):
    modules = _tree(tmp_path, {
        **CLEAN,
        "pkg/__init__.py": "from pkg.a import run\nfrom .c import _hidden\n",  # re-export: no
        "pkg/c.py": "VALUE = 1\n_hidden = 2\n__x = 3\n",
        "pkg/user.py": (
            "import importlib\n"
            "import pkg.c\n"
            "import pkg.c as see\n"
            "from pkg import c\n"
            "from pkg.c import VALUE, _hidden\n"              # 5
            "from .c import __x as x\n"                        # 6
            "from pkg.sub import _e\n"                         # 7: a private module
            "from pkg.sub._e import f\n"                       # 8: the same, from outside
            "\n\n"
            "def use():\n"
            "    later = importlib.import_module('pkg.c')\n"  # 12
            "    return (c._hidden, see._hidden, pkg.c._hidden, later._hidden,\n"  # 13
            "            getattr(c, '_hidden'), c.__name__, c.VALUE)\n"             # 14
            "import pkg.sub._e\n"                                                  # 15
        ),
    })
    assert private_offences(modules, tmp_path) == {"pkg": [
        "pkg/__init__.py:2: pkg.c._hidden",
        "pkg/user.py:5: pkg.c._hidden",
        "pkg/user.py:6: pkg.c.__x",
        "pkg/user.py:7: pkg.sub._e",
        "pkg/user.py:8: pkg.sub._e",
        "pkg/user.py:13: pkg.c._hidden",   # four reads on one line, listed once
        "pkg/user.py:14: pkg.c._hidden",
        "pkg/user.py:15: pkg.sub._e",
    ]}
    assert len([p for p in modules["pkg.user"].privates if p.line == 13]) == 4


def test_the_upward_rules_catch_any_module_above():
    base = RULES["units, errors, arrays, limits import only each other"]
    model = RULES["the model imports only units, errors, arrays and itself"]
    readers = RULES["the readers import only the base and the model"]
    engine = RULES["the engine reads no file and runs no analysis"]
    analyses = RULES["analyses sit below cli, report, plot and study"]
    facade = RULES["only cli, report and plot import the package facade"]
    above_model = ("dyade", "dyade.parallel", "dyade.linkage.sweep", "dyade.machine.motor",
                   "dyade.vibration.coupling", "dyade.analyses.base", "dyade.new_module")
    for target in above_model + ("dyade.files.schema", "dyade.model.mechanism"):
        assert base[1]("dyade.units", Import(target, 1, True)), target
    assert not base[1]("dyade.limits", Import("dyade.errors", 1, False))
    for target in above_model + ("dyade.files.schema", "dyade.limits"):
        assert model[0]("dyade.model.drive") and model[1]("dyade.model.drive",
                                                          Import(target, 1, True)), target
    for target in ("dyade.units", "dyade.errors", "dyade.arrays", "dyade.model.dyad_kinds",
                   "numpy"):
        assert not model[1]("dyade.model.mechanism", Import(target, 1, False)), target
    for target in above_model:
        assert readers[0]("dyade.files.mechanism.dyads") and readers[1](
            "dyade.files.mechanism.dyads", Import(target, 1, True)), target
    for target in ("dyade.units", "dyade.limits", "dyade.model.mechanism", "dyade.files.schema"):
        assert not readers[1]("dyade.files.mechanism", Import(target, 1, False)), target
    for name in ("dyade.linkage.sweep", "dyade.machine.flywheel", "dyade.vibration.gears.modes",
                 "dyade.clearance"):
        assert engine[0](name), name
        for target in ("dyade.files.torque_curve", "dyade.analyses", "dyade.study.run"):
            assert engine[1](name, Import(target, 1, True)), (name, target)
        assert not engine[1](name, Import("dyade.model.mechanism", 1, False))
    assert not engine[0]("dyade.analyses.coupling") and not engine[0]("dyade.files.gears")
    for target in ("dyade.cli.contract", "dyade.report.outcome", "dyade.plot.curves",
                   "dyade.study.run"):
        assert analyses[1]("dyade.analyses.coupling", Import(target, 1, True)), target
    for target in ("dyade.linkage.sweep", "dyade.files.coupling", "dyade.model.coupling"):
        assert not analyses[1]("dyade.analyses.coupling", Import(target, 1, True)), target
    assert facade[0]("dyade.linkage.sweep") and facade[1]("dyade.linkage.sweep",
                                                          Import("dyade", 1, True))
    assert facade[0]("dyade.model.mechanism") and facade[0]("dyade.analyses.base")
    assert not facade[0]("dyade.report.document") and not facade[0]("dyade")


# -- tests/ mirrors the package (issue 36) -----------------------------------------------
TEST_ONLY = {"benchmarks", "golden"}
"""folders of tests/ that mirror no package: the speed runs and the golden run"""


def test_the_tests_mirror_the_package_folder_by_folder():
    tests = ROOT / "tests"
    packages = {path.parent.relative_to(PACKAGE) for path in PACKAGE.rglob("__init__.py")}
    top = {p for p in packages if len(p.parts) == 1}
    missing = sorted(str(p) for p in top if not (tests / p).is_dir())
    assert not missing, f"tests/ has no folder for the packages {missing}"
    astray = sorted(str(path.relative_to(tests)) for path in tests.rglob("test_*.py")
                    if path.parent != tests
                    and path.parent.relative_to(tests).parts[0] not in TEST_ONLY
                    and path.parent.relative_to(tests) not in packages)
    assert not astray, f"test modules in folders that mirror no package folder: {astray}"
    top_level = {path.stem.removeprefix("test_") for path in tests.glob("test_*.py")}
    modules = {path.stem for path in PACKAGE.glob("*.py")} | {"api", "docs", "doctests",
                                                              "readme", "layers"}
    assert top_level <= modules, (f"top-level tests of no top-level module: "
                                  f"{sorted(top_level - modules)}")
