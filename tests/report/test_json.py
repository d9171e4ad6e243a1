"""JSON numbers written a block at a time (issue 17): the text ``json.dumps`` gives."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st


@settings(max_examples=300, deadline=None)
@given(st.lists(st.floats(allow_nan=True, allow_infinity=True, width=64), min_size=1,
                max_size=40))
def test_json_numbers_are_what_json_dumps_writes(values):
    """The vectorised JSON numbers against ``json.dumps`` of the 15-digit float (the
    path every other JSON value takes): whole numbers, 10¹⁵..10¹⁶, -0, NaN, ±inf."""
    import json
    import math

    from dyade.report.document import json_numbers

    values += [90.0, -0.0, 1e15, 9.99999999999999e15, -1.5e15, 1e16, 123456789012345.0,
               1.7976931348623157e308, 1.79769313486231e308, -1e308, 2.225073858507e-311,
               5e-324, -2.2250738585072014e-308, 1.5e-35]
    rounded = [float(f"{v + 0.0:.15g}") if math.isfinite(v) else None for v in values]
    expected = [json.dumps(r if r is not None and math.isfinite(r) else None)
                for r in rounded]
    assert json_numbers(np.array(values)) == expected
