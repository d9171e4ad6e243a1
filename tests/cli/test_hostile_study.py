"""Hostile input of `dyade study` (issue 31): each case with its exit code and the key
words of its message."""

from __future__ import annotations

import pytest

from tests.helpers import shipped
from tests.hostile_common import expect

SLIDER = shipped("slider-crank.toml")
STUDY = shipped("studies/press-slide-tolerance.toml")
MC = "[plan]\nkind='monte-carlo'\nsamples={n}\n[parameters]\n'crank.speed_rpm'={{uniform=[{a},{b}]}}\n"


def study(tmp_path, body: str):
    path = tmp_path / "s.toml"
    path.write_text(f"mechanism = {str(SLIDER)!r}\n" + body, encoding="utf-8")
    return path


FILES = {  # study file body -> words of the message (exit 2)
    "no parameters": ("", "`parameters` must be a table"),
    "samples 1e300": (MC.format(n="1e300", a=1, b=2), "`plan.samples` must be a whole number"),
    "samples -1": (MC.format(n=-1, a=1, b=2), "`plan.samples`"),
    "samples 0": (MC.format(n=0, a=1, b=2), "`plan.samples`"),
    "samples 1e12, sized first": (MC.format(n=10**12, a=1, b=2),
                                  "1,000,000,000,000 variants", "PB", "`plan.samples`"),
    "grid of 1e9 variants": ("[plan]\nkind='grid'\n[parameters]\n" + "\n".join(
        f"'links.{i}.mass'=[{', '.join(str(j + 1) for j in range(1000))}]" for i in (2, 3, 4)),
        "1,000,000,000 variants", "`parameters`"),
    "inf": (MC.format(n=3, a=1, b="inf"), "must be a finite number"),
    "nan": (MC.format(n=3, a="nan", b=2), "must be a finite number"),
    "unknown plan": ("[plan]\nkind='grd'\n", "Did you mean `grid`"),
    "unknown table": ("[plann]\n", "Did you mean `plan`"),
    "plan kind a number": ("[plan]\nkind=1\n", "Allowed: grid"),
    "bad TOML": ("x = \n", "not valid TOML"),
    "negative seed": (MC.format(n=3, a=1, b=2).replace("samples", "seed=-1\nsamples"),
                      "`plan.seed`"),
    "unknown tolerance": (MC.format(n=3, a=1, b=2) + "[tolerance]\nfoo=1\n",
                          "`tolerance.foo`"),
    "nan tolerance": (MC.format(n=3, a=1, b=2) + "[tolerance]\njoint_force=nan\n",
                      "`tolerance.joint_force`"),
    "unknown key path": ("[plan]\nkind='monte-carlo'\nsamples=3\n[parameters]\n"
                         "'nonexistent.key'={uniform=[1,2]}\n", "unknown key `nonexistent`"),
}


@pytest.mark.parametrize("case", FILES)
def test_bad_study_files_are_refused(tmp_path, case):
    body, *words = FILES[case]
    expect(["study", study(tmp_path, body)], 2, *words)


OTHER = {"slider-crank.toml": "a mechanism file", "gears/two-stage.toml": "a gear-drive file",
         "coupling/stiff-coupling.toml": "a coupling file"}


@pytest.mark.parametrize("name", OTHER)
def test_a_file_of_another_kind_names_its_commands(name):
    expect(["study", shipped(name)], 2, OTHER[name], "read")


@pytest.mark.parametrize("command", ["analyse", "gears", "describe", "driveline", "coupling"])
def test_a_study_file_given_to_another_command_says_so(command):
    expect([command, STUDY], 2, "a study file", "dyade study")


def test_outputs(tmp_path):
    small = study(tmp_path, MC.format(n=2, a=100, b=200))
    expect(["study", small, "--format", "parquet"], 2, "-o FILE.parquet")
    (tmp_path / "afile").write_text("x")
    expect(["study", small, "-o", tmp_path / "afile" / "x.csv"], 2, "is a file, not a folder")
    expect(["study", small, "-o", tmp_path / "new" / "dir" / "x.csv"], 0)
    assert (tmp_path / "new" / "dir" / "x.csv").read_text().startswith("variant,")
    out = expect(["study", small, "-o", "-"], 0)
    assert out.output.startswith("variant,") and not (tmp_path / "-").exists()
    expect(["study", small, "--resume"], 2, "--resume needs -o")
