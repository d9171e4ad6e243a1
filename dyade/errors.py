"""Exceptions that dyade explains to its users, with structured fields.

``DyadeError`` is an analysis problem (the command line exits 1), ``InputError`` a bad
file, key or parameter (exits 2), ``AssemblyError`` a dyad that cannot close. Anything
else that escapes is a bug and keeps its traceback.

The API names what was wrong in its own terms: a file and a key path for file data,
a parameter name for a function argument. The command line knows where a value came
from and names the flag instead (``InputError.naming``), so the engine never has to.

>>> err = InputError.parameter("inertia", "must be positive [kg·m²], got -1.", value=-1.0,
...                            unit="kg·m²")
>>> str(err)
'inertia must be positive [kg·m²], got -1.'
>>> str(err.naming({"inertia": "--J"}))
'--J must be positive [kg·m²], got -1.'
"""

from __future__ import annotations

from typing import Any


class DyadeError(Exception):
    """A problem dyade can explain: the mechanism cannot be analysed as asked.

    >>> import dyade
    >>> try:
    ...     dyade.read_mechanism("mechanisms/no-such-file.toml")
    ... except dyade.DyadeError as err:           # every error dyade explains
    ...     print(type(err).__name__)
    InputError
    """


class InputError(DyadeError, ValueError):
    """Bad input: a file, key or parameter that the user must fix.

    Attributes
    ----------
    source : str or None
        The file the value came from (its name as the user gave it), if any.
    key : str or None
        Dotted key path in that file (``links.4.mass``), or the API parameter name.
    value : object
        The offending value, when there is one.
    unit : str or None
        The unit the value is expected in.
    reason : str or None
        What is wrong, as a sentence that follows the name of the input
        (``must be positive [kg], got -1.``); None when the message stands alone.

    Examples
    --------
    >>> import dyade
    >>> mechanism = dyade.read_mechanism("mechanisms/fourbar.toml")
    >>> try:
    ...     dyade.analyse(mechanism, step_deg=-1)
    ... except dyade.InputError as err:
    ...     print(err.key, "|", err.reason)
    step_deg | must be positive [°], got -1.
    """

    def __init__(self, message: str, *, source: str | None = None, key: str | None = None,
                 value: Any = None, unit: str | None = None, reason: str | None = None) -> None:
        super().__init__(message)
        self.source, self.key, self.value, self.unit, self.reason = source, key, value, unit, reason

    @classmethod
    def in_file(cls, label: str, key: str, reason: str, *, source: str | None = None,
                value: Any = None, unit: str | None = None) -> InputError:
        """A key of a file: ``label: `key` reason``."""
        return cls(f"{label}: `{key}` {reason}", source=source or label, key=key, value=value,
                   unit=unit, reason=reason)

    @classmethod
    def parameter(cls, name: str | tuple[str, ...], reason: str, *, value: Any = None,
                  unit: str | None = None) -> InputError:
        """An argument of an API function: ``name reason``; a tuple of names for a
        problem of several together (``c1 and b1 are both zero …``)."""
        names = (name,) if isinstance(name, str) else tuple(name)
        err = cls(f"{' and '.join(names)} {reason}", key=names[0], value=value, unit=unit,
                  reason=reason)
        err.parameters = names
        return err

    parameters: tuple[str, ...] = ()
    """the API parameters the error is about (empty for file errors)"""

    @classmethod
    def refuse_renamed(cls, function: str, given: dict[str, Any], renamed: dict[str, str]
                       ) -> None:
        """Refuse keyword arguments of ``function`` under a former name: an
        ``InputError`` naming the new one (``renamed``: old -> new, with its unit), not a
        Python warning; any other unknown keyword is the ``TypeError`` Python gives.

        >>> InputError.refuse_renamed("analyse", {"step": 0.5}, {"step": "step_deg"})
        Traceback (most recent call last):
        ...
        dyade.errors.InputError: analyse() takes step_deg (degrees), not step: angles at
            the API carry their unit in the name (step_deg=0.5 is half a degree).
        """
        for name, value in given.items():
            new = renamed.get(name)
            if new is None:
                raise TypeError(f"{function}() got an unexpected keyword argument {name!r}")
            unit = "degrees" if new.endswith("_deg") else "rpm" if new.endswith("_rpm") else ""
            example = {"degrees": f"{new}=0.5 is half a degree",
                       "rpm": f"{new}=60 is one revolution per second"}.get(unit, "")
            err = cls(f"{function}() takes {new}{f' ({unit})' if unit else ''}, not {name}: "
                      f"angles at the API carry their unit in the name"
                      f"{f' ({example})' if example else ''}.", key=name, value=value,
                      reason=f"is now {new}")
            err.parameters = (name,)
            raise err

    def naming(self, names: dict[str, str]) -> InputError:
        """The same error with its parameters named as the user gave them: ``names`` maps
        a parameter to a flag (``--J``), to a file key (``coupling.toml: `J```) or to the
        API option it came from; the new names are the error's parameters (so that the
        command line can name an API option by its flag). Errors from files are returned
        unchanged, and so are parameters not in ``names``."""
        if not self.parameters or not any(p in names for p in self.parameters):
            return self
        err = type(self)(f"{' and '.join(names.get(p, p) for p in self.parameters)} "
                         f"{self.reason}", key=self.key, value=self.value, unit=self.unit,
                         reason=self.reason)
        err.parameters = tuple(names.get(p, p) for p in self.parameters)
        return err


class MissingExtra(InputError, ImportError):
    """An optional extra is not installed (matplotlib for plots): the message names the
    command that installs it. Both an ``InputError`` (the command line exits 2) and an
    ``ImportError`` (what ``import`` of the module would raise).

    >>> err = MissingExtra('plots need matplotlib: pip install "dyade[plot]"')
    >>> isinstance(err, ImportError), isinstance(err, InputError)
    (True, True)
    """


class AssemblyError(DyadeError):
    """A dyad cannot close (or is blocked) over part of the crank sweep.

    ``problems`` lists one sentence per dyad, naming it and the crank-angle ranges;
    ``partial`` is True when the mechanism closes at some positions of the sweep (so
    that analysing only those is possible).

    >>> import dyade
    >>> short = dyade.read_mechanism("mechanisms/fourbar.toml", {"dyad.2.lengths": [170, 120]})
    >>> try:
    ...     dyade.analyse(short)
    ... except dyade.AssemblyError as err:
    ...     print(err.partial, err.problems)
    True ('dyad 2 (kind 1 RRR, links 3-4) cannot close for crank angles 140.0°–220.0°',)
    >>> dyade.analyse(short, allow_partial=True).summary()["positions"]   # the rest
    280
    """

    def __init__(self, message: str, problems: tuple[str, ...] = (), partial: bool = False
                 ) -> None:
        super().__init__(message)
        self.problems, self.partial = problems, partial
