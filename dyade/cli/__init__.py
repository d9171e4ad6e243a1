"""The ``dyade`` command: a thin shell over ``dyade.analysis``.

Exit codes: 0 success, 1 analysis problem (``DyadeError``), 2 bad input or usage
(``InputError`` and click's usage errors). Heavy modules (numpy, rich) are imported
inside the commands, so that ``dyade --help`` stays fast.
"""

from __future__ import annotations

import click

from dyade import __version__


class DyadeGroup(click.Group):
    """Maps dyade's exceptions to click's exit codes, in one place."""

    def invoke(self, ctx: click.Context) -> object:
        from dyade.errors import DyadeError, InputError

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


from dyade.cli import analyse as _analyse  # noqa: E402,F401  (registers the commands)
from dyade.cli import clearance as _clearance  # noqa: E402,F401
from dyade.cli import coupling as _coupling  # noqa: E402,F401
from dyade.cli import accuracy as _accuracy  # noqa: E402,F401
