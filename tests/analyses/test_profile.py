"""The ``profile`` entry: numbers beyond floating point refused, never an inf or a warning."""

from __future__ import annotations

import warnings

import pytest

import dyade
from dyade.errors import InputError
from tests.helpers import shipped


@pytest.mark.parametrize("body, options", [
    ('[profile]\nmaster = "time"\nperiod = 1\nunit = "mm"\n[[profile.segment]]\n'
     'kind = "rise"\nlaw = "cycloid"\nend = 0.5\nto = 1e308\n[[profile.segment]]\n'
     'kind = "dwell"\nend = 1\n', {}),
    (None, {"speed_rpm": 1e-300}),
])
def test_overflow_is_refused_naming_the_file(tmp_path, body, options):
    path = shipped("profiles/indexing.toml")
    if body is not None:
        path = tmp_path / "huge.toml"
        path.write_text(body, encoding="utf-8")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(InputError, match=f"{path.name}: .*exceed the range"):
            dyade.run("profile", path, **options)
