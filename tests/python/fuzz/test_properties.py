"""Property tests of the input checks (hypothesis, derandomized): whatever JSON value stands in any field of a
valid document, reading it is either fine or a SchemaError naming the file, in one line of bounded length;
the integer and number checks accept exactly the values in range and raise ValueError for the rest."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

sys.path.insert(0, str(Path(__file__).resolve().parent))

from cases import grasps_doc, model_doc, set_path  # noqa: E402
from graspmix import io  # noqa: E402
from graspmix.io.schema import validate  # noqa: E402

JSON = st.recursive(
    st.none() | st.booleans() | st.integers() | st.floats() | st.text(max_size=200),
    lambda kids: st.lists(kids, max_size=4) | st.dictionaries(st.text(max_size=8), kids, max_size=4),
    max_leaves=12,
)


def _paths(doc, prefix=()):
    yield prefix
    if isinstance(doc, dict):
        for k, v in doc.items():
            yield from _paths(v, prefix + (k,))
    elif isinstance(doc, list):
        for i, v in enumerate(doc[:2]):
            yield from _paths(v, prefix + (i,))


GRASPS_PATHS = [p for p in _paths(grasps_doc()) if p]
MODEL_PATHS = [p for p in _paths(model_doc()) if p and len(p) <= 4]


@settings(derandomize=True, max_examples=300, deadline=None)
@given(st.sampled_from([("grasps", p) for p in GRASPS_PATHS] + [("model", p) for p in MODEL_PATHS]), JSON)
def test_any_value_in_any_field_is_read_or_a_one_line_schema_error(where, value):
    fmt, path = where
    doc = set_path(grasps_doc() if fmt == "grasps" else model_doc(), path, value)
    schema = io.SCHEMAS[io.GRASPS_FORMAT if fmt == "grasps" else io.MODEL_FORMAT]
    try:
        validate(doc, schema, "doc.json")
    except ValueError as e:
        text = str(e)
        assert text.startswith("doc.json: ") and "\n" not in text and len(text) < 600, text


@settings(derandomize=True, max_examples=300, deadline=None)
@given(st.integers() | st.floats() | st.booleans() | st.text(max_size=5) | st.none())
def test_check_int_accepts_exactly_the_integers_in_range(v):
    ok = isinstance(v, int) and not isinstance(v, bool) and 0 <= v <= io.SEED_MAX
    if ok:
        assert io.check_seed(v) == v
    else:
        with pytest.raises(ValueError, match="seed"):
            io.check_seed(v)


@settings(derandomize=True, max_examples=300, deadline=None)
@given(st.floats() | st.integers() | st.just(10**400) | st.booleans() | st.text(max_size=5))
def test_check_float_accepts_exactly_the_finite_numbers_in_range(v):
    number = isinstance(v, (int, float)) and not isinstance(v, bool)
    ok = number and 0 <= v <= 60 and not (isinstance(v, float) and math.isnan(v))
    if ok:
        assert io.check_sim_time(v, "hold_time") == float(v)
    else:
        with pytest.raises(ValueError, match="hold_time"):
            io.check_sim_time(v, "hold_time")


@given(st.text(max_size=10_000) | st.binary(max_size=10_000) | st.lists(st.integers(), max_size=3000))
@settings(derandomize=True, max_examples=100, deadline=None)
def test_quote_is_short(v):
    assert len(io.quote(v)) <= io.QUOTE_LIMIT + 40
