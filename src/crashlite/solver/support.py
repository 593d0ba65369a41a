"""Which deck cards the solver runs, which it passes over, and which it refuses.

A card that would change the physics but is not run by the solver is an
error before the first cycle (every such card listed), never silently
ignored. Bookkeeping cards and the outputs crashlite writes are accepted as
they are; cards that cannot change the solution but that crashlite does not
act on (other output requests, parallel and memory settings, sensors that no
*SENSOR_CONTROL uses) run with one warning per keyword, as LS-DYNA would run
them.

A card the reader keeps verbatim (a keyword or option it does not type,
e.g. *PART_ADAPTIVE_FAILURE, *INITIAL_VELOCITY_GENERATION_START_TIME) is
never taken as run, whatever its prefix: the solver reads typed cards
only. Definitions that other cards name by ID (materials, sections, curves,
tables, boxes, sets …) are passed over with a warning while nothing the
solver runs names them; a part naming an unread material, section,
equation of state or hourglass set is refused, naming both.
"""

from __future__ import annotations

from ..keyword.errors import Problem
from ..keyword.schema import RawKeyword
from ..model.model import Model

# cards the solver reads (prefixes; element, part, section, material, set,
# curve and node tables are checked where they are built)
RUN = (
    "CONTROL_TERMINATION",
    "CONTROL_TIMESTEP",
    "CONTROL_HOURGLASS",
    "CONTROL_SHELL",
    "BOUNDARY_SPC",
    "BOUNDARY_PRESCRIBED_MOTION",
    "INITIAL_VELOCITY",
    "CONSTRAINED_NODAL_RIGID_BODY",
    "CONSTRAINED_EXTRA_NODES",
    "CONSTRAINED_RIGID_BODIES",
    "RIGIDWALL_PLANAR",
    "RIGIDWALL_GEOMETRIC_CYLINDER",
    "LOAD_BODY_",
    "LOAD_NODE_POINT",
    "LOAD_NODE_SET",
    "DEFINE_",
    "SET_",
    "PART",
    "SECTION_",
    "MAT_",
    "HOURGLASS",
    "PARAMETER",
    "INCLUDE",
    "CONTACT_AUTOMATIC_SINGLE_SURFACE",
    "CONTACT_AUTOMATIC_NODES_TO_SURFACE",
    "CONTACT_AUTOMATIC_SURFACE_TO_SURFACE",
    "CONTROL_CONTACT",
    "CONTACT_TIED_",
    "CONSTRAINED_SPOTWELD",
    "CONSTRAINED_GENERALIZED_WELD",
    "ELEMENT_DIRECT_MATRIX_INPUT",
    "PART_MOVE",
    "INITIAL_VELOCITY_RIGID_BODY",
    "ELEMENT_MASS_PART",
)
# bookkeeping and the outputs crashlite writes: accepted without a word
NEUTRAL = (
    "KEYWORD",
    "TITLE",
    "END",
    "COMMENT",
    "CONTROL_ENERGY",
    "KEYWORD_ID",
    "DATABASE_GLSTAT",
    "DATABASE_MATSUM",
    "DATABASE_NODOUT",
    "DATABASE_RWFORC",
    "DATABASE_SECFORC",
    "DATABASE_DEFORC",
    "DATABASE_RCFORC",
    "DATABASE_SPCFORC",
    "DATABASE_HISTORY_NODE",
    "DATABASE_BINARY_D3PLOT",
    "DATABASE_CROSS_SECTION",
)
# run although the reader keeps them verbatim: the reader resolves parameters and includes
READ_VERBATIM = ("PARAMETER", "INCLUDE")
# definitions that act only through a card naming them (see the module text); the PART field naming each kind
DEFINITIONS = {"MAT_": "mid", "SECTION_": "secid", "EOS_": "eosid", "HOURGLASS": "hgid", "DEFINE_": None, "SET_": None}
PASSED = "passed over"  # how a passed-over card's warning begins (run() names each card once)
# cards that cannot change the solution but are not acted on: keyword -> why (one warning each)
PASSED_OVER = {
    "DATABASE_": "an output crashlite does not write",
    "CONTROL_OUTPUT": "output settings of LS-DYNA's own files",
    "CONTROL_CPU": "a CPU-time limit",
    "CONTROL_PARALLEL": "parallel settings",
    "CONTROL_MPP": "MPP decomposition settings",
    "CONTROL_UNITS": "a statement of the deck's units",
    "INTERFACE_SPRINGBACK": "a springback output file",
    # sensors act only through *SENSOR_CONTROL, which is refused when present
    "SENSOR_DEFINE_": "a sensor that no *SENSOR_CONTROL uses",
    "SENSOR_SWITCH": "a sensor switch that no *SENSOR_CONTROL uses",
}


def _solution(rec) -> str | None:
    """*CONTROL_SOLUTION: SOLN 0 (structural) is what crashlite runs; a thermal analysis is refused."""
    soln = int(rec.get("soln") or 0)
    if soln != 0:
        return f"SOLN {soln} (a thermal or coupled analysis) is not run by crashlite: only SOLN 0, structural"
    return None


