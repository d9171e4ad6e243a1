"""Option types and options shared by the commands."""

from __future__ import annotations

import click

MAX_VALUES = 10_000_000


class Number(click.ParamType):
    """A finite number (nan and inf are refused where they are typed), optionally
    positive or within a range."""

    name = "number"

    def __init__(self, positive: bool = False, low: float | None = None,
                 high: float | None = None, unit: str = "") -> None:
        self.positive, self.low, self.high, self.unit = positive, low, high, unit

    def convert(self, value, param, ctx) -> float:
        import math

        try:
            number = float(value)
        except (TypeError, ValueError):
            self.fail(f"must be a number, got {value!r}.", param, ctx)
        if not math.isfinite(number):
            self.fail(f"must be a finite number, got {value!r}.", param, ctx)
        if self.positive and number <= 0.0:
            self.fail(f"must be positive, got {value!r}.", param, ctx)
        if self.low is not None and number < self.low or self.high is not None and number > self.high:
            unit = f" {self.unit}" if self.unit else ""
            if self.low is None:
                self.fail(f"must be at most {self.high:g}{unit}, got {value!r}.", param, ctx)
            if self.high is None:
                self.fail(f"must be at least {self.low:g}{unit}, got {value!r}.", param, ctx)
            self.fail(f"must lie in {self.low:g}…{self.high:g}{unit}, got {value!r}.", param, ctx)
        return number


class Renamed(click.Option):
    """An option with old names kept as hidden aliases for one release (``old=``): they
    work, but --help and the messages show only the new name."""

    def __init__(self, param_decls, old: tuple[str, ...] = (), **kwargs) -> None:
        names = [d for d in param_decls if d.startswith("-")]
        dest = [d for d in param_decls if not d.startswith("-")]
        super().__init__(names + list(old) + dest, **kwargs)
        self.old = tuple(old)

    def add_to_parser(self, parser, ctx) -> None:
        """The new names as usual; the old ones stored apart, so that ``consume_value``
        knows which name the user typed."""
        opts = self.opts
        self.opts = [o for o in opts if o not in self.old]
        try:
            super().add_to_parser(parser, ctx)
        finally:
            self.opts = opts
        if self.old:
            parser.add_option(obj=self, opts=list(self.old), dest=f"{self.name}\0old",
                              action=("append" if self.multiple else "store")
                              + ("_const" if self.is_flag else ""),
                              nargs=self.nargs,
                              **({"const": self.flag_activation_value} if self.is_flag else {}))

    def consume_value(self, ctx, opts):
        """The value under either name; an old name typed is remembered
        (``renamed_from``), so that messages say it was renamed."""
        old = opts.get(f"{self.name}\0old")
        if old is not None:
            new = opts.get(self.name)
            value = (list(new or ()) + list(old)) if self.multiple else old
            opts = {**opts, self.name: value}
            ctx.meta.setdefault(RENAMED_KEY, {})[self.opts[0]] = "/".join(self.old)
        return super().consume_value(ctx, opts)

    def _shown(self, method, ctx):
        opts = self.opts
        self.opts = [o for o in opts if o not in self.old]
        try:
            return method(ctx)
        finally:
            self.opts = opts

    def get_help_record(self, ctx):
        return self._shown(super().get_help_record, ctx)

    def get_error_hint(self, ctx):
        hint = self._shown(super().get_error_hint, ctx)
        old = renamed_from(self.opts[0], ctx)
        return f"{hint} (renamed from {old})" if old else hint


RENAMED_KEY = "dyade.renamed"
"""``ctx.meta`` key: new flag -> the old name the user typed"""


def renamed_from(flag: str, ctx=None) -> str | None:
    """The former name under which the user gave ``flag`` in this command, if any."""
    ctx = ctx or click.get_current_context(silent=True)
    while ctx is not None:
        old = ctx.meta.get(RENAMED_KEY, {}).get(flag)
        if old:
            return old
        ctx = ctx.parent
    return None


def as_given(flag: str) -> str:
    """``flag`` as messages name it: ``--speed (renamed from --speed-rpm)`` where the user
    typed the former name."""
    old = renamed_from(flag) if flag.startswith("-") else None
    return f"{flag} (renamed from {old})" if old else flag


FINITE = Number()
POSITIVE = Number(positive=True)

# paths stay strings on the way of `dyade analyse`: pathlib alone costs 5 ms of start-up
MECHANISM_FILE = click.Path(exists=True, dir_okay=False, allow_dash=True)

set_option = click.option(
    "--set", "assignments", multiple=True, metavar="KEY=VALUE",
    help="Override a key of the file without editing it, with its dotted path as in the file "
         "(repeatable): --set crank.speed_rpm=600 --set dyad.2.lengths=[200,150]. Validated "
         "like the file.")


max_memory_option = click.option(
    "--max-memory", type=POSITIVE, default=4096, show_default=True, metavar="MB",
    help="Refuse, before computing, a run that would need more memory than this; the "
         "estimate is in the message (one bound for every command: dyade.limits).")
"""--max-memory [MB]: give it to the API as ``max_memory * 2**20`` [B]"""


jobs_option = click.option(
    "-j", "--jobs", type=click.IntRange(min=0), default=1, show_default=True, metavar="N",
    help="Analyse several files (or speeds) on N processes at once (0: all cores); the "
         "output is that of a serial run, in the same order.")


def value_range(text: str, hint: str, unit: str, positive_start: bool = False) -> list[float]:
    """Parse START:STOP:STEP into the list of values (STOP included;
    ``dyade.files.schema.value_range``), a bad one refused naming the option."""
    from dyade.files.schema import value_range as values

    try:
        return values(text, unit, positive_start, MAX_VALUES)
    except ValueError as err:
        raise click.BadParameter(str(err), param_hint=hint) from None
