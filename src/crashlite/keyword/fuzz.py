"""A seeded deck mutator: careless and hostile copies of small decks, for
the reader's robustness test (tests/unit/keyword/test_fuzz.py) and the
benchmark bench/fuzz_reader.py.

A *case* is a set of files (name -> bytes) whose main file is ``main.k``.
Seeds are the bundled example decks and one small typed deck per keyword
family; :func:`mutate` applies one to three random mutations (truncation,
deleted, duplicated or shifted lines, garbage in a field, NUL bytes, random
lines, CRLF or CR-only endings, tabs, a UTF-8 BOM, latin-1 bytes, an include
loop, a missing include, ...). :func:`run_case` reads a case with
``read_deck`` and names the outcome: ``read``, ``DeckError``, ``traceback``
(any other exception: a bug) or ``hang`` (past the time limit: a bug).
Everything is decided by the ``random.Random`` passed in, so a seed
reproduces a case exactly.
"""

from __future__ import annotations

import random
import signal
import tempfile
import traceback
from contextlib import contextmanager
from importlib import resources
from pathlib import Path

OUTCOMES = ("read", "DeckError", "traceback", "hang")

# ------------------------------------------------------------------ seeds

_FAMILIES: dict[str, str] = {
    "mesh": """\
*KEYWORD
*NODE
       1             0.0             0.0             0.0       0       0
       2             1.0             0.0             0.0
       3             1.0             1.0             0.0       7       7
       4             0.0             1.0             0.0
       5             0.0             0.0             1.0
       6             1.0             0.0             1.0
       7             1.0             1.0             1.0
       8             0.0             1.0             1.0
*ELEMENT_SHELL
       1       1       1       2       3       4
       2       1       5       6       7
*ELEMENT_SHELL_THICKNESS
       3       1       1       2       6       5
             1.0             1.0             1.0             1.0            30.0
*ELEMENT_SOLID
      10       2       1       2       3       4       5       6       7       8
*ELEMENT_BEAM
      20       3       1       7       2
*ELEMENT_DISCRETE
      30       4       1       8       0             1.0       0             0.0
*ELEMENT_MASS
      40       3          0.5
*PART
shell
         1         1         1
*PART
solid
         2         2         1
*PART
beam
         3         3         1
*PART
spring
         4         4         2
*SECTION_SHELL
         1         2
       1.0
*SECTION_SOLID
         2         1
*SECTION_BEAM
         3         1
       1.0       1.0
*SECTION_DISCRETE
         4         0
*MAT_ELASTIC
         1   7.85e-9  210000.0       0.3
*MAT_SPRING_ELASTIC
         2    1000.0
*END
""",
    "free": """\
*KEYWORD
*NODE
1,0.0,0.0,0.0,0,0
2,1.0,0.0,0.0
3,2.0,0.0,0.0
*ELEMENT_DISCRETE
1,1,1,2,0,1.0,0,0.0
2,1,2,3
*PART
spring
1,1,1
*SECTION_DISCRETE
1,0
*MAT_SPRING_ELASTIC
1,1000.0
*END
""",
    "long": """\
*KEYWORD LONG=Y
*NODE
                   1                 0.0                 0.0                 0.0                   0                   0
                   2                 1.0                 0.0                 0.0
                   3                 1.0                 1.0                 0.0
                   4                 0.0                 1.0                 0.0
*ELEMENT_SHELL
                   1                   1                   1                   2                   3                   4
*PART
plate
                   1                   1                   1
*SECTION_SHELL
                   1                   2
                 1.0
*MAT_ELASTIC
                   1             7.85e-9            210000.0                 0.3
*END
""",
    "materials": """\
*KEYWORD
*MAT_PIECEWISE_LINEAR_PLASTICITY_TITLE
steel
         1   7.85e-9  210000.0       0.3     235.0     800.0
       0.0       0.0        10         0
*MAT_PLASTIC_KINEMATIC
         2   7.85e-9  210000.0       0.3     235.0     800.0
*MAT_RIGID
         3   7.85e-9  210000.0       0.3
       1.0         7         7
*MAT_CRUSHABLE_FOAM
         4   1.0e-10      10.0      0.01        10
*MAT_HONEYCOMB
         5   1.0e-10    1000.0       0.0       1.0       0.2
        10
    1000.0
*HOURGLASS
         1         4       0.1
*DEFINE_CURVE
        10
                 0.0                 1.0
                 1.0                 2.0
*END
""",
    "contacts": """\
*KEYWORD
*NODE
       1             0.0             0.0             0.0
       2             1.0             0.0             0.0
       3             1.0             1.0             0.0
       4             0.0             1.0             0.0
*SET_SEGMENT
         1
         1         2         3         4
*SET_NODE_LIST
         2
         1         2         3         4
*SET_PART_LIST
         3
         1
*PART
plate
         1         1         1
*SECTION_SHELL
         1
       1.0
*MAT_ELASTIC
         1   7.85e-9  210000.0       0.3
*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_ID
         1master
         1         3         0         2
       0.2       0.1
*CONTACT_AUTOMATIC_SINGLE_SURFACE
         3         0         2
*CONTACT_TIED_NODES_TO_SURFACE_OFFSET
         2         1         4         0
*END
""",
    "walls": """\
*KEYWORD
*NODE
       1             0.0             0.0             0.0
       2             1.0             0.0             0.0
*SET_NODE_LIST
         1
         1         2
*RIGIDWALL_PLANAR_ID
         1wall
         1
       0.0       0.0      -1.0       0.0       0.0       0.0       0.1
*RIGIDWALL_PLANAR_MOVING_FINITE
         0
       0.0       0.0       5.0       0.0       0.0       4.0
       1.0       0.0       0.0      10.0      10.0
       1.0    -100.0
*RIGIDWALL_GEOMETRIC_CYLINDER
         1
       0.0       0.0       0.0       0.0       0.0       1.0
       5.0      10.0
*INITIAL_VELOCITY
         1
       0.0       0.0     -10.0
*BOUNDARY_SPC_NODE
         1         0         1         1         1
*END
""",
    "sets": """\
*KEYWORD
*NODE
       1             0.0             0.0             0.0
       2             1.0             0.0             0.0
       3             2.0             0.0             0.0
*SET_NODE_LIST
         1
         1         2
*SET_NODE_GENERATE
         2
         1         3
*SET_NODE_ADD
         3
         1         2
*SET_PART_LIST
         4
         1
*PART
plate
         1         1         1
*SECTION_SHELL
         1
       1.0
*MAT_ELASTIC
         1   7.85e-9  210000.0       0.3
*BOUNDARY_SPC_SET
         3         0         1         1         1         1         1         1
*DATABASE_HISTORY_NODE
         1         2
*END
""",
    "parameters": """\
*KEYWORD
*PARAMETER
R t              1.5I n               3
R e         210000.0C name        steel
*PARAMETER_EXPRESSION
R half    t/2.0
I sq      n**2
R s       sin(pi/6)+max(t, 2.0)*e/1000.0
*PARAMETER_LOCAL
R loc          2.0
*NODE
       1             0.0             0.0             0.0
       2            &t             0.0             0.0
*MAT_ELASTIC
        &n   7.85e-9        &e       0.3
*SECTION_SHELL
         1         2
     &half     &half       -&t       &t
*END
""",
    "includes": """\
*KEYWORD
*PARAMETER
R x            1.0
*INCLUDE_PATH_RELATIVE
sub
*INCLUDE
part.k
*INCLUDE_TRANSFORM
part2.k
       100       100       100       100       100       100       100
         0
       1.0       1.0       1.0
         1
*DEFINE_TRANSFORMATION
         1
TRANSL          10.0       0.0       0.0
*END
""",
}

