"""Output discipline shared by the commands.

Results go to stdout or ``-o``; diagnostics to stderr. Piped output, and any output under
``NO_COLOR``, is plain: no colour and no box-drawing characters. Files are written to a
temporary file beside the target and renamed on success, so an interrupted or failed
run never leaves a half-written result.
"""

from __future__ import annotations

import os
import sys
from contextlib import contextmanager
from typing import Any, Iterable, Iterator, TextIO


def plain(stream: TextIO | None = None) -> bool:
    """True when output must carry no colour and no box characters."""
    stream = stream or sys.stdout
    return "NO_COLOR" in os.environ or not stream.isatty()


def console(stderr: bool = False, file: TextIO | None = None, width: int | None = None):
    from rich.console import Console

    stream = file or (sys.stderr if stderr else sys.stdout)
    is_plain = plain(stream)
    if is_plain and width is None and "COLUMNS" not in os.environ:
        width = 160  # piped: wide enough for the tables; messages are not wrapped at all
    return Console(file=stream, highlight=False, no_color=is_plain,
                   color_system=None if is_plain else "auto", width=width,
                   emoji=False, soft_wrap=is_plain and stderr)


class atomic:
    """Write to a temporary file beside ``path``, rename on success, remove on failure.
    A missing folder of ``path`` is created (one rule for -o, --save-as and init); a
    target that cannot be written is an InputError naming it (exit 2); "-" is standard
    output."""

    def __init__(self, path: str | os.PathLike) -> None:
        self.path = os.fspath(path)
        self.folder, name = os.path.split(self.path)
        self.tmp = os.path.join(self.folder, f".{name}.part")

    def __enter__(self) -> TextIO:
        from dyade.errors import InputError

        if self.path == "-":  # standard output: nothing to create, rename or remove
            self.handle = sys.stdout
            return self.handle
        try:
            if self.folder:
                os.makedirs(self.folder, exist_ok=True)
            self.handle = open(self.tmp, "w", encoding="utf-8", newline="")
        except (FileExistsError, NotADirectoryError):
            raise InputError(f"{self.path}: cannot write the file: a part of its folder "
                             f"{self.folder} is a file, not a folder.",
                             source=self.path) from None
        except OSError as err:
            raise InputError(f"{self.path}: cannot write the file ({err.strerror}).",
                             source=self.path) from None
        return self.handle

    def __exit__(self, exc_type, exc, tb) -> None:
        if self.path == "-":
            return
        self.handle.close()
        if exc_type is None:
            os.replace(self.tmp, self.path)
        else:
            try:
                os.remove(self.tmp)
            except FileNotFoundError:
                pass


def to_file(output: str | os.PathLike | None) -> bool:
    """Whether an output option names a file: not when absent, nor for "-" (standard
    output), one rule for every command's -o and --save-as."""
    return bool(output) and os.fspath(output) != "-"


def _plain_renderable(part: Any) -> Any:
    """Tables without box characters, trees as indented text."""
    from rich.table import Table
    from rich.text import Text
    from rich.tree import Tree

    if isinstance(part, Table):
        part.box = None
        part.show_edge = False
        part.pad_edge = False
        return part
    if isinstance(part, Tree):
        lines: list[str] = []

        def walk(node: Tree, depth: int) -> None:
            label = node.label if isinstance(node.label, str) else str(node.label)
            lines.append("  " * depth + Text.from_markup(label).plain)
            for child in node.children:
                walk(child, depth + 1)

        walk(part, 0)
        return Text("\n".join(lines))  # already plain: no second markup pass
    return part


def literal(table: Any) -> Any:
    """A table whose texts are shown as written: rich would read "[rpm]" or "[ms]" in a
    header as markup and drop it. Its title, caption, headers and cells are escaped."""
    from rich.markup import escape
    from rich.table import Table

    if not isinstance(table, Table):
        return table
    for name in ("title", "caption"):
        if isinstance(getattr(table, name), str):
            setattr(table, name, escape(getattr(table, name)))
    for column in table.columns:
        column.overflow = "fold"  # a narrow terminal wraps a value, never cuts it ("3.5…")
        if isinstance(column.header, str):
            column.header = escape(column.header)
        column._cells = [escape(c) if isinstance(c, str) else c for c in column._cells]
    return table


