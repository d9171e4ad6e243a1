"""Whole-command times against bare `python -c "import numpy"` (issue 7).

    python tests/benchmarks/command_time.py [--runs 21]

Runs each command in a fresh process with this interpreter and the `dyade` script beside
it, best and median of ``--runs``; prints the ratios the issue's targets are about. Use
a regular (not editable) install: an editable one recompiles and adds an import finder.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def timings(command: list[str], runs: int) -> tuple[float, float]:
    """Best and median wall time [ms] of ``runs`` fresh processes."""
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        subprocess.run(command, stdout=subprocess.DEVNULL, check=True, cwd=ROOT)
        times.append((time.perf_counter() - start) * 1e3)
    return min(times), statistics.median(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=21)
    runs = parser.parse_args().runs
    dyade = str(Path(sys.executable).with_name("dyade" + (".exe" if os.name == "nt" else "")))
    base = timings([sys.executable, "-c", "import numpy"], runs)
    label = 'python -c "import numpy"'
    print(f"{label:52s} best {base[0]:6.1f} ms  median {base[1]:6.1f} ms")
    for args in (["analyse", "mechanisms/fourbar.toml", "--format", "csv"], ["--help"]):
        best, median = timings([dyade, *args], runs)
        print(f"{'dyade ' + ' '.join(args):52s} best {best:6.1f} ms  median {median:6.1f} ms"
              f"  ratio {best / base[0]:.2f} / {median / base[1]:.2f}")


if __name__ == "__main__":
    main()
