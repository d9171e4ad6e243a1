"""``python -m dyade``: the same as the ``dyade`` command."""

from dyade.cli import run

if __name__ == "__main__":  # pragma: no cover
    run()