def show(parts: Iterable[Any], output: str | os.PathLike | None = None, width: int | None = None) -> None:
    """Print rich renderables to stdout or (atomically) to a file."""
    parts = [literal(p) for p in parts if p is not None]
    if to_file(output):
        with atomic(output) as handle:
            con = console(file=handle, width=width or 160)
            con.print(*[_plain_renderable(p) for p in parts])
        return
    con = console(width=width)
    if plain():
        parts = [_plain_renderable(p) for p in parts]
    con.print(*parts)


def write_json(obj: dict, output: str | os.PathLike | None) -> None:
    """The document as ``json.dumps(jsonable(obj), indent=1)`` writes it; columns that
    are float arrays (a sweep's, perhaps spooled on disk) are written a column and a
    block of values at a time, in the same text (``report.document.write_columns``)."""
    import json  # only here: the import is not free

    from dyade.analyses.base import jsonable

    def emit(handle) -> None:
        if _arrays_first(obj):
            from dyade.report.document import write_columns

            rest = json.dumps(jsonable({k: v for k, v in obj.items() if k != "columns"}),
                              ensure_ascii=False, indent=1)
            handle.write("{\n")
            write_columns(obj["columns"], handle)
            handle.write(",\n" + rest[2:] + "\n" if rest != "{}" else "\n}\n")
        else:
            handle.write(json.dumps(jsonable(obj), ensure_ascii=False, indent=1) + "\n")

    if to_file(output):
        with atomic(output) as handle:
            emit(handle)
    else:
        emit(sys.stdout)


def _arrays_first(obj: dict) -> bool:
    """A document whose first entry is its columns, each a float array."""
    import numpy as np

    columns = next(iter(obj.values()), None) if next(iter(obj), None) == "columns" else None
    if getattr(columns, "float_columns", False):  # a Spool: no need to read them to know
        return True
    return columns is not None and not isinstance(columns, (list, tuple)) and all(
        isinstance(values, np.ndarray) and values.dtype == np.float64 and values.ndim == 1
        for values in (columns[name] for name in columns))


@contextmanager
def flags(names: dict[str, str]) -> Iterator[None]:
    """Name the API's parameters as the user gave them in errors raised inside:
    ``names`` maps a parameter to its flag (``{"inertia": "--J"}``) or file key."""
    from dyade.errors import InputError

    try:
        yield
    except InputError as err:
        from dyade.cli.options import as_given  # a former name typed: the message says so

        raise err.naming({api: as_given(flag) for api, flag in names.items()}) from None


@contextmanager
def progress(description: str, total: float | None = None, show: bool = True
             ) -> Iterator[Any]:
    """A transient progress bar on stderr while a long run goes on, only when stderr is
    a terminal (and ``show``); yields ``tick(done, total=None)`` with ``tick.note(text)``
    (words after the description, how it goes), which do nothing otherwise. The commands show it for runs expected to take more than about a second.
    The bar (and its refresh thread) starts at the first tick: the worker processes of
    ``-j`` are forked before, from a process without threads."""
    if not show or not sys.stderr.isatty():
        def idle(done: float, total: float | None = None) -> None:
            return None

        idle.note = lambda text: None  # type: ignore[attr-defined]
        yield idle
        return
    from rich.progress import Progress

    bar = Progress(console=console(stderr=True), transient=True)
    task = bar.add_task(description, total=total)
    started = False

    def tick(done: float, new_total: float | None = None) -> None:
        nonlocal started
        if not started:  # the bar's refresh thread starts here, after any fork of -j
            bar.start()
            started = True
        bar.update(task, completed=done, **({} if new_total is None else {"total": new_total}))

    def note(text: str) -> None:  # how it goes (a rate, a best error so far)
        if started:
            bar.update(task, description=f"{description}: {text}")

    tick.note = note  # type: ignore[attr-defined]

    try:
        yield tick
    finally:
        if started:
            bar.stop()

