"""Responses: named scalars extracted from a design's run and model.

Types (``type = ...`` in ``[responses.NAME]``):

=================== =====================================================
``mass``            mass of ``parts`` (names or IDs; default the model)
``part_energy``     internal energy of ``parts`` (matsum), summed
``energy``          a glstat ``quantity``: kinetic, internal, total,
                    hourglass, sliding, wall, external
``wall_force``      rigid wall ``id`` (default the first) force
``section_force``   cross section ``id`` force (secforc)
``discrete_force``  discrete element ``id`` axial force (deforc)
``contact_force``   contact interface ``id`` slave-side force (rcforc; ``id``
                    is the contact's CID, else its place among the deck's
                    contacts: ``model.contacts``)
``node_displacement`` history ``node`` displacement (final: any node; an
                    LS-DYNA run's from its d3plot where not a history node)
``node_velocity``   history ``node`` velocity
``intrusion``       largest displacement of ``nodes`` (IDs) or node ``set``,
                    optionally relative to a ``reference`` node
``deceleration``    CFC-filtered (``cfc``, default 60) peak deceleration
                    of history ``node`` along its direction of travel
``pulse``           a crash-pulse ``figure`` of history ``node``:
                    peak_deceleration, mean_deceleration, dynamic_crush,
                    olc, time_to_zero_velocity
``expression``      arithmetic of earlier responses and the variables
=================== =====================================================

Time histories reduce with ``stat``: max (default for forces), min, absmax,
final, mean; vectors take ``component`` x, y, z or magnitude (forces on a
wall default to the normal force). ``cfc`` filters a history before its
reduction (J211, Hz). Every response takes ``scale`` (a factor, e.g. 1000
for tonne → kg) and ``unit`` (a label for plots and tables); decelerations
are in g unless ``unit = "model"``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from ..model.model import Model
    from ..results.d3plot import FinalState
    from ..solver.results import Results
    from ..units import UnitSystem

TYPES = (
    "mass",
    "part_energy",
    "energy",
    "wall_force",
    "section_force",
    "discrete_force",
    "contact_force",
    "node_displacement",
    "node_velocity",
    "intrusion",
    "deceleration",
    "pulse",
    "expression",
)
STATS = ("max", "min", "absmax", "final", "mean")
COMPONENTS = ("x", "y", "z", "magnitude", "normal")
ENERGIES = ("kinetic", "internal", "total", "hourglass", "sliding", "wall", "external")
PULSE_FIGURES = ("peak_deceleration", "mean_deceleration", "dynamic_crush", "olc", "time_to_zero_velocity")
_KEYS = {
    "mass": ("parts",),
    "part_energy": ("parts", "stat"),
    "energy": ("quantity", "stat"),
    "wall_force": ("id", "component", "stat", "cfc"),
    "section_force": ("id", "component", "stat", "cfc"),
    "discrete_force": ("id", "stat", "cfc"),
    "contact_force": ("id", "component", "stat", "cfc"),
    "node_displacement": ("node", "component", "stat"),
    "node_velocity": ("node", "component", "stat"),
    "intrusion": ("nodes", "set", "reference", "component", "over"),
    "deceleration": ("node", "component", "cfc"),
    "pulse": ("node", "component", "cfc", "figure"),
    "expression": ("expression",),
}
G_MM_S2 = 9806.65


class ResponseError(RuntimeError):
    """A response that cannot be taken from a run (the run's design fails)."""


@dataclass
class ResponseSpec:
    name: str
    type: str
    options: dict = field(default_factory=dict)
    scale: float = 1.0
    unit: str = ""

    def get(self, key: str, default: Any = None) -> Any:
        v = self.options.get(key)
        return default if v is None else v

    def describe(self) -> dict:
        return {"type": self.type, **self.options, "scale": self.scale, "unit": self.unit}

    def depends_on(self) -> list[str]:
        if self.type != "expression":
            return []
        from ..keyword.expression import names_used

        return sorted(names_used(self.options["expression"]))

    @property
    def label(self) -> str:
        return f"{self.name} [{self.unit}]" if self.unit else self.name


def parse_response(name: str, t: dict) -> ResponseSpec:
    """A ResponseSpec from its TOML table; ValueError names the key."""
    typ = t.get("type")
    if typ not in TYPES:
        raise ValueError(f"type {typ!r} is not a response type; known: {', '.join(TYPES)}")
    allowed = ("type", "scale", "unit") + _KEYS[typ]
    extra = [k for k in t if k not in allowed]
    if extra:
        raise ValueError(f"unknown key(s) {', '.join(map(repr, extra))} for type {typ!r} (known: {', '.join(allowed)})")
    opts = {k: t[k] for k in _KEYS[typ] if k in t}
    scale = t.get("scale", 1.0)
    if isinstance(scale, bool) or not isinstance(scale, (int, float)) or not math.isfinite(scale) or scale == 0:
        raise ValueError(f"scale must be a non-zero number, got {scale!r}")
    unit = t.get(
        "unit",
        "g"
        if typ == "deceleration"
        or (typ == "pulse" and "deceleration" in str(t.get("figure", "")) or t.get("figure") == "olc")
        else "",
    )
    if not isinstance(unit, str):
        raise ValueError(f"unit must be a string, got {unit!r}")
    if "stat" in opts and opts["stat"] not in STATS:
        raise ValueError(f"stat {opts['stat']!r} is not one of {', '.join(STATS)}")
    if "component" in opts and opts["component"] not in COMPONENTS:
        raise ValueError(f"component {opts['component']!r} is not one of {', '.join(COMPONENTS)}")
    if "component" in opts and opts["component"] == "normal" and typ != "wall_force":
        raise ValueError("component 'normal' applies to wall_force")
    if typ == "energy":
        if opts.get("quantity") not in ENERGIES:
            raise ValueError(f"quantity {opts.get('quantity')!r} is not one of {', '.join(ENERGIES)}")
    if typ == "pulse" and opts.get("figure") not in PULSE_FIGURES:
        raise ValueError(f"figure {opts.get('figure')!r} is not one of {', '.join(PULSE_FIGURES)}")
    for key in ("id", "node", "reference", "set"):
        if key in opts and (isinstance(opts[key], bool) or not isinstance(opts[key], int)):
            raise ValueError(f"{key} must be an integer ID, got {opts[key]!r}")
    if typ in ("node_displacement", "node_velocity", "deceleration", "pulse") and "node" not in opts:
        raise ValueError("node: missing (a node ID)")
    if typ == "intrusion":
        if ("nodes" in opts) == ("set" in opts):
            raise ValueError("give nodes = [IDs] or set = node set ID")
        if "nodes" in opts and (
            not isinstance(opts["nodes"], list)
            or not opts["nodes"]
            or not all(isinstance(n, int) and not isinstance(n, bool) for n in opts["nodes"])
        ):
            raise ValueError(f"nodes must be a list of node IDs, got {opts['nodes']!r}")
        if opts.get("over", "final") not in ("final", "history"):
            raise ValueError(f"over must be 'final' or 'history', got {opts.get('over')!r}")
    if "parts" in opts:
        p = opts["parts"]
        p = p if isinstance(p, list) else [p]
        if not p or not all(isinstance(x, (str, int)) and not isinstance(x, bool) for x in p):
            raise ValueError(f"parts must be part names or IDs, got {opts['parts']!r}")
        opts["parts"] = p
    if "cfc" in opts and (
        isinstance(opts["cfc"], bool) or not isinstance(opts["cfc"], (int, float)) or opts["cfc"] <= 0
    ):
        raise ValueError(f"cfc must be a positive number of Hz, got {opts['cfc']!r}")
    if typ == "expression":
        text = opts.get("expression")
        if not isinstance(text, str) or not text.strip():
            raise ValueError("expression: missing (arithmetic of earlier responses and variables)")
        from ..keyword.expression import ExpressionError, names_used

        try:
            names_used(text)
        except ExpressionError as e:
            raise ValueError(f"expression {text!r}: {e}") from None
    return ResponseSpec(name, typ, opts, float(scale), unit)


# --- checks against the deck ---------------------------------------------------


def history_node_ids(model: Model) -> set[int]:
    """Deck IDs of the nodes a run records in nodout."""
    out: set[int] = set()
    for rec in model.find("DATABASE_HISTORY_NODE"):
        ids = []
        if rec.rows:
            for k, col in rec.rows.items():
                if k.startswith("id"):
                    ids += [int(v) for v in np.asarray(col).ravel() if v is not None and int(v) > 0]
        if "SET" in rec.options:
            for sid in ids:
                out.update(int(n) for n in model.set_members("NODE", sid))
        else:
            out.update(ids)
    return out


def check_response(spec: ResponseSpec, model: Model, variables: list[str], responses: list[str]) -> None:
    """ValueError (naming the key) where the deck lacks what the response reads."""
    t, o = spec.type, spec.options
    if "parts" in o:
        try:
            model.part_ids_of(o["parts"])
        except KeyError as e:
            titles = ", ".join(repr(str(r.get("heading", "")).strip()) for r in model.parts.values())
            raise ValueError(f"parts: {e.args[0]} in the deck (parts: {titles})") from None
    node_ids = set(model.nodes.ids.tolist())
    hist = None
    for key in ("node", "reference"):
        if key in o:
            if o[key] not in node_ids:
                raise ValueError(f"{key}: node {o[key]} is not in the deck")
            needs_history = (
                t in ("deceleration", "pulse", "node_velocity")
                or o.get("stat", "final") != "final"
                or (t == "intrusion" and o.get("over", "final") == "history")
            )
            if needs_history:
                hist = history_node_ids(model) if hist is None else hist
                if o[key] not in hist:
                    raise ValueError(
                        f"{key}: node {o[key]} is not a history node: add it to "
                        f"*DATABASE_HISTORY_NODE (its time history is needed)"
                    )
    if t == "intrusion":
        members = o.get("nodes")
        if "set" in o:
            if ("NODE", o["set"]) not in model.sets:
                raise ValueError(f"set: *SET_NODE {o['set']} is not in the deck")
            members = model.set_members("NODE", o["set"]).tolist()
        missing = [n for n in members if n not in node_ids]
        if missing:
            raise ValueError(f"nodes: {', '.join(map(str, missing[:10]))} not in the deck")
        if o.get("over") == "history":
            hist = history_node_ids(model) if hist is None else hist
            lack = [n for n in members if n not in hist]
            if lack:
                raise ValueError(
                    f"over = 'history' needs history nodes; {', '.join(map(str, lack[:10]))} "
                    f"are not in *DATABASE_HISTORY_NODE"
                )
    if t == "wall_force" and "id" in o:
        walls = [r.values.get("rwid") for r in model.find("RIGIDWALL")]
        ids = [w for w in walls if w]
        if o["id"] not in ids and not (not ids and 1 <= o["id"] <= len(walls)):
            raise ValueError(f"id: rigid wall {o['id']} is not in the deck (walls: {ids or len(walls)})")
    if t == "wall_force" and not model.find("RIGIDWALL"):
        raise ValueError("the deck has no rigid wall")
    if t == "section_force":
        secs = [r.values.get("csid") for r in model.find("DATABASE_CROSS_SECTION")]
        if not secs:
            raise ValueError("the deck has no *DATABASE_CROSS_SECTION")
        if "id" in o and o["id"] not in secs:
            raise ValueError(f"id: cross section {o['id']} is not in the deck (sections: {secs})")
    if t == "discrete_force" and "id" in o:
        ids = model.discretes.ids.tolist()
        if o["id"] not in ids:
            raise ValueError(f"id: discrete element {o['id']} is not in the deck")
        if int(model.discretes.pf[ids.index(o["id"])]) == 1:
            raise ValueError(f"id: discrete element {o['id']} has PF 1 (*ELEMENT_DISCRETE): DEFORC does not print it")
    if t == "expression":
        for n in spec.depends_on():
            if n not in responses and n not in variables:
                raise ValueError(f"expression names {n!r}: neither a response nor a variable")


# the *DATABASE_ keyword an external solver needs to write what a response reads
EXTERNAL_OUTPUT = {
    "energy": "GLSTAT",
    "part_energy": "MATSUM",
    "wall_force": "RWFORC",
    "section_force": "SECFORC",
    "discrete_force": "DEFORC",
    "node_displacement": "NODOUT",
    "node_velocity": "NODOUT",
    "deceleration": "NODOUT",
    "pulse": "NODOUT",
    "intrusion": "NODOUT",
    "contact_force": "RCFORC",
}


def final_nodes(spec: ResponseSpec, model: Model) -> list[int]:
    """The nodes whose final displacement a response takes (with its
    reference node last); empty for other responses."""
    t, o = spec.type, spec.options
    final = (t == "node_displacement" and o.get("stat", "final") == "final") or (
        t == "intrusion" and o.get("over", "final") == "final"
    )
    if not final:
        return []
    nodes = (
        [o["node"]]
        if "node" in o
        else (model.set_members("NODE", o["set"]).tolist() if "set" in o else list(o["nodes"]))
    )
    return nodes + ([o["reference"]] if "reference" in o else [])


def reads_d3plot(spec: ResponseSpec, model: Model) -> bool:
    """True where an external solver's run gives the response from its
    d3plot's final state: a final displacement of a node that is not a
    history node (nodout has the history nodes only)."""
    nodes = final_nodes(spec, model)
    return bool(nodes) and not set(nodes) <= history_node_ids(model)


def _contact_card(spec: ResponseSpec, model: Model, solver: str = "lsdyna"):
    """The deck's contact card a contact_force response names, numbered as
    rcforc numbers them (``model.contacts``: its CID, else its place among
    the contact interfaces); None where a verbatim card's ID is unknown.
    ValueError where the deck lacks it or the run writes no force for it."""
    from ..model.contacts import contact_cards, duplicates

    cards = contact_cards(model)
    known = all(c.known for c in cards)
    if not cards:
        raise ValueError("the deck has no *CONTACT_ card")
    wanted = spec.get("id")
    if wanted is None:  # the first interface rcforc has: the first that is not single surface
        card = next((c for c in cards if not c.single_surface), cards[0])
    else:
        hits = [c for c in cards if c.number == wanted]
        if not hits:
            if known:
                numbers = sorted({c.number for c in cards})
                raise ValueError(f"id: contact interface {wanted} is not in the deck (interfaces: {numbers})")
            return None
        if len(hits) > 1 or wanted in duplicates(cards):
            names = ", ".join(f"*{c.keyword} (place {c.place})" for c in hits)
            raise ValueError(
                f"id: contact interface {wanted} is ambiguous: {names} (a contact without an ID is numbered "
                "by its place among the deck's contacts, which here is another contact's ID): give every "
                "contact an _ID"
            )
        card = hits[0]
    if card.single_surface:
        raise ValueError(
            f"id: contact interface {card.number} is a single surface contact (*{card.keyword}), for which "
            "LS-DYNA writes no resultant in rcforc (its forces cancel): measure it with a "
            "*CONTACT_FORCE_TRANSDUCER_PENALTY"
        )
    if solver == "openradioss":
        _openradioss_interface(card, cards)
    return card


def _openradioss_interface(card, cards) -> int:
    """The /INTER ID OpenRadioss's LS-DYNA reader gives ``card`` (its time
    history's interface); ValueError saying why where it cannot be known."""
    from ..model.contacts import openradioss_ids

    unknown = [c for c in cards if not c.known]
    if unknown:
        raise ValueError(
            f"id: the /INTER ID OpenRadioss gives *{card.keyword} cannot be known: the ID of "
            f"*{unknown[0].keyword} (a card crashlite keeps verbatim) could not be read, and OpenRadioss "
            "numbers contacts without an ID after the largest ID: give every contact an _ID with a CID"
        )
    if not card.converted_by_openradioss:
        raise ValueError(
            f"id: OpenRadioss's LS-DYNA reader makes no interface of *{card.keyword}, so its time history "
            'has no force for it: use wall_force or section_force, or solver = "crashlite" or "lsdyna"'
        )
    return openradioss_ids(cards)[card.number]


def check_external_response(spec: ResponseSpec, model: Model, solver: str) -> None:
    """ValueError where a run of the deck in an external solver (LS-DYNA,
    OpenRadioss: its time histories are read, ``results.from_history``,
    and LS-DYNA's d3plot for final displacements of other nodes) cannot
    give the response."""
    from ..external import NAMES

    name = NAMES.get(solver, solver)
    t = spec.type
    if t == "contact_force":
        _contact_card(spec, model, solver)
    d3plot = reads_d3plot(spec, model)
    if d3plot:
        _check_d3plot(spec, model, name, solver)
    kw = EXTERNAL_OUTPUT.get(t)
    if kw and not d3plot and not model.find(f"DATABASE_{kw}"):
        raise ValueError(
            f"{t} reads {kw.lower()}, which {name} writes only when the deck asks for it: add *DATABASE_{kw}"
        )


def _check_d3plot(spec: ResponseSpec, model: Model, name: str, solver: str) -> None:
    """The final displacement of nodes that are not history nodes comes
    from the d3plot's final state: the deck must ask for one."""
    hist = history_node_ids(model)
    lack = ", ".join([str(n) for n in final_nodes(spec, model) if n not in hist][:10])
    if solver != "lsdyna":
        raise ValueError(
            f"the final displacement of node(s) {lack}: an {name} run gives it for history nodes only "
            "(nodout): add them to *DATABASE_HISTORY_NODE"
        )
    if not model.find("DATABASE_BINARY_D3PLOT"):
        raise ValueError(
            f"the final displacement of node(s) {lack}: an {name} run gives it for history nodes (nodout) "
            "and, from the d3plot's final state, for any node, but the deck asks for no d3plot: add "
            "*DATABASE_BINARY_D3PLOT, or add the nodes to *DATABASE_HISTORY_NODE"
        )
    from ..results.d3plot import MISSING, lasso

    if lasso() is None:
        raise ValueError(f"the final displacement of node(s) {lack} is read from the d3plot, and {MISSING}")


# --- evaluation ----------------------------------------------------------------


def _reduce(t: np.ndarray, y: np.ndarray, stat: str) -> float:
    if len(y) == 0:
        raise ResponseError("the run recorded no states")
    if stat == "max":
        return float(np.max(y))
    if stat == "min":
        return float(np.min(y))
    if stat == "absmax":
        return float(np.max(np.abs(y)))
    if stat == "final":
        return float(y[-1])
    if len(y) < 2:
        return float(y[0])
    return float(np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(t)) / (t[-1] - t[0]))


