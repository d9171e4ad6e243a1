"""What the hostile-input modules of issue 31 share: a command run in-process that must
end with its exit code and the key words of its message, never a traceback or a Python
warning."""

from __future__ import annotations

from click.testing import CliRunner

from dyade.cli import main


def run(args, stdin: str | bytes | None = None):
    """``dyade ARGS`` in-process; no unhandled exception, traceback or warning."""
    result = CliRunner().invoke(main, [str(a) for a in args], input=stdin)
    assert result.exception is None or isinstance(result.exception, SystemExit), \
        f"unhandled {type(result.exception).__name__}: {result.exception}"
    assert "Traceback" not in result.output and "Warning:" not in result.output
    return result


def expect(args, code: int, *words: str, stdin=None):
    """Run and check the exit code and that every word is in the output."""
    result = run(args, stdin)
    assert result.exit_code == code, result.output
    for word in words:
        assert word in result.output, (word, result.output)
    return result
