"""The output of a figure command: -o, --format, --show and --dpi, where the figure goes
(``Target``) and how it is written or shown."""

from __future__ import annotations

import os
from typing import NamedTuple

import click

from dyade.cli.output import console

FORMATS = ("png", "svg", "pdf")

def output_options(default_format: str | None = "png"):
    """-o, --format, --show and --dpi, shared by every figure command."""
    def decorate(command):
        options = [
            click.option("-o", "--output", type=click.Path(allow_dash=True),
                         help="Write the figure to this file, its format from the suffix (a "
                              "missing folder is created; -: standard output, in --format); "
                              "with several mechanism files a directory (NAME-KIND.FORMAT "
                              "each)."),
            click.option("--show", is_flag=True,
                         help="Open the figure in a window (needs a display); with -o as "
                              "well, write it too."),
            click.option("--dpi", type=click.IntRange(min=20, max=1200), default=None,
                         metavar="N",
                         help="Resolution of a PNG or GIF [dots per inch]  [default: 100 for "
                              "PNG and GIF]."),
        ]
        if default_format:
            options.insert(1, click.option(
                "--format", "fmt", type=click.Choice(FORMATS), default=None,
                help=f"Format when -o names no file with a suffix (a directory, or no -o)  "
                     f"[default: {default_format}]."))
        for option in reversed(options):
            command = option(command)
        return command
    return decorate


class Target(NamedTuple):
    """Where a figure goes: a file (None: only a window) and whether to show it."""

    path: str | None
    show: bool
    dpi: int | None
    fmt: str | None = None
    """the format of a figure on standard output (path "-")"""


def prepare(show: bool) -> None:
    """matplotlib is there (else exit 2 naming the extra); a window can open for --show."""
    from dyade.plot import require

    require()
    if show and os.name == "posix" and not (os.environ.get("DISPLAY")
                                            or os.environ.get("WAYLAND_DISPLAY")
                                            or os.uname().sysname == "Darwin"):
        raise click.UsageError("--show needs a display (DISPLAY is not set); write the figure "
                               "with -o FILE instead.")


def stem(path: str) -> str:
    """The name a figure of input ``path`` is named after ("-": stdin)."""
    return "stdin" if path == "-" else os.path.splitext(os.path.basename(path))[0]


def suffix_format(path: str, allowed: tuple[str, ...]) -> str:
    fmt = os.path.splitext(path)[1].lower().lstrip(".")
    if fmt not in allowed:
        raise click.BadParameter(f"{path}: the format comes from the suffix, one of "
                                 f"{', '.join('.' + a for a in allowed)}.", param_hint="-o")
    return fmt


def emit(fig, target: Target, announce: bool) -> None:
    """Write the figure when it has a file (its format from the suffix)."""
    from dyade.plot import canvas

    if target.path == "-":  # standard output: the bytes of the format asked for
        import sys

        sys.stdout.buffer.write(canvas.render(fig, target.fmt or "png", target.dpi or 100))
        sys.stdout.flush()
    elif target.path:
        canvas.save(fig, target.path, target.dpi or 100)
        if announce:
            console(stderr=True).print(f"wrote {target.path}")


def figure_for(target: Target, size: tuple[float, float] = (7.0, 5.0)):
    """A window's figure for --show, else None (the plot module makes its own)."""
    if not target.show:
        return None
    from dyade.plot import canvas

    return canvas.window(*size)


def single_target(output: str | None, fmt: str | None, show: bool, dpi: int | None,
                   name: str) -> tuple[Target, bool]:
    """The target of a figure from options or a file (one figure)."""
    prepare(show)
    if output == "-":
        return Target("-", show, dpi, fmt or "png"), False
    if output and os.path.isdir(output):
        output = os.path.join(output, f"{name}.{fmt or 'png'}")
    elif output:
        suffix_format(output, FORMATS)
    elif not show:
        return Target(f"{name}.{fmt or 'png'}", show, dpi), True
    return Target(output, show, dpi), False


def finish(fig, target: Target, announce: bool) -> None:
    emit(fig, target, announce)
    if target.show:
        from dyade.plot import canvas

        canvas.show()