def _component(v: np.ndarray, comp: str) -> np.ndarray:
    if comp == "magnitude":
        return np.linalg.norm(v, axis=-1)
    return v[..., "xyz".index(comp)]


def _column(ids, wanted, what: str, default_first: bool = True) -> int:
    ids = np.asarray(ids).ravel()
    if wanted is None:
        if len(ids) == 0:
            raise ResponseError(f"the run recorded no {what}")
        return 0
    hit = np.flatnonzero(ids == wanted)
    if len(hit) == 0:
        raise ResponseError(f"{what} {wanted} not recorded by the run (recorded: {ids.tolist()[:20]})")
    return int(hit[0])


def _filtered(spec, t, y, time_scale):
    cfc = spec.get("cfc")
    if cfc is None:
        return t, y
    from ..verify.filters import filter_signal

    try:
        return filter_signal(t, y, float(cfc), time_scale=time_scale)
    except ValueError as e:
        raise ResponseError(f"CFC {cfc:g} filter: {e}") from None


def evaluate_responses(
    specs: dict,
    res: Results,
    model: Model,
    variables: dict,
    units: UnitSystem | None = None,
    final_state: FinalState | None = None,
    solver: str | None = None,
) -> dict[str, float]:
    """Every response of a finished run: name -> float (scaled).

    res: solver Results; model: the design's Model; variables: name ->
    value of the design; units: the deck's UnitSystem (default from its
    densities), for g and the CFC filters' seconds; final_state: an
    external solver's d3plot final state, for final displacements of
    nodes ``res`` lacks (an LS-DYNA run's are its history nodes); solver:
    the external solver that ran it ("lsdyna", "openradioss"; None:
    crashlite's), for the contact interface IDs of an OpenRadioss run."""
    if units is None:
        from ..units import system

        try:
            units = system(model.unit_system())
        except ValueError:
            units = system("mm-t-s")
    time_scale = 1.0 / units.time  # seconds per time unit
    g = G_MM_S2 * units.length / units.time**2
    out: dict[str, float] = {}
    for name, spec in specs.items():
        v = _one(spec, res, model, variables, out, time_scale, g, final_state, solver)
        if not math.isfinite(v):
            raise ResponseError(f"response {name!r} is not finite ({v})")
        out[name] = v * spec.scale if spec.type != "expression" else v
    return out


