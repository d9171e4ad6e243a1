"""A study of a cam file (issue 40): its rows are the cam's own checks (``dyade cam``)
of each variant, read by another way; refused keys and never-in-contact variants are
rows that say why."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import dyade
from dyade.errors import InputError
from dyade.files.cam import read_cam

FILE = "mechanisms/cams/translating-roller.toml"


@pytest.fixture(scope="module")
def table():
    spec = dyade.study.parse({"mechanism": FILE, "parameters": {
        "cam.base_radius": [25, 40], "follower.roller_radius": [10, 14],
        "follower.offset": [0, 8], "follower.stiffness": [400, 2000]}})
    return dyade.study(spec)


def test_rows_equal_direct_runs_of_the_cam(table):
    columns, units = table.columns(), table.units
    assert list(columns["status"]) == ["ok"] * 16 and units["cam.base_radius"] == "mm"
    assert units["follower.stiffness"] == "N/m" and units["pressure_angle_max_deg"] == "°"
    assert units["base_radius_min"] == "m" and units["lift_off_speed_rpm"] == "rpm"
    cam = read_cam(FILE)
    for k in (0, 5, 10, 15):  # the model changed directly, not through the file's keys
        variant = dataclasses.replace(
            cam, base_radius=columns["cam.base_radius"][k] * 1e-3,
            roller_radius=columns["follower.roller_radius"][k] * 1e-3,
            offset=columns["follower.offset"][k] * 1e-3,
            stiffness=float(columns["follower.stiffness"][k]))
        direct = dyade.run("cam", variant)
        for name in table.outputs:
            expected = direct.value(name)
            assert columns[name][k] == pytest.approx(float(expected), rel=1e-12, abs=0), name
    # the stiffer spring holds the follower on to a higher speed (k·(s + s0) grows)
    lift = columns["lift_off_speed_rpm"]
    soft, stiff = columns["follower.stiffness"] == 400, columns["follower.stiffness"] == 2000
    assert np.all(lift[stiff] > lift[soft])


def test_variants_that_cannot_be_cams_are_rows_that_say_why():
    spec = dyade.study.parse({"mechanism": FILE, "parameters": {
        "follower.offset": [8, 60], "follower.preload": [10, -60]}})
    columns = dyade.study(spec).columns()
    status = list(columns["status"])
    assert status == ["ok", "failed", "refused", "refused"]
    assert "can never keep contact" in columns["reason"][1]
    assert "`follower.offset` must be less than the pitch radius" in columns["reason"][2]
    with pytest.raises(InputError, match=r"\[parameters\]: .*unknown key `cam.base_radus`"):
        dyade.study(dyade.study.parse({"mechanism": FILE,
                                       "parameters": {"cam.base_radus": [30, 40]}}))
