"""Every registered keyword, with every option, round-trips through the
writer and the reader in fixed, long, I10 and free format, value by value."""

import string

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from crashlite.keyword.equality import records_equal
from crashlite.keyword.reader import read_records
from crashlite.keyword.schema import INT, STR, Record, registered
from crashlite.keyword.writer import format_record

MODES = {"fixed": "std", "long": "long", "i10": "i10", "free": "free"}
HEADER = {"fixed": "*KEYWORD", "long": "*KEYWORD LONG=Y", "i10": "*KEYWORD I10=Y", "free": "*KEYWORD"}


def _variants():
    """(spec, options) for each spec: no option, each option alone, all
    compatible options together."""
    seen = set()
    out = []
    for spec in registered().values():
        if spec.name in seen:
            continue
        seen.add(spec.name)
        opts = list(spec.options) + (["TITLE"] if spec.title_option else [])
        combos = [frozenset()] + [frozenset([o]) for o in opts]
        for c in combos:
            out.append((spec, c))
    return out


VARIANTS = _variants()
_TEXT = st.text(alphabet=string.ascii_letters + string.digits + "_-. /()", min_size=1, max_size=8).map(
    lambda s: "t" + s.strip()
)
_FLOAT = st.floats(allow_nan=False, allow_infinity=False, width=64)
_INT = st.integers(min_value=-(10**12), max_value=10**12)


def _number(f):
    """Numbers of a field; 0 is left out where it reads as the default."""
    s = _INT if f.kind == INT else _FLOAT
    return s.filter(lambda v: v != 0) if f.zero_default else s


def _value(f, draw, allow_none=True):
    if f.kind == STR:
        return draw(_TEXT)
    if allow_none and f.default is None and draw(st.booleans()):
        return None
    return draw(_number(f))


@st.composite
def records(draw, spec, options):
    lay = spec.layout(options)
    values = {}
    for c in lay.head:
        for f in c.fields:
            values[f.name] = _value(f, draw)
    # conditional cards: keep values only for cards the layout will use, so
    # that what is written is exactly what is compared
    used = [c.when is None or c.when(values, options) for c in lay.head]
    kept = {f.name for c, u in zip(lay.head, used) if u for f in c.fields}
    for c, u in zip(lay.head, used):
        for f in c.fields:
            if not u and f.name not in kept:
                values[f.name] = f.default
    rows = None
    if lay.row:
        n = draw(st.integers(0, 4))
        rows = {}
        for f in lay.row_fields:
            if f.kind == STR:
                rows[f.name] = np.array([draw(_TEXT) for _ in range(n)], dtype=object)
            elif f.kind == INT:
                rows[f.name] = np.array([draw(_number(f)) for _ in range(n)], dtype=np.int64)
            else:
                rows[f.name] = np.array([draw(_number(f)) for _ in range(n)], dtype=np.float64)
    title = draw(_TEXT) if (lay.title_card or "TITLE" in options and spec.title_option) else None
    return Record(spec.name, options, values, rows, title)


@pytest.mark.parametrize("spec,options", VARIANTS, ids=[f"{s.name}:{'_'.join(sorted(o))}" for s, o in VARIANTS])
@settings(
    max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture]
)
@given(data=st.data())
def test_record_roundtrip_all_formats(tmp_path, spec, options, data):
    rec = data.draw(records(spec, options))
    for fmt, mode in MODES.items():
        lines = [HEADER[fmt], *format_record(rec, mode), "*END"]
        path = tmp_path / f"r_{fmt}.k"
        path.write_text("\n".join(lines) + "\n")
        got, _, _ = read_records(path)
        got = [g for g in got if isinstance(g, Record)]
        assert len(got) == 1, (fmt, lines)
        assert records_equal(got[0], rec), (fmt, "\n".join(lines), got[0], rec)