def _one(spec: ResponseSpec, res, model, variables, done, time_scale, g, final_state=None, solver=None) -> float:
    t, o = spec.type, spec.options
    if t == "mass":
        return float(model.mass_properties(o.get("parts")).mass)
    if t == "expression":
        from ..keyword.expression import evaluate

        names = {k.lower(): float(v) for k, v in {**variables, **done}.items()}
        return float(evaluate(o["expression"], names)) * spec.scale
    time = np.asarray(res.time, float)
    stat = o.get("stat", "max")
    if t == "part_energy":
        pids = model.part_ids_of(o.get("parts"))
        cols = [int(np.flatnonzero(res.part_ids == p)[0]) for p in pids if np.any(res.part_ids == p)]
        if not cols:
            raise ResponseError(f"no internal energy recorded for parts {o.get('parts')}")
        return _reduce(time, res.part_internal[:, cols].sum(axis=1), o.get("stat", "final"))
    if t == "energy":
        q = o["quantity"]
        y = res.total if q == "total" else getattr(res, q)
        if len(y) != len(time):
            raise ResponseError(f"glstat {q} energy not recorded")
        return _reduce(time, y, o.get("stat", "final"))
    if t == "wall_force":
        j = _column(res.wall_ids, o.get("id"), "rigid wall")
        comp = o.get("component", "normal")
        if comp == "normal":
            y = (
                res.wall_normal_force[:, j]
                if res.recorded("wall_normal_force")
                else np.linalg.norm(res.wall_force[:, j], axis=-1)
            )
        else:
            y = _component(res.wall_force[:, j], comp)
        return _reduce(*_filtered(spec, time, y, time_scale), stat)
    if t == "section_force":
        j = _column(res.section_ids, o.get("id"), "cross section")
        y = _component(res.section_force[:, j], o.get("component", "magnitude"))
        return _reduce(*_filtered(spec, time, y, time_scale), stat)
    if t == "discrete_force":
        j = _column(res.discrete_ids, o.get("id"), "discrete element")
        return _reduce(*_filtered(spec, time, res.discrete_force[:, j], time_scale), stat)
    if t == "contact_force":
        j = _column(res.contact_ids, _contact_id(spec, model, solver), "contact interface")
        y = _component(res.contact_force[:, j], o.get("component", "magnitude"))
        return _reduce(*_filtered(spec, time, y, time_scale), stat)
    if t in ("node_displacement", "node_velocity"):
        comp = o.get("component", "x")
        st = o.get("stat", "final")
        if t == "node_displacement" and st == "final":
            d = _final_displacement(res, model, [o["node"]], final_state)
            return float(_component(d, comp)[0])
        j = _column(res.history_nodes, o["node"], "history node")
        arr = res.node_displacement if t == "node_displacement" else res.node_velocity
        return _reduce(time, _component(arr[:, j], comp), st)
    if t == "intrusion":
        return _intrusion(spec, res, model, final_state)
    if t in ("deceleration", "pulse"):
        from ..verify.pulse import crash_pulse

        j = _column(res.history_nodes, o["node"], "history node")
        comp = o.get("component", "x")
        v = _component(res.node_velocity[:, j], comp)
        try:
            p = crash_pulse(time, velocity=v, cfc=float(o.get("cfc", 60)), time_scale=time_scale)
        except ValueError as e:
            raise ResponseError(f"crash pulse of node {o['node']}: {e}") from None
        fig = "peak_deceleration" if t == "deceleration" else o["figure"]
        val = getattr(p, fig)
        if val is None:
            raise ResponseError(f"{fig} of node {o['node']} is not defined: {p.note}")
        if fig in ("peak_deceleration", "mean_deceleration", "olc") and spec.unit.lower() == "g":
            val = val / g
        return float(val)
    raise ResponseError(f"response type {t!r} not handled")  # pragma: no cover


