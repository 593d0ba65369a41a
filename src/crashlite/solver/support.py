"""Which deck cards the solver runs, and which it refuses.

A card that would change the physics but is not run by the solver is an
error before the first cycle (every such card listed), never silently
ignored. Output requests and bookkeeping cards are accepted as they are.
"""

from __future__ import annotations

from ..keyword.errors import Problem
from ..model.model import Model

# cards the solver reads (prefixes; element, part, section, material, set,
# curve and node tables are checked where they are built)
RUN = (
    "CONTROL_TERMINATION", "CONTROL_TIMESTEP", "CONTROL_HOURGLASS", "CONTROL_BULK_VISCOSITY", "CONTROL_SHELL",
    "BOUNDARY_SPC", "BOUNDARY_PRESCRIBED_MOTION", "INITIAL_VELOCITY",
    "CONSTRAINED_NODAL_RIGID_BODY", "CONSTRAINED_EXTRA_NODES", "CONSTRAINED_RIGID_BODIES",
    "RIGIDWALL_PLANAR", "RIGIDWALL_GEOMETRIC_CYLINDER", "LOAD_BODY_", "LOAD_NODE_POINT", "LOAD_NODE_SET",
    "DEFINE_", "SET_", "PART", "SECTION_", "MAT_", "HOURGLASS", "PARAMETER", "INCLUDE",
    "CONTACT_AUTOMATIC_SINGLE_SURFACE", "CONTACT_AUTOMATIC_NODES_TO_SURFACE",
    "CONTACT_AUTOMATIC_SURFACE_TO_SURFACE", "CONTROL_CONTACT",
    "CONTACT_TIED_", "CONSTRAINED_SPOTWELD", "CONSTRAINED_GENERALIZED_WELD", "ELEMENT_DIRECT_MATRIX_INPUT",
)
# cards with no effect on the mechanics: output requests, run controls of other codes
NEUTRAL = (
    "KEYWORD", "TITLE", "END", "COMMENT", "DATABASE_", "CONTROL_OUTPUT", "CONTROL_ENERGY", "CONTROL_CPU",
    "CONTROL_PARALLEL", "CONTROL_MPP", "KEYWORD_ID",
)


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


def unsupported_cards(model: Model, extra_run: tuple[str, ...] = ()) -> list[Problem]:
    """One Problem per card the solver does not run (``extra_run``: more
    prefixes run by element families and constraints built elsewhere)."""
    known = RUN + NEUTRAL + tuple(extra_run)
    problems, seen = [], set()
    for rec in list(model.keywords) + list(model.unknown):
        name = _name(rec)
        file, line = _where(rec)
        if name.startswith(known) or (file, line, name) in seen:
            continue
        seen.add((file, line, name))
        problems.append(Problem(file or model.source or "", line, name, None,
                                f"*{name} is not run by the crashlite solver yet; remove it or run the deck "
                                "in LS-DYNA"))
    return problems