# one spring between two nodes: the smallest deck that reads (also the hostile-input tests' base)
SPRING = """\
*KEYWORD
*NODE
       1             0.0             0.0             0.0
       2             1.0             0.0             0.0
*ELEMENT_DISCRETE
       1       1       1       2
*PART
spring
         1         1         1
*SECTION_DISCRETE
         1         0
*MAT_SPRING_ELASTIC
         1    1000.0
*END
"""

_INCLUDED = {
    "part.k": SPRING.replace("       1             0.0", "       1            &x", 1),
    "sub/part2.k": SPRING.replace("*KEYWORD\n", "", 1),
}


def _examples() -> list[dict[str, bytes]]:
    out = []
    root = resources.files("crashlite") / "examples"
    for name in ("pulse", "impactor", "tube"):
        d = root / name
        files = {}
        for f in sorted(d.iterdir(), key=lambda p: p.name):
            if f.name.endswith(".k"):
                key = "main.k" if f.name == f"{name}.k" else f.name
                files[key] = f.read_bytes()
        if "main.k" in files:
            out.append(files)
    return out


def seeds() -> list[dict[str, bytes]]:
    """Every seed case: the bundled examples, then one per keyword family."""
    out = _examples()
    for fam, text in _FAMILIES.items():
        files = {"main.k": text.encode()}
        if fam == "includes":
            files.update({k: v.encode() for k, v in _INCLUDED.items()})
        out.append(files)
    return out