def _shell_bulk_viscosity(rec) -> str | None:
    """The warning of a *CONTROL_BULK_VISCOSITY whose TYPE asks for it on shells too."""
    if int(rec.get("type") or 1) < 0:
        return (
            f"TYPE {int(rec.get('type'))}: LS-DYNA also damps the shells' membrane compression with Q1, Q2; "
            "crashlite applies the bulk viscosity to solids only"
        )
    return None


# typed cards run with one warning (the text, or what the function returns: None, no warning) unless the
# check (None: none) names a setting crashlite does not run: then they are refused with its text
RUN_WITH_WARNING = {
    "CONTROL_BULK_VISCOSITY": (None, _shell_bulk_viscosity),
    "CONTROL_SOLUTION": (
        _solution,
        "SOLN 0 is crashlite's analysis; NLQ (vector length), ISNAN (NaN check) and LCINT (LS-DYNA resamples "
        "curves to LCINT points, crashlite uses them as given) cannot change the solution",
    ),
    "CONTROL_ACCURACY": (
        None,
        "crashlite's shells take their corotational frame from the side 1-2 (INN 1) and update stresses "
        "incrementally in it (OSU 0): the invariant frame (INN 2-4) follows the diagonals instead, which changes "
        "the stresses only in elements sheared in their plane (by the order of the shear angle), and the "
        "second-order objective update (OSU 1) matters only for rotations that are large within one step",
    ),
}


def _name(rec) -> str:
    name = getattr(rec, "keyword", None)
    if name is None:  # raw card kept as read: "*NAME_OPTION ..." line
        name = rec.keyword_line.split()[0].lstrip("*")
    return name.upper()


def _where(rec) -> tuple[str, int]:
    src = getattr(rec, "source", None)
    if src:
        return str(src[0]), int(src[1])
    return "", 0


def unsupported_cards(model: Model, extra_run: tuple[str, ...] = (), warnings: list | None = None) -> list[Problem]:
    """One Problem per card the solver does not run (``extra_run``: more
    prefixes run by element families and constraints built elsewhere); one
    warning per keyword passed over (appended to ``warnings``)."""
    known = RUN + NEUTRAL + tuple(extra_run)
    passed = tuple(PASSED_OVER)
    problems, seen, warned = [], set(), set()

    def warn(file, line, name, why):
        if warnings is not None and name not in warned:
            warned.add(name)
            warnings.append(
                Problem(file or model.source or "", line, name, None, f"{PASSED}: {why}; it cannot change the solution")
            )

    for rec in list(model.keywords) + list(model.unknown):
        name = _name(rec)
        file, line = _where(rec)
        raw = isinstance(rec, RawKeyword)  # kept verbatim: an option or variant the reader does not type
        if name.startswith(NEUTRAL + READ_VERBATIM if raw else known) or (file, line, name) in seen:
            continue
        seen.add((file, line, name))
        if name in RUN_WITH_WARNING and not raw:
            check, why = RUN_WITH_WARNING[name]
            refused = check(rec) if check else None
            if refused:
                problems.append(Problem(file or model.source or "", line, name, None, refused))
            elif callable(why):
                said = why(rec)
                if said and warnings is not None:
                    warnings.append(Problem(file or model.source or "", line, name, "TYPE", said))
            elif warnings is not None and name not in warned:
                warned.add(name)
                warnings.append(Problem(file or model.source or "", line, name, None, f"run as crashlite runs: {why}"))
            continue
        if name.startswith(passed):
            warn(file, line, name, next(v for k, v in PASSED_OVER.items() if name.startswith(k)))
            continue
        kind = next((k for k in DEFINITIONS if name.startswith(k)), None) if raw else None
        if kind is not None:
            users = _parts_naming(model, rec, DEFINITIONS[kind])
            if not users:
                warn(file, line, name, "a definition crashlite does not read, and no card the solver runs names it")
                continue
            why = f"*{name} is not run by the crashlite solver yet, and part(s) {', '.join(map(str, users))} use it"
        else:
            why = f"*{name} is not run by the crashlite solver yet; remove it or run the deck in LS-DYNA"
        problems.append(Problem(file or model.source or "", line, name, None, why))
    return problems


def _parts_naming(model: Model, raw: RawKeyword, part_field: str | None) -> list[int]:
    """The parts whose ``part_field`` names the ID on the first data card of
    an unread definition (curves, tables, boxes and sets: none are checked
    here, the card naming one fails where it is built)."""
    if part_field is None or not raw.lines:
        return []
    title = "TITLE" in raw.keyword.split("_")
    lines = [ln for ln in raw.lines if ln.strip() and not ln.lstrip().startswith("$")]
    if len(lines) <= title:
        return []
    first = lines[int(title)]
    text = first.split(",")[0] if "," in first else first[:10]
    try:
        ident = int(float(text))
    except ValueError:
        return []
    return sorted(pid for pid, p in model.parts.items() if int(p.get(part_field) or 0) == ident)