def _contact_id(spec: ResponseSpec, model, solver) -> int | None:
    """The interface ID of the response's contact in the run's rcforc: the
    ``id`` as given (crashlite and LS-DYNA number alike; None: the first
    interface the run has), or the /INTER ID OpenRadioss gives that card."""
    if solver != "openradioss":
        return spec.get("id")
    from ..model.contacts import contact_cards

    try:
        card = _contact_card(spec, model, solver)
        return spec.get("id") if card is None else _openradioss_interface(card, contact_cards(model))
    except ValueError as e:
        raise ResponseError(str(e)) from None


def _final_displacement(res, model, nodes, final_state=None) -> np.ndarray:
    """(n, 3) final displacement of deck nodes from the run's final state;
    from ``final_state`` (a d3plot's) for all of them where the run's lacks
    one, so the nodes of a response share one state."""
    ids = np.asarray(res.node_ids) if len(res.node_ids) else model.nodes.ids
    if final_state is not None and not {int(n) for n in nodes} <= set(ids.tolist()):
        return _state_displacement(final_state, nodes)
    pos = {int(n): i for i, n in enumerate(ids)}
    idx = []
    for n in nodes:
        if int(n) not in pos:
            raise ResponseError(f"node {n} not in the run's final state")
        idx.append(pos[int(n)])
    idx = np.array(idx)
    x0 = model.nodes.xyz[model.node_index(np.asarray(nodes))]
    return np.asarray(res.final_x)[idx] - x0