# ------------------------------------------------------------------ mutations

GARBAGE = (
    "abc",
    "1e999",
    "-1e999",
    "nan",
    "inf",
    "&nope",
    "-&nope",
    "&",
    "\x00",
    "1e",
    "1.2.3",
    "--1",
    "+",
    "-",
    ".",
    "e5",
    "0x10",
    "1,5",
    "99999999999999999999",
    "18446744073709551619",
    "-9223372036854775809",
    "2147483648",
    "0",
    "-1",
    "-7",
    "300",
    "8",
    "1.5",
    "1d3",
    "1.5-3",
    "\xa0.85e-09",
    "1\xa02",
    "\t1",
    "*",
    "$",
    "é",
    "\xff\xfe",
    "&x*2",
    "2**4000",
    "   ",
    "1e308",
    "4.9e-324",
    "-0",
    "1" * 400,
)

_RANDOM_LINES = (
    "*NODE",
    "*ELEMENT_SHELL",
    "*PART",
    "*END",
    "*KEYWORD",
    "*KEYWORD LONG=Y",
    "*KEYWORD I10=Y",
    "*INCLUDE",
    "*PARAMETER",
    "*PARAMETER_EXPRESSION",
    "*SET_NODE_LIST",
    "*SET_PART_ADD",
    "*SECTION_SHELL_TITLE",
    "*MAT_ELASTIC",
    "*CONTACT_AUTOMATIC_SINGLE_SURFACE",
    "*RIGIDWALL_PLANAR",
    "*DEFINE_CURVE",
    "*DEFINE_TRANSFORMATION",
    "*INCLUDE_TRANSFORM",
    "*INCLUDE_PATH",
    "*NODE +",
    "*ELEMENT_SOLID%",
    "*BOUNDARY_SPC_SET",
    "*CONSTRAINED_NODAL_RIGID_BODY",
    "*ELEMENT_MASS_NODE_SET",
    "*",
    "$ comment",
    "",
    ",,,,",
    "1,2,3,4,5,6,7,8,9,10,11,12",
    "R a       2**62",
    "I b       &b+1",
    "R c       1e300*1e300",
)


def _lines(data: bytes) -> list[bytes]:
    return data.split(b"\n")


def _join(lines: list[bytes]) -> bytes:
    return b"\n".join(lines)


def _pick_line(rng, lines) -> int:
    return rng.randrange(len(lines)) if lines else 0


def _printable(rng, n) -> bytes:
    return bytes(rng.randrange(32, 127) for _ in range(n))


def m_truncate(rng, files, name):
    d = files[name]
    files[name] = d[: rng.randrange(len(d) + 1)]


def m_delete_lines(rng, files, name):
    ln = _lines(files[name])
    i = _pick_line(rng, ln)
    del ln[i : i + rng.choice((1, 1, 2, 5))]
    files[name] = _join(ln)


def m_duplicate_lines(rng, files, name):
    ln = _lines(files[name])
    i = _pick_line(rng, ln)
    k = rng.choice((1, 1, 3))
    ln[i:i] = ln[i : i + k] * rng.choice((1, 2))
    files[name] = _join(ln)


def m_shift(rng, files, name):
    ln = _lines(files[name])
    if not ln:
        return
    i = _pick_line(rng, ln)
    ln[i] = (b" " * rng.choice((1, 2))) + ln[i] if rng.random() < 0.6 else ln[i][1:]
    files[name] = _join(ln)


