"""The motor catalogue reader: what a spreadsheet writes, refused or read, never a traceback."""

from __future__ import annotations

import pytest

from dyade.errors import InputError
from dyade.files.catalogue import parse_catalogue, read_catalogue

HEADER = "name,rated_torque,peak_torque,rated_speed_rpm,top_speed_rpm,rotor_inertia\n"


def test_a_byte_order_mark_before_the_header_is_read(tmp_path):
    path = tmp_path / "motors.csv"
    path.write_bytes(b"\xef\xbb\xbf" + (HEADER + "M1,1,3,3000,6000,1e-4\n").encode())
    assert [m.name for m in read_catalogue(path).motors] == ["M1"]
    assert parse_catalogue("\ufeff" + HEADER + "M1,1,3,3000,6000,1e-4\n").motors[0].name == "M1"


def test_a_file_not_in_utf8_is_refused_naming_it(tmp_path):
    path = tmp_path / "motors.csv"
    path.write_bytes(b"\xff\xfe\x00name")
    with pytest.raises(InputError, match="motors.csv.*UTF-8"):
        read_catalogue(path)


def test_a_row_with_more_fields_than_the_header_is_refused_naming_the_row():
    with pytest.raises(InputError, match="row 2 \\(M2\\) has 7 fields, the header 6"):
        parse_catalogue(HEADER + "M1,1,3,3000,6000,1e-4\nM2,1,3,3000,6000,1e-4,x\n", "m.csv")


def test_a_value_beyond_any_motor_is_refused_before_it_overflows():
    with pytest.raises(InputError, match="rotor_inertia.*row 1 \\(M1\\).*up to 1e\\+09"):
        parse_catalogue(HEADER + "M1,1,3,3000,6000,1e300\n", "m.csv")


def test_two_motors_of_one_name_are_refused_naming_both_rows():
    with pytest.raises(InputError, match="'M1' of row 2 is also the name of row 1"):
        parse_catalogue(HEADER + "M1,1,3,3000,6000,1e-4\nM1,2,6,3000,6000,2e-4\n", "m.csv")
