"""The ``dyade`` command: a thin shell over the API (``dyade``).

Each command parses its options, calls the API and hands the result to ``dyade.report``.

Exit codes: 0 success, 1 analysis problem (``DyadeError``), 2 bad input or usage
(``InputError`` and click's usage errors). Heavy modules (numpy, rich) are imported
inside the commands, so that ``dyade --help`` stays fast.
"""

from __future__ import annotations

import errno
import sys

import click

from dyade import __version__

SUBCOMMANDS = {"describe": "describe", "analyse": "analyse", "init": "init",
               "clearance": "clearance", "coupling": "coupling", "accuracy": "accuracy",
               "flywheel": "machine", "balance": "machine",
               "plot": "plot", "gears": "gears", "driveline": "driveline",
               "study": "study", "report": "report", "profile": "profile",
               "servo": "servo", "synthesise": "synthesise", "cam": "cam", "help": "help"}
"""command -> module of dyade.cli that defines it, imported when the command is used
(or listed by --help), so that a run pays only for its own command"""


class DyadeGroup(click.Group):
    """Maps dyade's exceptions to click's exit codes, in one place; loads subcommands
    lazily."""

    def list_commands(self, ctx: click.Context) -> list[str]:
        return sorted(SUBCOMMANDS)

    def get_command(self, ctx: click.Context, name: str) -> click.Command | None:
        if name in SUBCOMMANDS and name not in self.commands:
            import importlib

            importlib.import_module(f"dyade.cli.{SUBCOMMANDS[name]}")
        return super().get_command(ctx, name)

    def resolve_command(self, ctx: click.Context, args: list[str]):
        """A misspelt command gets "Did you mean" (``dyade analyze``: analyse)."""
        name = args[0] if args else ""
        if name and not name.startswith("-") and self.get_command(ctx, name) is None:
            import difflib

            close = difflib.get_close_matches(name, self.list_commands(ctx), n=1, cutoff=0.6)
            hint = f" Did you mean `{close[0]}`?" if close else ""
            ctx.fail(f"No such command '{name}'.{hint} The commands: "
                     f"{', '.join(self.list_commands(ctx))}.")
        return super().resolve_command(ctx, args)

    def invoke(self, ctx: click.Context) -> object:
        from dyade.errors import DyadeError, InputError

        _process_settings()
        try:
            outcome = super().invoke(ctx)
            sys.stdout.flush()  # a full disk says so here, not in Python's exit
            return outcome
        except OSError as err:  # writing the output failed (reading is an InputError)
            if err.errno == errno.EPIPE:  # the reader went away (`| head`): a normal end
                _closed_pipe()
            raise click.ClickException(f"could not write the output: {err.strerror or err}"
                                       f"{f' ({err.filename})' if err.filename else ''}."
                                       ) from None
        except KeyboardInterrupt:  # Ctrl-C: the shell's convention, 128 + SIGINT
            click.echo("Interrupted.", err=True)
            raise click.exceptions.Exit(130) from None
        except Terminated:  # SIGTERM: 128 + 15; files being written are removed on the way
            click.echo("Terminated.", err=True)
            raise click.exceptions.Exit(143) from None
        except InputError as err:
            raise click.UsageError(str(err)) from None  # exit 2
        except DyadeError as err:
            raise click.ClickException(str(err)) from None  # exit 1


def _closed_pipe() -> None:
    """End quietly as a Unix tool killed by SIGPIPE does: exit status 141 (128 + 13),
    no message; standard output goes to /dev/null first, so that Python's own flush at
    exit finds no broken pipe to complain about."""
    import os

    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError, AttributeError):  # no file descriptor (a test's capture)
        pass
    raise click.exceptions.Exit(141) from None


class Terminated(Exception):
    """SIGTERM arrived: unwind (removing partial files) and exit 143."""


def _process_settings() -> None:
    """What a command may set for the whole process and a library may not: SIGTERM
    unwinds like Ctrl-C (so no partial file is left), and a Python warning, should one
    ever escape the engine, is one line on stderr, not a source listing."""
    import threading
    import warnings

    try:  # the C module: signal.py builds enums at import (0.7 ms) that this needs not
        import _signal as signal
    except ImportError:  # pragma: no cover - not CPython
        import signal

    def terminate(signum, frame):
        raise Terminated

    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGTERM, terminate)

    def one_line(message, category, filename, lineno, file=None, line=None):
        click.echo(f"warning: {message} ({category.__name__}; please report it)", err=True)

    warnings.showwarning = one_line


def _version(ctx: click.Context, _: click.Parameter, value: bool) -> None:
    """--version: dyade's, Python's and numpy's versions (numpy's from its metadata, so
    that asking costs no numpy import)."""
    if not value or ctx.resilient_parsing:
        return
    import platform
    from importlib.metadata import PackageNotFoundError, version

    try:
        numpy = version("numpy")
    except PackageNotFoundError:  # pragma: no cover - numpy is a dependency
        numpy = "not installed"
    click.echo(f"dyade {__version__} (Python {platform.python_version()}, numpy {numpy})")
    ctx.exit()


@click.group(cls=DyadeGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.option("--version", is_flag=True, expose_value=False, is_eager=True, callback=_version,
              help="Show dyade's, Python's and numpy's versions and exit.")
def main() -> None:
    """Kinematics and kinetostatics of planar linkages built from dyads.

    A mechanism file (TOML) lists the frame points, the crank (link 2) and the dyads in
    assembly order; `dyade help mechanism-file` shows every key (`dyade help`: every
    page of the file references and the user guide). Start with

    \b
        dyade describe mechanisms/fourbar.toml
        dyade analyse mechanisms/fourbar.toml
        dyade analyse mechanisms/fourbar.toml --format csv -o fourbar.csv

    Shell completion: put this line in ~/.bashrc (zsh_source in ~/.zshrc, fish_source
    for fish):

    \b
        eval "$(_DYADE_COMPLETE=bash_source dyade)"
    """