def m_garbage(rng, files, name):
    """Garbage in a field: a fixed-width slice or a comma token replaced."""
    ln = _lines(files[name])
    cand = [i for i, x in enumerate(ln) if x and not x.startswith((b"*", b"$"))]
    if not cand:
        return
    i = rng.choice(cand)
    g = rng.choice(GARBAGE).encode("latin-1")
    line = ln[i]
    if b"," in line:
        toks = line.split(b",")
        toks[rng.randrange(len(toks))] = g
        ln[i] = b",".join(toks)
    else:
        w = rng.choice((8, 10, 16, 20))
        k = rng.randrange(max(1, (len(line) + w - 1) // w))
        ln[i] = line[: k * w] + g.rjust(w) + line[k * w + w :]
    files[name] = _join(ln)


def m_nul(rng, files, name):
    d = files[name]
    i = rng.randrange(len(d) + 1)
    files[name] = d[:i] + b"\x00" * rng.choice((1, 1, 4)) + d[i:]


def m_random_line(rng, files, name):
    ln = _lines(files[name])
    i = rng.randrange(len(ln) + 1)
    new = rng.choice(_RANDOM_LINES).encode() if rng.random() < 0.6 else _printable(rng, rng.randrange(1, 90))
    ln.insert(i, new)
    files[name] = _join(ln)


def m_swap_keyword(rng, files, name):
    ln = _lines(files[name])
    kws = [i for i, x in enumerate(ln) if x.startswith(b"*")]
    if kws:
        ln[rng.choice(kws)] = rng.choice(_RANDOM_LINES[:25]).encode()
        files[name] = _join(ln)


def m_crlf(rng, files, name):
    files[name] = files[name].replace(b"\r\n", b"\n").replace(b"\n", b"\r\n")


def m_cr_only(rng, files, name):
    files[name] = files[name].replace(b"\r\n", b"\n").replace(b"\n", b"\r")


def m_mixed_endings(rng, files, name):
    ln = _lines(files[name])
    files[name] = b"".join(x + rng.choice((b"\n", b"\r\n", b"\r")) for x in ln)


def m_tabs(rng, files, name):
    ln = _lines(files[name])
    for _ in range(rng.randrange(1, 4)):
        i = _pick_line(rng, ln)
        if ln:
            ln[i] = ln[i].replace(b"    ", b"\t", rng.randrange(1, 4))
    files[name] = _join(ln)


def m_bom(rng, files, name):
    files[name] = b"\xef\xbb\xbf" + files[name]


def m_latin1(rng, files, name):
    d = files[name]
    i = rng.randrange(len(d) + 1)
    files[name] = d[:i] + rng.choice((b"\xe9", b"\xa0", b"\xff", b"\xb5", b"\xc3\xa9", b"\x85")) + d[i:]


def m_include_loop(rng, files, name):
    # the main file includes a file that includes the main file back
    other = rng.choice([n for n in files if n != "main.k"] or ["loop.k"])
    files.setdefault(other, b"*KEYWORD\n")
    files[other] += b"\n*INCLUDE\nmain.k\n" if not other.startswith("sub/") else b"\n*INCLUDE\n../main.k\n"
    files["main.k"] = _insert_after_keyword(files["main.k"], b"*INCLUDE\n" + other.encode())


def m_self_include(rng, files, name):
    files[name] = _insert_after_keyword(files[name], b"*INCLUDE\n" + name.split("/")[-1].encode())


def m_missing_include(rng, files, name):
    files[name] = _insert_after_keyword(files[name], b"*INCLUDE\nnot_there.k")


def m_blank_include(rng, files, name):
    files[name] = _insert_after_keyword(
        files[name], rng.choice((b"*INCLUDE", b"*INCLUDE\n   ", b"*INCLUDE_TRANSFORM", b"*INCLUDE_PATH\n"))
    )


def m_include_odd(rng, files, name):
    """An include of a binary, empty, NUL-only or keyword-less file, or a folder."""
    kind = rng.randrange(5)
    for k in [k for k in files if k == "odd.k" or k.startswith("odd.k/")]:
        del files[k]  # a second include_odd replaces the first
    if kind == 0:
        files["odd.k"] = bytes(rng.randrange(256) for _ in range(rng.randrange(1, 300)))
    elif kind == 1:
        files["odd.k"] = b""
    elif kind == 2:
        files["odd.k"] = b"\x00" * rng.randrange(1, 200)
    elif kind == 3:
        files["odd.k"] = b"just some text\nwithout keywords\n"
    else:
        files["odd.k/inner.k"] = b"*KEYWORD\n"
    files["main.k"] = _insert_after_keyword(files["main.k"], b"*INCLUDE\nodd.k")


def m_whole_file(rng, files, name):
    """The main file replaced: binary, NUL bytes, empty, text without keywords."""
    kind = rng.randrange(4)
    files["main.k"] = (
        bytes(rng.randrange(256) for _ in range(rng.randrange(1, 500))),
        b"\x00" * rng.randrange(1, 500),
        b"",
        _printable(rng, 200),
    )[kind]


def m_parameter(rng, files, name):
    """A parameter chain with absurd magnitudes, or a self reference."""
    chain = rng.choice(
        (
            b"*PARAMETER_EXPRESSION\nI a       2**4000\nI b       a*a\nI c       b*b\nI d       c*c\n",
            b"*PARAMETER_EXPRESSION\nI a       2**62\nI b       a*a*a*a\nR c       b*1.0\n",
            b"*PARAMETER_EXPRESSION\nR a       1e300\nR b       a*a\n",
            b"*PARAMETER_EXPRESSION\nI a       a+1\n",
            b"*PARAMETER\nI big     99999999999999999999999\n",
            b"*PARAMETER\nR x       1e999\n",
            b"*PARAMETER_EXPRESSION\nR x       " + b"(" * 300 + b"1" + b")" * 300 + b"\n",
        )
    )
    files[name] = _insert_after_keyword(files[name], chain.rstrip(b"\n"))


def m_deep_include(rng, files, name):
    depth = rng.randrange(2, 40)
    for k in range(depth):
        files[f"d{k}.k"] = f"*KEYWORD\n*INCLUDE\nd{k + 1}.k\n*END\n".encode()
    files[f"d{depth}.k"] = b"*KEYWORD\n*END\n"
    files["main.k"] = _insert_after_keyword(files["main.k"], b"*INCLUDE\nd0.k")


def _insert_after_keyword(data: bytes, text: bytes) -> bytes:
    """``text`` (its own lines) after the *KEYWORD line, or at the top."""
    ln = _lines(data)
    at = next((i + 1 for i, x in enumerate(ln) if x.upper().startswith(b"*KEYWORD")), 0)
    ln[at:at] = _lines(text)
    return _join(ln)


MUTATIONS = {
    "truncate": (m_truncate, 6),
    "delete_lines": (m_delete_lines, 8),
    "duplicate_lines": (m_duplicate_lines, 6),
    "shift": (m_shift, 6),
    "garbage": (m_garbage, 14),
    "nul": (m_nul, 3),
    "random_line": (m_random_line, 6),
    "swap_keyword": (m_swap_keyword, 3),
    "crlf": (m_crlf, 2),
    "cr_only": (m_cr_only, 2),
    "mixed_endings": (m_mixed_endings, 1),
    "tabs": (m_tabs, 2),
    "bom": (m_bom, 2),
    "latin1": (m_latin1, 3),
    "include_loop": (m_include_loop, 1),
    "self_include": (m_self_include, 1),
    "missing_include": (m_missing_include, 1),
    "blank_include": (m_blank_include, 1),
    "include_odd": (m_include_odd, 1),
    "whole_file": (m_whole_file, 1),
    "parameter": (m_parameter, 2),
    "deep_include": (m_deep_include, 1),
}


def mutate(files: dict[str, bytes], rng: random.Random) -> tuple[dict[str, bytes], list[str]]:
    """A mutated copy of ``files`` and the names of the mutations applied."""
    files = dict(files)
    names = list(MUTATIONS)
    weights = [MUTATIONS[n][1] for n in names]
    applied = []
    for _ in range(rng.choice((1, 1, 1, 2, 2, 3))):
        m = rng.choices(names, weights)[0]
        target = rng.choice(sorted(files))
        MUTATIONS[m][0](rng, files, target)
        applied.append(m)
    return files, applied


def case(seed: int, index: int, pool: list[dict[str, bytes]] | None = None):
    """Case ``index`` of the run with ``seed``: (files, mutations applied)."""
    pool = seeds() if pool is None else pool
    rng = random.Random(f"{seed}:{index}")
    return mutate(pool[rng.randrange(len(pool))], rng)


# ------------------------------------------------------------------ running


class Hang(Exception):
    pass


@contextmanager
def time_limit(seconds: float):
    """Raise Hang in the main thread after ``seconds`` (Linux/macOS; no-op elsewhere)."""
    if not hasattr(signal, "setitimer"):
        yield
        return

    def on_alarm(signum, frame):
        raise Hang(f"still running after {seconds} s")

    old = signal.signal(signal.SIGALRM, on_alarm)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)


def write_case(files: dict[str, bytes], folder: Path) -> Path:
    for name, data in sorted(files.items()):
        p = folder / name
        try:
            p.parent.mkdir(parents=True, exist_ok=True)
            if not p.is_dir():
                p.write_bytes(data)
        except OSError:  # a file and a folder of the same name: the first one stays
            pass
    return folder / "main.k"


def run_case(files: dict[str, bytes], limit: float = 20.0, folder: Path | None = None):
    """Read one case: (outcome, detail). ``detail`` is the DeckError text,
    the traceback, or '' when the deck was read."""
    from .errors import DeckError
    from .reader import read_deck

    with tempfile.TemporaryDirectory(dir=folder) as tmp:
        main = write_case(files, Path(tmp))
        try:
            with time_limit(limit):
                read_deck(main)
        except DeckError as e:
            return "DeckError", str(e)
        except Hang:
            return "hang", traceback.format_exc()
        except RecursionError:
            return "traceback", traceback.format_exc(limit=-8)
        except Exception:  # noqa: BLE001 - anything else is what the fuzzer looks for
            return "traceback", traceback.format_exc()
    return "read", ""