def _state_displacement(state: FinalState, nodes) -> np.ndarray:
    """(n, 3) displacement of deck nodes in a d3plot's final state (by node ID)."""
    pos = {int(n): i for i, n in enumerate(state.node_ids)}
    lack = [int(n) for n in nodes if int(n) not in pos]
    if lack:
        raise ResponseError(f"node(s) {', '.join(map(str, lack[:10]))} not in the final state of {state.source}")
    return state.displacement[[pos[int(n)] for n in nodes]]


def _intrusion(spec, res, model, final_state=None) -> float:
    o = spec.options
    members = model.set_members("NODE", o["set"]).tolist() if "set" in o else list(o["nodes"])
    comp = o.get("component", "magnitude")
    ref = o.get("reference")
    if o.get("over", "final") == "final":
        d = _final_displacement(res, model, members + ([ref] if ref is not None else []), final_state)
        if ref is not None:
            d = d[:-1] - d[-1]
        y = _component(d, comp)
        return float(np.max(np.abs(y)))
    cols = [_column(res.history_nodes, n, "history node") for n in members]
    d = res.node_displacement[:, cols]
    if ref is not None:
        d = d - res.node_displacement[:, [_column(res.history_nodes, ref, "history node")]]
    return float(np.max(np.abs(_component(d, comp))))
