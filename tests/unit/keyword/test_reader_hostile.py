"""Careless and hostile decks (issues 34 and 35): each ends in one DeckError
naming file, line, keyword and field, or reads as LS-DYNA reads it; never a
traceback, a hang or a silently wrong model."""

import numpy as np
import pytest

from crashlite import DeckError, read_deck
from crashlite.keyword.fuzz import SPRING
from crashlite.model.mesh import index_map


def _problems(path):
    with pytest.raises(DeckError) as e:
        read_deck(path)
    return e.value.problems


def _text(path):
    return "\n".join(str(p) for p in _problems(path))


# ---------------------------------------------------------------- crashes found by the fuzzer


def test_unreadable_definition_id_is_reported_not_a_traceback(deck):
    # the PART's PID unreadable: it used to enter model.parts under None and
    # crash the reference check (TypeError in references.py)
    p = deck("m.k", SPRING.replace("         1         1         1\n", "       abc         1         1\n"))
    probs = _problems(p)
    assert any(x.keyword == "PART" and x.field == "PID" and "'abc'" in x.message for x in probs)


def test_blank_definition_id_is_an_error_naming_the_field(deck):
    p = deck("m.k", SPRING.replace("*MAT_SPRING_ELASTIC\n         1", "*MAT_SPRING_ELASTIC\n          "))
    probs = _problems(p)
    assert any(
        x.keyword == "MAT_SPRING_ELASTIC" and x.field == "MID" and "blank" in x.message and x.line == 13 for x in probs
    )


def test_index_map_of_an_empty_query():
    # (0,) queries used to fail to reshape (ValueError in mesh.py)
    look = index_map(np.array([3, 1, 2]))
    assert look(np.zeros(0, np.int64)).shape == (0,)
    assert look(np.zeros((0, 4), np.int64)).shape == (0, 4)
    assert look(np.zeros((0, 2, 3), np.int64)).shape == (0, 2, 3)
    assert look(np.array(2)).shape == ()


def test_mass_block_without_rows_reads(deck):
    p = deck("m.k", SPRING.replace("*PART", "*ELEMENT_MASS\n*PART"))
    m = read_deck(p)
    assert len(m.masses) == 0


def test_include_transform_offset_past_64_bits(deck):
    deck("part.k", "*NODE\n       1             0.0             0.0             0.0\n")
    p = deck("m.k", "*KEYWORD\n*INCLUDE_TRANSFORM\npart.k\n1e300\n*END\n")
    probs = _problems(p)
    assert any(x.keyword == "INCLUDE_TRANSFORM" and x.field == "IDNOFF" and "64-bit" in x.message for x in probs)


def test_include_transform_offset_taking_an_id_past_64_bits(deck):
    deck("part.k", "*NODE\n9000000000000000000,0.0,0.0,0.0\n")
    p = deck("m.k", "*KEYWORD\n*INCLUDE_TRANSFORM\npart.k\n500000000000000000,,,,,,\n*END\n")
    text = _text(p)
    assert "part.k:1: *NODE, field NID: ID 9000000000000000000 plus the *INCLUDE_TRANSFORM offset" in text


def test_include_transform_fractional_offset_is_an_error(deck):
    deck("part.k", "*NODE\n       1             0.0             0.0             0.0\n")
    p = deck("m.k", "*KEYWORD\n*INCLUDE_TRANSFORM\npart.k\n       1.5\n*END\n")
    assert "*INCLUDE_TRANSFORM, field IDNOFF: expected an integer, got '1.5'" in _text(p)


# ---------------------------------------------------------------- issue 35: decks read wrong without a word


def _pulse():
    from importlib import resources

    return (resources.files("crashlite") / "examples" / "pulse" / "pulse.k").read_bytes()


def _same_model(a, b):
    assert a.nodes.equals(b.nodes) and a.discretes.equals(b.discretes) and a.masses.equals(b.masses)
    assert a.keywords == b.keywords and len(a.keywords) > 3


@pytest.mark.parametrize("eol", [b"\r", b"\r\n"])
def test_cr_only_and_crlf_line_endings_read_as_lf(tmp_path, eol):
    (tmp_path / "lf.k").write_bytes(_pulse())
    (tmp_path / "cr.k").write_bytes(_pulse().replace(b"\n", eol))
    a, b = read_deck(tmp_path / "lf.k"), read_deck(tmp_path / "cr.k")
    assert len(b.nodes) == 2 and len(b.discretes) == 1
    _same_model(a, b)


