"""``python -m dyade``: the same as the ``dyade`` command."""

from dyade.cli import main

if __name__ == "__main__":  # pragma: no cover
    main()
