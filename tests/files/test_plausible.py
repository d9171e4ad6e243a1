"""Every number of every file checked against what a machine has where it is read
(issue 42, dyade.limits.PLAUSIBLE): an absurd value is refused naming the file and the
key, before anything is computed from it, as a link's inertia always was."""

from __future__ import annotations

import pytest

import dyade
from tests.helpers import shipped
from tests.hostile_common import expect

DYADE_16 = shipped("dyade-16.toml")

ABSURD = {  # --set key -> value (1e300 in the key's unit): refused naming that key
    "drive": ({"motor": "constant", "flywheel_inertia": 1e300}, "drive.flywheel_inertia"),
    "drive ": ({"motor": "constant", "torque": 1e300}, "drive.torque"),
    "drive  ": ({"motor": "asynchronous", "rated_torque": 10, "rated_speed_rpm": 1e299,
                 "synchronous_speed_rpm": 1e300}, "drive.rated_speed_rpm"),
    "drive   ": ({"motor": "table", "table": [[0, 1e300], [100, 1]]}, "drive.table.1"),
    "crank.length": (1e300, "crank.length"),
    "frame.points.B0": ([1e300, 0], "frame.points.B0"),
    "links.3.centre": ([0, -1e300], "links.3.centre"),
    "links.7.radius_of_gyration": (1e300, "links.7.radius_of_gyration"),  # was an OverflowError
    "spring.1.stiffness": (1e300, "spring.1.stiffness"),
    "spring.1.free_length": (1e300, "spring.1.free_length"),
    "load.1.table": ([[0, 1e300, 0, 0], [200, 0, 0, 0]], "load.1.table.1"),
    "gravity": ({"x": 0, "y": -1e300}, "gravity.y"),
    "friction": ({"coefficient": 1e300}, "friction.coefficient"),
}


@pytest.mark.parametrize("key", ABSURD)
def test_an_absurd_number_in_a_mechanism_file_is_refused_naming_its_key(key):
    value, named = ABSURD[key]
    with pytest.raises(dyade.InputError) as caught:
        dyade.read_mechanism(DYADE_16, {key.strip(): value})
    assert caught.value.source.endswith("dyade-16.toml") and caught.value.key == named
    assert "what a machine has" in str(caught.value)


def test_the_flywheel_of_the_drive_is_refused_like_a_link_inertia():
    flywheel = expect(["describe", DYADE_16, "--set", "drive.motor=\"constant\"", "--set",
                       "drive.flywheel_inertia=1e300"], 2, "drive.flywheel_inertia",
                      "1e-12…1e+07 kg·m²")
    link = expect(["describe", DYADE_16, "--set", "links.2.inertia=1e300"], 2,
                  "links.2.inertia", "1e-12…1e+07 kg·m²")
    assert "Traceback" not in flywheel.output + link.output


def test_what_a_machine_has_is_still_read():
    """The shipped files and the plausible tops themselves pass; the crank speed above
    1e6 rpm is read (and its rows withheld by the analysis, not the reader)."""
    dyade.read_mechanism(DYADE_16, {"drive": {"motor": "constant", "flywheel_inertia": 1e7},
                                    "spring.1.stiffness": 1e13, "crank.speed_rpm": 1e9,
                                    "gravity": {"x": 0, "y": -9.81e3}})


@pytest.mark.parametrize("key, value", [("J", 1e300), ("c1", 1e300), ("moment", 1e300),
                                        ("speed_rpm", 1e300)])
def test_an_absurd_number_in_a_coupling_file_is_refused(tmp_path, key, value):
    text = shipped("coupling/stiff-coupling.toml").read_text()
    lines = [line for line in text.splitlines() if not line.startswith(f"{key} ")]
    path = tmp_path / "c.toml"
    path.write_text("\n".join([f"{key} = {value}"] + lines) + "\n")
    with pytest.raises(dyade.InputError, match=f"c.toml: `{key}` must lie in"):
        dyade.read_coupling(path)


@pytest.mark.parametrize("column, value", [("J_red", "1e300"), ("omega_2", "-1e300")])
def test_an_absurd_number_in_a_torque_csv_of_dyade_is_refused(tmp_path, column, value):
    from dyade.files.torque_curve import load_columns

    written = dyade.run("sweep", shipped("fourbar.toml"), step_deg=10)
    cols = written.columns
    names = ["angle_deg", "M_drive", "J_red", "dJ_red", "omega_2"]
    lines = [",".join(names)] + [",".join(repr(float(cols[n][k])) for n in names)
                                 for k in range(len(cols["angle_deg"]))]
    k = names.index(column)
    fields = lines[3].split(",")
    fields[k] = value
    lines[3] = ",".join(fields)
    path = tmp_path / "curve.csv"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(dyade.InputError, match=f"curve.csv: line 4, column {column}: .* beyond "
                                               f"what a machine has"):
        load_columns(path)