def test_mixed_line_endings(tmp_path):
    lines = _pulse().split(b"\n")
    mixed = b"".join(x + (b"\n", b"\r\n", b"\r")[i % 3] for i, x in enumerate(lines))
    (tmp_path / "lf.k").write_bytes(_pulse())
    (tmp_path / "mixed.k").write_bytes(mixed)
    _same_model(read_deck(tmp_path / "lf.k"), read_deck(tmp_path / "mixed.k"))


def test_utf8_bom_keeps_the_first_keyword(tmp_path):
    text = _pulse()
    # *INITIAL_VELOCITY_NODE first: with the BOM glued to it, it used to be dropped
    iv = b"*INITIAL_VELOCITY_NODE\n         2  -15555.6       0.0       0.0\n"
    body = text.replace(b"*KEYWORD\n", b"").replace(
        b"*INITIAL_VELOCITY_NODE\n$#     nid        vx        vy        vz\n         2      -&v0       0.0       0.0\n",
        b"",
    )
    (tmp_path / "bom.k").write_bytes(b"\xef\xbb\xbf" + iv + body)
    m = read_deck(tmp_path / "bom.k")
    ivs = m.find("INITIAL_VELOCITY_NODE")
    assert len(ivs) == 1 and float(ivs[0].rows["vx"][0]) == -15555.6


def test_utf16_deck_is_refused(tmp_path):
    (tmp_path / "u16.k").write_bytes(_pulse().decode().encode("utf-16"))
    text = _text(tmp_path / "u16.k")
    assert "u16.k" in text and "UTF-16" in text


def test_integer_past_64_bits_in_a_long_format_shell_row(deck):
    big = "18446744073709551619"  # 2**64 + 3: used to wrap round to node 3
    p = deck(
        "m.k",
        f"""\
*KEYWORD LONG=Y
*NODE
                   1                 0.0                 0.0                 0.0
                   2                 1.0                 0.0                 0.0
                   3                 1.0                 1.0                 0.0
                   4                 0.0                 1.0                 0.0
*ELEMENT_SHELL
                   1                   1                   1                   2{big:>20}                   4
*END
""",
    )
    probs = _problems(p)
    assert any(
        x.line == 8 and x.keyword == "ELEMENT_SHELL" and x.field == "N3" and "64-bit" in x.message for x in probs
    ), probs


@pytest.mark.parametrize(
    "big", ["18446744073709551700", "9223372036854775808", "-9223372036854775809", "1e19", "99999999999999999999e0"]
)
def test_integer_past_64_bits_in_a_free_format_spring(deck, big):
    p = deck("m.k", SPRING.replace("       1       1       1       2\n", f"1,1,1,{big}\n"))
    probs = _problems(p)
    assert any(x.line == 6 and x.field == "N2" and "64-bit" in x.message for x in probs), probs


def test_largest_64_bit_id_reads(deck):
    big = 2**63 - 1
    p = deck(
        "m.k",
        SPRING.replace("       2             1.0", f"{big},1.0,0.0,0.0\n$", 1).replace(
            "       1       1       1       2\n", f"1,1,1,{big}\n"
        ),
    )
    m = read_deck(p)
    assert int(m.nodes.ids[1]) == big


@pytest.mark.parametrize(
    "tc, rc, field, shown",
    [("300", "0", "TC", "300"), ("-12", "0", "TC", "-12"), ("8", "0", "TC", "8"), ("0", "9", "RC", "9")],
)
def test_constraint_codes_out_of_range(deck, tc, rc, field, shown):
    p = deck(
        "m.k",
        SPRING.replace(
            "       2             1.0             0.0             0.0",
            f"       2             1.0             0.0             0.0{tc:>8}{rc:>8}",
        ),
    )
    probs = _problems(p)
    assert any(
        x.keyword == "NODE" and x.field == field and f"node 2: {field} = {shown} is not a constraint code" in x.message
        for x in probs
    ), probs


def test_constraint_codes_in_range_read(deck):
    p = deck(
        "m.k",
        SPRING.replace(
            "       2             1.0             0.0             0.0",
            "       2             1.0             0.0             0.0       7       5",
        ),
    )
    m = read_deck(p)
    assert m.nodes.tc.tolist() == [0, 7] and m.nodes.rc.tolist() == [0, 5]


