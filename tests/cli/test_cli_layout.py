"""The command line's layout (issue 25): one idea per module. No command module is
another's library (what commands share lives in common, options, batch, writers,
output), the imports inside dyade/cli form no circle, and no module there imports
another's private names. (Read with ``ast`` by tests/test_layers.py, not imported.)"""

from __future__ import annotations

import ast

from tests.test_layers import FILES, MODULES, within

CLI = sorted(name for name in MODULES if within(name, "dyade.cli"))
EDGES = {name: {imp.target for imp in MODULES[name].imports
                if within(imp.target, "dyade.cli") and imp.target != name} for name in CLI}


def test_no_command_module_imports_analyse():
    offences = [f"{name}:{imp.line} imports dyade.cli.analyse" for name in CLI
                for imp in MODULES[name].imports if imp.target == "dyade.cli.analyse"]
    assert not offences, offences


def test_no_circle_inside_the_cli():
    """Depth-first search for a path back to where it started (the group's lazy import
    of its commands by name is an edge from dyade.cli to itself, left out)."""
    circles = []

    def visit(name: str, path: list[str]) -> None:
        for target in sorted(EDGES.get(name, ())):
            if target == path[0]:
                circles.append(" -> ".join(path + [target]))
            elif target not in path and target in EDGES:
                visit(target, path + [target])

    for name in CLI:
        visit(name, [name])
    assert not circles, circles[:5]


def test_no_private_name_is_imported_across_cli_modules():
    offences = []
    for name in CLI:
        tree = ast.parse(FILES[name].read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("dyade"):
                offences += [f"{name}:{node.lineno} imports {node.module}.{alias.name}"
                             for alias in node.names
                             if alias.name.startswith("_") and not alias.name.endswith("__")]
    assert not offences, offences
