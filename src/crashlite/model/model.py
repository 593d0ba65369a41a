"""The Model: everything a deck defines, typed.

Mesh data live in struct-of-arrays tables (see ``mesh``). Entities that users
address by ID (parts, sections, materials, curves, sets, ...) are schema
records kept in dicts by ID. All other keywords (boundary conditions,
contacts, controls, outputs, and keywords crashlite does not type) are kept in
``keywords`` in deck order so that a written deck keeps their sequence.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from ..keyword.schema import RawKeyword, Record, records_equal
from .mesh import Beams, Discretes, Inertias, Masses, Nodes, Shells, Solids, index_map

if TYPE_CHECKING:
    from .mass import MassProperties

MESH_TABLES = ("nodes", "shells", "solids", "beams", "discretes", "masses", "inertias")
ENTITY_GROUPS = (
    "parts",
    "sections",
    "materials",
    "hourglasses",
    "curves",
    "vectors",
    "coordinate_systems",
    "transformations",
)


@dataclass(eq=False)
class Model:
    nodes: Nodes = field(default_factory=Nodes.empty)
    shells: Shells = field(default_factory=Shells.empty)
    solids: Solids = field(default_factory=Solids.empty)
    beams: Beams = field(default_factory=Beams.empty)
    discretes: Discretes = field(default_factory=Discretes.empty)
    masses: Masses = field(default_factory=Masses.empty)
    inertias: Inertias = field(default_factory=Inertias.empty)
    parts: dict[int, Record] = field(default_factory=dict)
    sections: dict[int, Record] = field(default_factory=dict)
    materials: dict[int, Record] = field(default_factory=dict)
    hourglasses: dict[int, Record] = field(default_factory=dict)
    curves: dict[int, Record] = field(default_factory=dict)
    vectors: dict[int, Record] = field(default_factory=dict)
    coordinate_systems: dict[int, Record] = field(default_factory=dict)
    transformations: dict[int, Record] = field(default_factory=dict)
    sets: dict[tuple[str, int], Record] = field(default_factory=dict)  # (kind, sid)
    keywords: list[Record | RawKeyword] = field(default_factory=list)
    parameters: list = field(default_factory=list)  # keyword.parameters.Parameter
    source: str | None = None  # file the model was read from
    files: list[str] = field(default_factory=list)  # every file read (includes)
    warnings: list = field(default_factory=list)  # keyword.errors.Problem

    # --- lookups -----------------------------------------------------------
    @property
    def title(self) -> str:
        for k in self.keywords:
            if isinstance(k, Record) and k.keyword == "TITLE":
                return k.get("title", "")
        return ""

    def node_index(self, ids: ArrayLike) -> np.ndarray:
        """0-based indices of deck node IDs (-1 where unknown)."""
        return index_map(self.nodes.ids)(ids)

    def find(self, keyword: str) -> list[Record]:
        """Records of ``keywords`` whose keyword name starts with ``keyword``."""
        kw = keyword.upper().lstrip("*")
        return [k for k in self.keywords if isinstance(k, Record) and k.name.startswith(kw)]

    @property
    def unknown(self) -> list[RawKeyword]:
        return [k for k in self.keywords if isinstance(k, RawKeyword)]

    def set_members(self, kind: str, sid: int) -> np.ndarray:
        """Deck IDs in a *SET_<kind> (LIST, GENERATE and ADD resolved)."""
        from .sets import set_members

        return set_members(self, kind.upper(), int(sid))

    def part_ids_of(self, parts: int | str | Iterable[int | str] | None) -> np.ndarray:
        """Part IDs from part IDs, part titles or None (all parts)."""
        if parts is None:
            return np.array(sorted(self.parts), dtype=np.int64)
        out = []
        titles = {str(r.get("heading", "")).strip().lower(): pid for pid, r in self.parts.items()}
        for p in [parts] if isinstance(parts, (int, str, np.integer)) else parts:
            if isinstance(p, str):
                key = p.strip().lower()
                if key not in titles:
                    raise KeyError(f"no part titled {p!r}")
                out.append(titles[key])
            else:
                if int(p) not in self.parts:
                    raise KeyError(f"no part with ID {int(p)}")
                out.append(int(p))
        return np.array(out, dtype=np.int64)

    # --- derived quantities ------------------------------------------------
    def mass_properties(self, parts: int | str | Iterable[int | str] | None = None) -> MassProperties:
        """Mass, centre of gravity and inertia tensor about the CoG.

        ``parts``: None (whole model), part IDs or titles. Point masses and
        inertias count with the whole model, or with a part when their PID
        names it. See ``model.properties``.
        """
        from .properties import mass_properties

        return mass_properties(self, parts)

    def unit_system(self) -> str:
        """Guess of the unit system from material densities."""
        from .properties import guess_units

        return guess_units(self)

    def __eq__(self, other) -> bool:
        return models_equal(self, other)

    def counts(self) -> dict[str, int]:
        out = {t: len(getattr(self, t)) for t in MESH_TABLES}
        out.update({g: len(getattr(self, g)) for g in ENTITY_GROUPS})
        out["sets"] = len(self.sets)
        out["keywords"] = len(self.keywords)
        return out


# --- value-by-value equality of models (NaN equals NaN) --------------------
def _raw_key(raw):
    """A verbatim keyword's content, independent of how its format was marked."""
    rest = raw.keyword_line.split(None, 1)[1:] or [""]
    return raw.keyword, rest[0].rstrip(), raw.mode, [ln.rstrip() for ln in raw.lines]


def model_differences(a: Model, b: Model) -> list[str]:
    """What differs between two models (empty: equal)."""
    out = []
    for t in MESH_TABLES:
        if not getattr(a, t).equals(getattr(b, t)):
            out.append(f"{t} differ")
    for g in (*ENTITY_GROUPS, "sets"):
        da, db = getattr(a, g), getattr(b, g)
        if da.keys() != db.keys():
            out.append(f"{g}: IDs differ ({sorted(set(da) ^ set(db))[:10]})")
            continue
        for k in da:
            if not records_equal(da[k], db[k]):
                out.append(f"{g}[{k}] differs")
    ka, kb = a.keywords, b.keywords
    if len(ka) != len(kb):
        out.append(f"keywords: {len(ka)} vs {len(kb)}")
    else:
        for x, y in zip(ka, kb):
            if isinstance(x, RawKeyword) and isinstance(y, RawKeyword):
                if _raw_key(x) != _raw_key(y):
                    out.append(f"verbatim *{x.keyword} differs")
            elif type(x) is not type(y) or not records_equal(x, y):
                out.append(f"*{getattr(x, 'name', x.keyword)} differs from *{getattr(y, 'name', y.keyword)}")
    return out


def models_equal(a: Model, b: Model) -> bool:
    return not model_differences(a, b)
