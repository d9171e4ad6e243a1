"""-j 2 against -j 1 (issue 17): the 8 shipped mechanisms at 5 crank speeds each (40
files), ``dyade analyse FILES -o DIR -j N``, the two alternating; wall-clock medians and
their ratio, and whether the two folders are byte-identical. Run it on a quiet machine
with at least two free cores:

    python tests/benchmarks/jobs_time.py --runs 15
"""

from __future__ import annotations

import argparse
import filecmp
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

MECHANISMS = Path(__file__).resolve().parents[2] / "mechanisms"
DYADE = str(Path(sys.executable).with_name("dyade"))


def files(folder: Path) -> list[str]:
    """Each shipped mechanism at its own speed times 1.0, 1.1, … 1.4."""
    out = []
    for path in sorted(MECHANISMS.glob("*.toml")):
        text = path.read_text(encoding="utf-8")
        for k in range(5):
            scaled = re.sub(r"(?m)^speed_rpm = ([0-9.]+)",
                            lambda m: f"speed_rpm = {float(m.group(1)) * (1 + k / 10):g}", text)
            target = folder / f"{path.stem}-{k}.toml"
            target.write_text(scaled, encoding="utf-8")
            out.append(str(target))
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=11)
    parser.add_argument("--format", default="csv")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        inputs = files(folder)
        times: dict[int, list[float]] = {1: [], 2: []}
        for _ in range(args.runs):
            for jobs in (1, 2):
                out = folder / f"out{jobs}"
                shutil.rmtree(out, ignore_errors=True)
                start = time.perf_counter()
                subprocess.run([DYADE, "analyse", *inputs, "--format", args.format, "-j",
                                str(jobs), "-o", str(out)], check=True,
                               stderr=subprocess.DEVNULL)
                times[jobs].append(time.perf_counter() - start)
        compared = filecmp.dircmp(folder / "out1", folder / "out2")
        same = not (compared.diff_files or compared.left_only or compared.right_only)
        one, two = (statistics.median(times[j]) for j in (1, 2))
        print(f"{len(inputs)} files, {args.runs} runs each: -j 1 {one * 1e3:.0f} ms, "
              f"-j 2 {two * 1e3:.0f} ms (min {min(times[1]) * 1e3:.0f} / "
              f"{min(times[2]) * 1e3:.0f}): ratio {two / one:.2f}; identical files: {same}")


if __name__ == "__main__":
    main()
