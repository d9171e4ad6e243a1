"""The ``dyade`` command: a thin shell over the API (``dyade``).

Each command parses its options, calls the API and hands the result to ``dyade.report``.

Exit codes: 0 success, 1 analysis problem (``DyadeError``), 2 bad input or usage
(``InputError`` and click's usage errors). Heavy modules (numpy, rich) are imported
inside the commands, so that ``dyade --help`` stays fast.
"""

from __future__ import annotations

import click

from dyade import __version__

SUBCOMMANDS = {"describe": "analyse", "analyse": "analyse", "init": "analyse",
               "clearance": "clearance", "coupling": "coupling", "accuracy": "accuracy",
               "gears": "gears"}
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

    def invoke(self, ctx: click.Context) -> object:
        from dyade.cli.memory import keep_freed_memory
        from dyade.errors import DyadeError, InputError

        keep_freed_memory()  # a process-wide setting: the command's to make, not the library's
        try:
            return super().invoke(ctx)
        except InputError as err:
            raise click.UsageError(str(err)) from None  # exit 2
        except DyadeError as err:
            raise click.ClickException(str(err)) from None  # exit 1


@click.group(cls=DyadeGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="dyade")
def main() -> None:
    """Kinematics and kinetostatics of planar linkages built from dyads.

    A mechanism file (TOML) lists the frame points, the crank (link 2) and the dyads in
    assembly order; see mechanisms/README.md for every key. Start with

        dyade describe mechanisms/fourbar.toml

        dyade analyse mechanisms/fourbar.toml --format csv -o fourbar.csv
    """