@pytest.mark.parametrize("nid", ["0", "-4"])
def test_node_id_zero_or_negative(deck, nid):
    p = deck("m.k", SPRING.replace("       1             0.0", f"{nid:>8}             0.0"))
    probs = _problems(p)
    assert any(x.keyword == "NODE" and x.field == "NID" and f"node ID {nid}" in x.message for x in probs), probs


def test_element_id_zero(deck):
    p = deck("m.k", SPRING.replace("       1       1       1       2\n", "       0       1       1       2\n"))
    probs = _problems(p)
    assert any(x.keyword == "ELEMENT_DISCRETE" and x.field == "EID" and "discrete ID 0" in x.message for x in probs), (
        probs
    )


@pytest.mark.parametrize("value", [b"\xa0.85e-09", b"1\xa0000.0", b"1000.0\xa0", b"1_000.0"])
def test_no_break_space_or_underscore_in_a_number(tmp_path, value):
    text = SPRING.encode().replace(b"         1    1000.0", b"         1" + value.rjust(10))
    (tmp_path / "m.k").write_bytes(text)
    probs = _problems(tmp_path / "m.k")
    assert any(x.keyword == "MAT_SPRING_ELASTIC" and x.field == "K" and x.line == 13 for x in probs), probs
    if b"\xa0" in value:
        assert "no-break space" in str(probs[0])


def test_no_break_space_in_a_node_row_and_a_parameter(tmp_path):
    text = SPRING.encode().replace(
        b"             1.0             0.0             0.0", b"          \xa0.85e-09             0.0             0.0"
    )
    text = text.replace(b"*KEYWORD\n", b"*KEYWORD\n*PARAMETER\nR a        \xa01.0\n")
    (tmp_path / "m.k").write_bytes(text)
    probs = _problems(tmp_path / "m.k")
    assert any(x.keyword == "NODE" and x.field == "X" and x.line == 6 for x in probs), probs
    assert any(x.keyword == "PARAMETER" and x.field == "VAL" and x.line == 3 for x in probs), probs


@pytest.mark.parametrize(
    "content, says",
    [
        (bytes(range(256)) * 4, "binary data"),
        (b"\x00" * 1000, "binary data"),
        (bytes(range(1, 32)) * 40, "binary data"),
        (b"just some words\nand more\n", "no keyword"),
        (b"", "empty"),
        (b"$ only a comment\n\n", "no keyword"),
    ],
)
def test_non_deck_main_file_is_refused(tmp_path, content, says):
    (tmp_path / "x.k").write_bytes(content)
    probs = _problems(tmp_path / "x.k")
    assert len(probs) == 1 and probs[0].file.endswith("x.k") and says in probs[0].message


def test_nul_byte_in_a_deck_names_its_line(tmp_path):
    (tmp_path / "m.k").write_bytes(SPRING.encode().replace(b"spring", b"spr\x00ing"))
    probs = _problems(tmp_path / "m.k")
    assert len(probs) == 1 and probs[0].line == 8 and "NUL" in probs[0].message


@pytest.mark.parametrize("card", ["*INCLUDE\n", "*INCLUDE\n      \n", "*INCLUDE_TRANSFORM\n"])
def test_blank_include_is_an_error(deck, card):
    p = deck("m.k", SPRING.replace("*END\n", card + "*END\n"))
    probs = _problems(p)
    assert any(x.keyword.startswith("INCLUDE") and x.field == "FILENAME" and x.line == 14 for x in probs), probs


@pytest.mark.parametrize(
    "content, says",
    [
        (bytes(range(256)), "binary data"),
        (b"\x00" * 64, "binary data"),
        (b"results of something\n1 2 3\n", "no keyword"),
    ],
)
def test_include_of_a_non_deck_file_is_an_error(tmp_path, content, says):
    (tmp_path / "other.dat").write_bytes(content)
    (tmp_path / "m.k").write_bytes(SPRING.replace("*END\n", "*INCLUDE\nother.dat\n*END\n").encode())
    probs = _problems(tmp_path / "m.k")
    assert len(probs) == 1 and probs[0].file.endswith("other.dat") and says in probs[0].message
    assert "m.k:15" in probs[0].message  # where it was included


def test_include_of_an_empty_file_warns(tmp_path):
    (tmp_path / "empty.k").write_bytes(b"$ nothing yet\n")
    (tmp_path / "m.k").write_bytes(SPRING.replace("*END\n", "*INCLUDE\nempty.k\n*END\n").encode())
    m = read_deck(tmp_path / "m.k")
    assert any(w.file.endswith("empty.k") and "no keyword" in w.message for w in m.warnings)


