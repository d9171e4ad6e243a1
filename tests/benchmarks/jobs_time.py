"""-j 2 against -j 1 (issue 17): the 8 shipped mechanisms at 5 crank speeds each (40
files), ``python -m dyade analyse FILES -o DIR -j N``, every (tree, N) in turn in each
round; wall-clock medians and their ratio, and whether all folders are byte-identical.
``--tree NAME=PATH`` (repeatable) runs the dyade of another source tree side by side
(issue 25: the fork pool against ``ProcessPoolExecutor``); default: this tree. Run it on
a quiet machine with at least two free cores:

    python tests/benchmarks/jobs_time.py --runs 15 --tree old=../base --tree new=.
"""

from __future__ import annotations

import argparse
import filecmp
import os
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
MECHANISMS = ROOT / "mechanisms"


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
    parser.add_argument("--tree", action="append", metavar="NAME=PATH",
                        help="a source tree whose dyade to run (repeatable; default: this one)")
    args = parser.parse_args()
    trees = dict(t.split("=", 1) for t in args.tree) if args.tree else {"this": str(ROOT)}
    trees = {name: str(Path(path).resolve()) for name, path in trees.items()}
    cases = [(name, jobs) for name in trees for jobs in (1, 2)]
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        inputs = files(folder)
        times: dict[tuple[str, int], list[float]] = {case: [] for case in cases}
        cpu: dict[tuple[str, int], list[float]] = {case: [] for case in cases}
        """user + system time of the command and its workers [s]"""
        for _ in range(args.runs):
            for name, jobs in cases:
                out = folder / f"out-{name}-{jobs}"
                shutil.rmtree(out, ignore_errors=True)
                env = {**os.environ, "PYTHONPATH": trees[name]}
                before = resource.getrusage(resource.RUSAGE_CHILDREN)
                start = time.perf_counter()
                subprocess.run([sys.executable, "-m", "dyade", "analyse", *inputs, "--format",
                                args.format, "-j", str(jobs), "-o", str(out)], check=True,
                               stderr=subprocess.DEVNULL, cwd=trees[name], env=env)
                times[name, jobs].append(time.perf_counter() - start)
                after = resource.getrusage(resource.RUSAGE_CHILDREN)
                cpu[name, jobs].append(after.ru_utime + after.ru_stime - before.ru_utime
                                       - before.ru_stime)
        first = folder / f"out-{cases[0][0]}-1"
        same = all(not (c.diff_files or c.left_only or c.right_only) for c in
                   (filecmp.dircmp(first, folder / f"out-{name}-{jobs}") for name, jobs in cases))
    print(f"{len(inputs)} files, --format {args.format}, {args.runs} runs each "
          f"(median [min-max] ms); identical files: {same}")
    for name in trees:
        one, two = (statistics.median(times[name, jobs]) for jobs in (1, 2))
        print(f"  {name:8} -j 1 {one * 1e3:5.0f} [{min(times[name, 1]) * 1e3:.0f}-"
              f"{max(times[name, 1]) * 1e3:.0f}]   -j 2 {two * 1e3:5.0f} "
              f"[{min(times[name, 2]) * 1e3:.0f}-{max(times[name, 2]) * 1e3:.0f}]   "
              f"-j 2 / -j 1 {two / one:.2f};   CPU -j 1 "
              f"{statistics.median(cpu[name, 1]) * 1e3:.0f}, -j 2 "
              f"{statistics.median(cpu[name, 2]) * 1e3:.0f}")
    if len(trees) > 1:
        base = next(iter(trees))
        for name in list(trees)[1:]:
            ratios = [statistics.median(times[name, j]) / statistics.median(times[base, j])
                      for j in (1, 2)]
            print(f"  {name} / {base}: -j 1 {ratios[0]:.2f}, -j 2 {ratios[1]:.2f}")


if __name__ == "__main__":
    main()
