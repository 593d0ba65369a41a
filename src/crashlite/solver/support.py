"""Which deck cards the solver runs, which it passes over, and which it refuses.

A card that would change the physics but is not run by the solver is an
error before the first cycle (every such card listed), never silently
ignored. Bookkeeping cards and the outputs crashlite writes are accepted as
they are; cards that cannot change the solution but that crashlite does not
act on (other output requests, parallel and memory settings, sensors that no
*SENSOR_CONTROL uses) run with one warning per keyword, as LS-DYNA would run
them.
"""

from __future__ import annotations

from ..keyword.errors import Problem
from ..model.model import Model

# cards the solver reads (prefixes; element, part, section, material, set,
# curve and node tables are checked where they are built)
RUN = (
    "CONTROL_TERMINATION",
    "CONTROL_TIMESTEP",
    "CONTROL_HOURGLASS",
    "CONTROL_BULK_VISCOSITY",
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
    for rec in list(model.keywords) + list(model.unknown):
        name = _name(rec)
        file, line = _where(rec)
        if name.startswith(known) or (file, line, name) in seen:
            continue
        seen.add((file, line, name))
        if name.startswith(passed):
            if warnings is not None and name not in warned:
                warned.add(name)
                why = next(v for k, v in PASSED_OVER.items() if name.startswith(k))
                warnings.append(
                    Problem(
                        file or model.source or "", line, name, None, f"{PASSED}: {why}; it cannot change the solution"
                    )
                )
            continue
        problems.append(
            Problem(
                file or model.source or "",
                line,
                name,
                None,
                f"*{name} is not run by the crashlite solver yet; remove it or run the deck in LS-DYNA",
            )
        )
    return problems