def test_text_before_the_first_keyword_warns(tmp_path):
    (tmp_path / "m.k").write_bytes(b"a stray line\n" + SPRING.encode())
    m = read_deck(tmp_path / "m.k")
    assert any(w.line == 1 and "before the first keyword" in w.message for w in m.warnings)


def _fails_fast(seconds):
    import signal

    def boom(*a):
        raise AssertionError(f"still running after {seconds} s")

    old = signal.signal(signal.SIGALRM, boom)
    signal.alarm(seconds)
    return old


def test_parameter_chain_of_squares_ends_quickly(deck):
    import signal

    chain = "".join(f"I p{i + 1}      p{i}*p{i}\n" for i in range(60))
    p = deck("m.k", "*KEYWORD\n*PARAMETER_EXPRESSION\nI p0       2**4000\n" + chain + "*END\n")
    old = _fails_fast(20)
    try:
        probs = _problems(p)
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)
    assert probs[0].line == 3 and probs[0].field == "EXPRESSION" and "64-bit" in probs[0].message


def test_real_parameter_chain_of_squares(deck):
    chain = "R b         a*a\nR c         b*b\n"
    p = deck("m.k", "*KEYWORD\n*PARAMETER_EXPRESSION\nR a         2**4000\n" + chain + "*END\n")
    probs = _problems(p)
    assert probs[0].line == 3 and "largest double" in probs[0].message


def test_integer_expression_result_capped():
    from crashlite.keyword.expression import ExpressionError, evaluate

    with pytest.raises(ExpressionError, match="too large"):
        evaluate("a*a", {"a": 2**4000})
    assert evaluate("a*2", {"a": 2**62}) == 2**63  # fine as a real parameter


def test_900_deep_include_chain(tmp_path):
    for k in range(900):
        (tmp_path / f"d{k}.k").write_text(f"*KEYWORD\n*INCLUDE\nd{k + 1}.k\n*END\n")
    (tmp_path / "d900.k").write_text("*KEYWORD\n*END\n")
    (tmp_path / "m.k").write_text("*KEYWORD\n*INCLUDE\nd0.k\n*END\n")
    probs = _problems(tmp_path / "m.k")
    assert len(probs) == 1 and probs[0].keyword == "INCLUDE" and probs[0].field == "FILENAME"
    assert "nested more than" in probs[0].message and "m.k -> d0.k" in probs[0].message


def test_include_chain_of_moderate_depth_reads(tmp_path):
    for k in range(30):
        (tmp_path / f"d{k}.k").write_text(f"*KEYWORD\n*INCLUDE\nd{k + 1}.k\n*END\n")
    (tmp_path / "d30.k").write_text(SPRING)
    (tmp_path / "m.k").write_text("*KEYWORD\n*INCLUDE\nd0.k\n*END\n")
    assert len(read_deck(tmp_path / "m.k").discretes) == 1


def test_fixed_format_expression_with_a_comma(deck):
    p = deck(
        "m.k",
        "*KEYWORD\n*PARAMETER\nR t              1.5\n*PARAMETER_EXPRESSION\n"
        "R s       max(t, 2.0)*2\nR u,min(t,1.0)\n*END\n",
    )
    params = {x.name: x.value for x in read_deck(p).parameters}
    assert params["s"] == 4.0 and params["u"] == 1.0


def test_include_name_too_long(deck):
    p = deck("m.k", SPRING.replace("*END\n", "*INCLUDE\n" + "1" * 400 + "\n*END\n"))
    probs = _problems(p)
    assert len(probs) == 1 and probs[0].field == "FILENAME" and "not found" in probs[0].message


@pytest.mark.parametrize("name", ["x" * 5000, "a\x00b.k", "."])
def test_deck_path_that_cannot_be_a_deck(name):
    with pytest.raises(DeckError):
        read_deck(name)


@pytest.mark.parametrize("literal", ["1" * 400, "9" * 5000])
def test_huge_integer_literal_in_an_expression(deck, literal):
    p = deck("m.k", f"*KEYWORD\n*PARAMETER_EXPRESSION\nR a       {literal}\n*END\n")
    probs = _problems(p)
    assert len(probs) == 1 and probs[0].field == "EXPRESSION" and probs[0].line == 3, probs


def test_large_integer_literal_in_a_real_expression_reads(deck):
    p = deck("m.k", f"*KEYWORD\n*PARAMETER_EXPRESSION\nR a       {10**30}*2\n*END\n")
    assert read_deck(p).parameters[0].value == 2e30
