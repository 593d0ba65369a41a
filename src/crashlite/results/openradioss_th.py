"""OpenRadioss time-history files (``<run>T01``) as crashlite histories.

The file is a sequence of Fortran-style records: a 4-byte big-endian
length, the record, the length again. Integers are 4-byte big-endian,
reals 4-byte big-endian IEEE floats, titles one byte per character. In
order (as OpenRadioss's engine writes it, ``hist1.F``/``hist2.F``, and its
``th_to_csv`` converter reads it):

1. the file code (3040: 40-character titles, 3041: 80, 3050/4021: 100)
   and an 80-character run title; 2. the date and program (80 characters);
   3. from code 3051 on, three more records: a record count, the title
   length, the unit factors of mass, length and time;
4. six counts: parts (and TH sub-groups), materials, properties, subsets,
   time-history groups, global variables; then the global variables'
   codes (one record);
5. each part: ID, title, material, two more integers and its number of
   variables, then (if any) their codes; each material and property: ID
   and title; each subset: ID, parent, its children's and parts' counts,
   its number of variables and title, then the children, parts and
   variable codes (each a record when not empty);
6. each time-history group (``/TH/NODE``, ``/TH/RWALL`` ...): ID, type
   (0 node, 101 interface, 102 rigid wall, 103 rigid body, 104 section,
   ...), an integer, its number of entities, its number of variables and
   title; a record per entity (ID and title); the variable codes;
7. then per output time: the time, the global variables, the parts'
   variables (all parts in one record), the subsets' variables, and one
   record per group holding each entity's variables in turn.

Variable codes are 1-based places in OpenRadioss's lists of names
(``hm_read_thgrou.F``): a node's DX DY DZ VX ... (1-19) and REACX ...
(620-629), a rigid wall's FNX FNY FNZ FTX FTY FTZ, an interface's FNX ...
||F|| ... CAREA, a section's FNX ... F3 CX CY CZ, a part's IE KE XMOM ...
PW. Forces of rigid walls, interfaces and sections (and their moments)
are written as impulses, their integral over time since the start; they
are turned into forces as ``th_to_csv`` does (central differences of the
impulse over the neighbouring output times, one-sided at the ends).

Mapped onto LS-DYNA's categories (lasso-python Binout names, as
``results.load`` gives an LS-DYNA folder):

* ``glstat``: ``time``, ``time_step``; ``kinetic_energy`` the translational
  plus the rotational kinetic energy (LS-DYNA's includes both);
  ``internal_energy``, ``hourglass_energy``, ``sliding_interface_energy``
  (the contact energy), ``external_work``, ``spring_and_damper_energy``
  as OpenRadioss writes them (its internal energy holds neither the
  hourglass nor the contact energy, as LS-DYNA's); ``total_energy`` their
  sum; ``added_mass``, ``percent_increase`` and ``global_x_velocity`` ...
  (momentum / mass) where written.
* ``matsum`` (parts with variables): ``internal_energy``,
  ``kinetic_energy`` (plus the rotational one where written),
  ``hourglass_energy``, ``x_momentum`` ..., ``x_rbvelocity`` ...
* ``nodout`` (``/TH/NODE`` groups, by node ID): ``x_displacement``,
  ``x_velocity``, ``x_acceleration``, ``x_coordinate``, ``rx_velocity``,
  ``rx_acceleration``, ``rx_displacement`` (each axis). A node in several
  groups is read once; a quantity some groups lack is NaN for their
  nodes. Values are in the frame the group names (``Iskew``), as written.
* ``rwforc`` (``/TH/RWALL``): ``("forces", "x_force")`` ... the force of
  the nodes on the wall (normal plus tangential: the sign LS-DYNA's
  rwforc has), ``normal_force`` the magnitude of the normal part.
* ``rcforc`` (``/TH/INTER``): OpenRadioss writes the force on the main
  (master) side; as LS-DYNA, a line per side: the secondary (slave) side
  (``side`` 0) takes its opposite.
* ``secforc`` (``/TH/SECTIO``): ``x_force`` ... (normal plus tangential,
  global frame), ``total_force``; ``x_moment`` ... and ``total_moment``
  where the global moments (MX MY MZ) were asked for. The sign is
  OpenRadioss's own.

A run stopped while writing leaves a last state cut short: it is left out.
"""

from __future__ import annotations

import struct
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

# OpenRadioss's names of the global variables, by code
GLOBALS = (
    "IE", "KE", "XMOM", "YMOM", "ZMOM", "MASS", "DT", "RKE", "WFEXT", "SPRING_ENERGY", "CONTACT_ENERGY",
    "HOURGLASS_ENERGY", "ELASTIC_CONTACT_ENERGY", "FRICTIONAL_CONTACT_ENERGY", "DAMPING_CONTACT_ENERGY",
    "PLASTIC_WORK", "ADDED_MASS", "PERCENT_ADDED_MASS", "INLET_MASS", "OUTLET_MASS", "INLET_ENERGY",
    "OUTLET_ENERGY",
)  # fmt: skip
PART = (
    "IE", "KE", "XMOM", "YMOM", "ZMOM", "MASS", "HE", "TURBKE", "XCG", "YCG", "ZCG", "XXMOM", "YYMOM", "ZZMOM",
    "IXX", "IYY", "IZZ", "IXY", "IYZ", "IZX", "RIE", "KERB", "RKERB", "RKE", "ERODED", "UNUSED", "UNUSED",
    "HEAT", "VX", "VY", "VZ", "PW",
)  # fmt: skip
_NODE = (
    "DX", "DY", "DZ", "VX", "VY", "VZ", "AX", "AY", "AZ", "VRX", "VRY", "VRZ", "ARX", "ARY", "ARZ", "X", "Y", "Z",
    "TEMP",
)  # fmt: skip
_NODE_REACTIONS = ("REACX", "REACY", "REACZ", "REACXX", "REACYY", "REACZZ", "DRX", "DRY", "DRZ", "PEXT")
_RWALL = ("FNX", "FNY", "FNZ", "FTX", "FTY", "FTZ")
_INTER = (
    "FNX", "FNY", "FNZ", "FTX", "FTY", "FTZ", "SFW", "|FNX|", "|FNY|", "|FNZ|", "||FN||", "|FX|", "|FY|", "|FZ|",
    "||F||", "PVOL", "PSURF", "PMED", "DELTAP", "VOL", "SURF", "MX", "MY", "MZ", "QFRIC", "CE_ELAST", "CE_FRIC",
    "CE_DAMP", "CAREA",
)  # fmt: skip
_SECTIO = (
    "FNX", "FNY", "FNZ", "FTX", "FTY", "FTZ", "M1", "M2", "M3", "WORK", "DFX", "DFY", "DFZ", "DF2", "WORKR", "DMX",
    "DMY", "DMZ", "DM2", "KIN", "KINR", "DMVX", "DMVY", "DMVZ", "DKIN", "DMVRX", "DMVRY", "DMVRZ", "DKINR",
    "TFEXT", "MX", "MY", "MZ", "F1", "F2", "F3", "CX", "CY", "CZ",
)  # fmt: skip
_RBODY = (
    "FX", "FY", "FZ", "MX", "MY", "MZ", "RX", "RY", "RZ", "FXI", "FYI", "FZI", "MXI", "MYI", "MZI", "X", "Y", "Z",
    "DX", "DY", "DZ", "VX", "VY", "VZ", "AX", "AY", "AZ", "VRX", "VRY", "VRZ", "ARX", "ARY", "ARZ", "MASS", "IXX",
    "IYY", "IZZ", "IXY", "IYZ", "IZX", "STATUS",
)  # fmt: skip
NODE, INTER, RWALL, RBODY, SECTIO = 0, 101, 102, 103, 104
KEYWORDS = {NODE: "/TH/NODE", INTER: "/TH/INTER", RWALL: "/TH/RWALL", RBODY: "/TH/RBODY", SECTIO: "/TH/SECTIO"}
_NAMES = {RWALL: _RWALL, INTER: _INTER, RBODY: _RBODY, SECTIO: _SECTIO}
# variables written as impulses (th_to_csv differentiates them)
_IMPULSES = {
    RWALL: set(_RWALL),
    INTER: {"FNX", "FNY", "FNZ", "FTX", "FTY", "FTZ", "|FNX|", "|FNY|", "|FNZ|", "||FN||"}
    | {"|FX|", "|FY|", "|FZ|", "||F||", "MX", "MY", "MZ"},
    SECTIO: {"FNX", "FNY", "FNZ", "FTX", "FTY", "FTZ", "MX", "MY", "MZ", "M1", "M2", "M3", "F1", "F2", "F3"},
}


def variable_name(group_type: int, code: int) -> str:
    """OpenRadioss's name of variable ``code`` of a group of ``group_type``
    (``VAR<code>`` where the list is not known here)."""
    if group_type == NODE:
        if 1 <= code <= len(_NODE):
            return _NODE[code - 1]
        if 620 <= code < 620 + len(_NODE_REACTIONS):
            return _NODE_REACTIONS[code - 620]
    names = _NAMES.get(group_type)
    if names is not None and 1 <= code <= len(names):
        return names[code - 1]
    return f"VAR{code}"


@dataclass
class Group:
    """One time-history group (``/TH/NODE``, ``/TH/RWALL`` ...)."""

    id: int
    type: int  # NODE, INTER, RWALL, RBODY, SECTIO, ... (OpenRadioss's code)
    title: str
    ids: np.ndarray  # (n_entities,) entity IDs
    entity_titles: list[str]
    codes: np.ndarray  # (n_variables,) variable codes
    values: np.ndarray = field(default_factory=lambda: np.zeros((0, 0, 0)))  # (n_states, n_entities, n_variables)

    @property
    def names(self) -> list[str]:
        """The variables' OpenRadioss names (DX, FNX, ...)."""
        return [variable_name(self.type, int(c)) for c in self.codes]

    def quantity(self, name: str) -> np.ndarray | None:
        """(n_states, n_entities) of one variable by name, or None."""
        names = self.names
        return self.values[:, :, names.index(name)] if name in names else None


@dataclass
class TimeHistory:
    """The contents of a T01 file."""

    path: str
    code: int  # the file's format code (3040, 3041, 3050, 4021)
    title: str
    time: np.ndarray  # (n_states,)
    global_codes: np.ndarray  # (n_globals,)
    globals: np.ndarray  # (n_states, n_globals)
    part_ids: np.ndarray  # parts with variables
    part_titles: list[str]
    part_codes: list[np.ndarray]
    part_values: list[np.ndarray]  # per part (n_states, n_variables)
    groups: list[Group]
    units: tuple[float, float, float] | None = None  # mass, length, time factors (code > 3050)

    def global_value(self, name: str) -> np.ndarray | None:
        """(n_states,) of a global variable by OpenRadioss name (GLOBALS), or None."""
        code = GLOBALS.index(name) + 1
        hit = np.flatnonzero(self.global_codes == code)
        return self.globals[:, hit[0]] if len(hit) else None

    def part_value(self, name: str) -> np.ndarray | None:
        """(n_states, n_parts) of a part variable (PART names) for all parts
        with variables, or None when no part has it; NaN for parts without."""
        code = PART.index(name) + 1
        if not any(code in c for c in self.part_codes):
            return None
        out = np.full((len(self.time), len(self.part_ids)), np.nan)
        for j, (c, v) in enumerate(zip(self.part_codes, self.part_values)):
            hit = np.flatnonzero(c == code)
            if len(hit):
                out[:, j] = v[:, hit[0]]
        return out

    def of_type(self, group_type: int) -> list[Group]:
        return [g for g in self.groups if g.type == group_type]


class FormatError(ValueError):
    """The file is not an OpenRadioss time history (the message says where)."""


class _Records:
    def __init__(self, data: bytes, path: str):
        self.data, self.path, self.pos = data, path, 0
        first = data[:4]
        if len(first) < 4:
            raise FormatError(f"{path}: empty or too short for an OpenRadioss time history")
        self.order = ">"
        if not self._plausible(">"):
            if not self._plausible("<"):
                raise FormatError(f"{path}: not an OpenRadioss time history (no record structure at its start)")
            self.order = "<"

    def _plausible(self, order: str) -> bool:
        (n,) = struct.unpack(order + "i", self.data[:4])
        return 0 < n <= len(self.data) - 8 and self.data[4 + n : 8 + n] == self.data[:4]

    def at_end(self) -> bool:
        return self.pos >= len(self.data)

    def next(self, what: str) -> bytes | None:
        """The next record, or None when the file ends (also inside a record)."""
        d, p = self.data, self.pos
        if p + 4 > len(d):
            return None
        (n,) = struct.unpack(self.order + "i", d[p : p + 4])
        if n < 0 or p + 8 + n > len(d):
            return None
        if d[p + 4 + n : p + 8 + n] != d[p : p + 4]:
            raise FormatError(f"{self.path}: record at byte {p} ({what}): its end marker does not match its length")
        self.pos = p + 8 + n
        return d[p + 4 : p + 4 + n]

    def need(self, what: str) -> bytes:
        r = self.next(what)
        if r is None:
            raise FormatError(f"{self.path}: the file ends in its header ({what})")
        return r

    def ints(self, rec: bytes, offset: int = 0, count: int | None = None) -> np.ndarray:
        count = (len(rec) - offset) // 4 if count is None else count
        return np.frombuffer(rec, self.order + "i4", count, offset).astype(np.int64)

    def reals(self, rec: bytes, count: int, what: str) -> np.ndarray:
        if len(rec) == 4 * count:
            return np.frombuffer(rec, self.order + "f4").astype(float)
        if len(rec) == 8 * count:
            return np.frombuffer(rec, self.order + "f8").astype(float)
        raise FormatError(f"{self.path}: {what}: a record of {len(rec)} bytes where {count} values were expected")


def _text(rec: bytes, start: int, length: int) -> str:
    return rec[start : start + length].decode("latin-1").strip()


def read(path: Path | str) -> TimeHistory:
    """Read an OpenRadioss time-history file (``<run>T01``)."""
    path = Path(path)
    r = _Records(path.read_bytes(), str(path))
    head = r.need("title")
    code = int(r.ints(head, 0, 1)[0])
    title = _text(head, 4, 80)
    length = 100 if code >= 4021 else 80 if code >= 3041 else 40
    r.need("date")
    units = None
    if code > 3050:
        r.need("record count")
        length = int(r.ints(r.need("title length"))[0])
        u = r.reals(r.need("unit factors"), 3, "unit factors")
        units = (float(u[0]), float(u[1]), float(u[2]))
    counts = r.ints(r.need("counts"), 0, 6)
    n_parts, n_mat, n_geo, n_subs, n_groups, n_glob = (int(c) for c in counts)
    global_codes = r.ints(r.need("global variable codes")) if n_glob > 0 else np.zeros(0, np.int64)

    parts = []  # (id, title, codes)
    for _ in range(n_parts):
        rec = r.need("part")
        pid = int(r.ints(rec, 0, 1)[0])
        nvar = int(r.ints(rec, 4 + length, 4)[3])
        codes = r.ints(r.need("part variable codes")) if nvar > 0 else np.zeros(0, np.int64)
        parts.append((pid, _text(rec, 4, length), codes))
    for _ in range(n_mat + n_geo):
        r.need("material or property")
    subset_vars = 0
    for _ in range(n_subs):
        _, _, n_child, n_part, nvar = (int(v) for v in r.ints(r.need("subset"), 0, 5))
        for n in (n_child, n_part, nvar):
            if n > 0:
                r.need("subset lists")
        subset_vars += max(nvar, 0)
    groups = []
    for _ in range(n_groups):
        rec = r.need("time-history group")
        gid, gtype, _, n_ent, nvar = (int(v) for v in r.ints(rec, 0, 5))
        ids, titles = [], []
        for _ in range(n_ent):
            e = r.need("group entity")
            ids.append(int(r.ints(e, 0, 1)[0]))
            titles.append(_text(e, 4, length))
        codes = r.ints(r.need("group variable codes")) if nvar > 0 else np.zeros(0, np.int64)
        groups.append(Group(gid, gtype, _text(rec, 20, length), np.asarray(ids, np.int64), titles, codes))

    part_vars = sum(len(c) for _, _, c in parts)
    time, glob, pvals, gvals = [], [], [], [[] for _ in groups]
    while not r.at_end():
        state = _state(r, len(global_codes), part_vars, subset_vars, groups)
        if state is None:  # cut short: a run stopped while writing
            break
        t, g, p, per_group = state
        time.append(t)
        glob.append(g)
        pvals.append(p)
        for k, v in enumerate(per_group):
            gvals[k].append(v)
    n = len(time)
    for g, vals in zip(groups, gvals):
        g.values = np.asarray(vals, float).reshape(n, len(g.ids), len(g.codes))
    glob_arr = np.asarray(glob, float).reshape(n, len(global_codes))
    pv = np.asarray(pvals, float).reshape(n, part_vars)
    keep = [(pid, t, c, k) for k, (pid, t, c) in enumerate(parts) if len(c)]
    starts = np.cumsum([0] + [len(c) for _, _, c in parts])
    return TimeHistory(
        path=str(path),
        code=code,
        title=title,
        time=np.asarray(time, float),
        global_codes=global_codes,
        globals=glob_arr,
        part_ids=np.asarray([k[0] for k in keep], np.int64),
        part_titles=[k[1] for k in keep],
        part_codes=[k[2] for k in keep],
        part_values=[pv[:, starts[k[3]] : starts[k[3]] + len(k[2])] for k in keep],
        groups=groups,
        units=units,
    )


def _state(r: _Records, n_glob: int, part_vars: int, subset_vars: int, groups: list[Group]):
    """One output time's records, or None where the file ends before its last."""
    rec = r.next("time")
    if rec is None:
        return None
    t = float(r.reals(rec, 1, "time")[0])
    g = np.zeros(0)
    if n_glob > 0:
        rec = r.next("global variables")
        if rec is None:
            return None
        g = r.reals(rec, n_glob, f"global variables at time {t:g}")
    p = np.zeros(0)
    if part_vars > 0:
        rec = r.next("part variables")
        if rec is None:
            return None
        p = r.reals(rec, part_vars, f"part variables at time {t:g}")
    if subset_vars > 0 and r.next("subset variables") is None:
        return None
    per_group = []
    for grp in groups:
        size = len(grp.ids) * len(grp.codes)
        if size == 0:  # nothing written for an empty group
            per_group.append(np.zeros(0))
            continue
        rec = r.next("group variables")
        if rec is None:
            return None
        per_group.append(r.reals(rec, size, f"group {grp.id} ({KEYWORDS.get(grp.type, grp.type)}) at time {t:g}"))
    return t, g, p, per_group


def rate(time: np.ndarray, impulse: np.ndarray) -> np.ndarray:
    """Force from impulse (time first), as th_to_csv: central differences,
    one-sided at the first and last time; zero over a zero time step."""
    t = np.asarray(time, float)
    y = np.asarray(impulse, float)
    n = len(t)
    if n < 2:
        return np.zeros_like(y)
    lo = np.r_[0, np.arange(n - 2), n - 2]
    hi = np.r_[1, np.arange(2, n), n - 1]
    dt = (t[hi] - t[lo]).reshape((n,) + (1,) * (y.ndim - 1))
    dy = y[hi] - y[lo]
    return np.divide(dy, dt, out=np.zeros_like(dy), where=dt != 0)


def _xyz(out: dict, fmt: str, values: dict, names: tuple[str, str, str]) -> None:
    if all(n in values for n in names):
        for axis, n in zip("xyz", names):
            out[fmt.format(axis)] = values[n]


def _glstat(th: TimeHistory) -> dict:
    g = th.global_value
    out: dict = {"time": th.time}
    if g("DT") is not None:
        out["time_step"] = g("DT")
    ke, rke = g("KE"), g("RKE")
    if ke is not None:
        out["kinetic_energy"] = ke + (rke if rke is not None else 0.0)
    for name, binout in (
        ("IE", "internal_energy"),
        ("HOURGLASS_ENERGY", "hourglass_energy"),
        ("CONTACT_ENERGY", "sliding_interface_energy"),
        ("WFEXT", "external_work"),
        ("SPRING_ENERGY", "spring_and_damper_energy"),
        ("ADDED_MASS", "added_mass"),
        ("PERCENT_ADDED_MASS", "percent_increase"),
    ):
        if g(name) is not None:
            out[binout] = g(name)
    parts = [out.get(k) for k in ("kinetic_energy", "internal_energy", "hourglass_energy", "sliding_interface_energy")]
    if out.get("kinetic_energy") is not None and out.get("internal_energy") is not None:
        out["total_energy"] = sum(p for p in parts if p is not None)
    mass = g("MASS")
    if mass is not None:
        for axis in "xyz":
            mom = g(f"{axis.upper()}MOM")
            if mom is not None:
                out[f"global_{axis}_velocity"] = np.divide(mom, mass, out=np.zeros_like(mom), where=mass != 0)
    return out


def _matsum(th: TimeHistory) -> dict | None:
    if not len(th.part_ids):
        return None
    v = {name: th.part_value(name) for name in PART}
    v = {k: a for k, a in v.items() if a is not None}
    out: dict = {"time": th.time, "ids": th.part_ids}
    if "IE" in v:
        out["internal_energy"] = v["IE"]
    if "KE" in v:
        out["kinetic_energy"] = v["KE"] + (np.nan_to_num(v["RKE"]) if "RKE" in v else 0.0)
    if "HE" in v:
        out["hourglass_energy"] = v["HE"]
    _xyz(out, "{}_momentum", v, ("XMOM", "YMOM", "ZMOM"))
    _xyz(out, "{}_rbvelocity", v, ("VX", "VY", "VZ"))
    return out


_NODOUT = {  # Binout name format -> OpenRadioss names
    "{}_displacement": ("DX", "DY", "DZ"),
    "{}_velocity": ("VX", "VY", "VZ"),
    "{}_acceleration": ("AX", "AY", "AZ"),
    "{}_coordinate": ("X", "Y", "Z"),
    "r{}_displacement": ("DRX", "DRY", "DRZ"),
    "r{}_velocity": ("VRX", "VRY", "VRZ"),
    "r{}_acceleration": ("ARX", "ARY", "ARZ"),
}


def _nodout(th: TimeHistory) -> dict | None:
    groups = th.of_type(NODE)
    ids: list[int] = []
    where: list[tuple[Group, int]] = []
    seen: set[int] = set()
    for g in groups:
        for j, nid in enumerate(g.ids.tolist()):
            if nid not in seen:
                seen.add(nid)
                ids.append(nid)
                where.append((g, j))
    if not ids:
        return None
    n = len(th.time)
    values: dict = {}
    for names in _NODOUT.values():
        for name in names:
            if not any(name in g.names for g in groups):
                continue
            col = np.full((n, len(ids)), np.nan)
            for k, (g, j) in enumerate(where):
                q = g.quantity(name)
                if q is not None:
                    col[:, k] = q[:, j]
            values[name] = col
    out: dict = {"time": th.time, "ids": np.asarray(ids, np.int64)}
    for fmt, names in _NODOUT.items():
        _xyz(out, fmt, values, names)
    return out


def _forces(th: TimeHistory, group_type: int) -> tuple[np.ndarray, dict] | None:
    """Entity IDs and named forces (impulses differentiated) of every group
    of a type: quantities all its groups have."""
    groups = [g for g in th.of_type(group_type) if len(g.ids) and len(g.codes)]
    if not groups:
        return None
    common = set(groups[0].names).intersection(*(g.names for g in groups[1:]))
    ids = np.concatenate([g.ids for g in groups])
    out = {}
    for name in common:
        v = np.concatenate([g.quantity(name) for g in groups], axis=1)
        out[name] = rate(th.time, v) if name in _IMPULSES.get(group_type, ()) else v
    return ids, out


def _sum3(v: dict, a: tuple[str, str, str], b: tuple[str, str, str]) -> np.ndarray | None:
    """(n, m, 3) of the named x/y/z quantities ``a`` plus ``b`` (each where present)."""
    have = [names for names in (a, b) if all(n in v for n in names)]
    if not have:
        return None
    return sum(np.stack([v[n] for n in names], axis=2) for names in have)


_FN, _FT = ("FNX", "FNY", "FNZ"), ("FTX", "FTY", "FTZ")


def _summed(th: TimeHistory, group: int) -> tuple | None:
    """(ids, variables, normal + tangential force (n_times, n, 3)) of a
    force group, or None where the file has none."""
    got = _forces(th, group)
    if got is None:
        return None
    ids, v = got
    f = _sum3(v, _FN, _FT)
    return None if f is None else (ids, v, f)


def _rwforc(th: TimeHistory) -> dict | None:
    got = _summed(th, RWALL)
    if got is None:
        return None
    ids, v, f = got
    out = {("forces", "time"): th.time, ("forces", "ids"): ids}
    for k, axis in enumerate("xyz"):
        out[("forces", f"{axis}_force")] = f[:, :, k]
    fn = np.stack([v[n] for n in _FN], axis=2) if all(n in v for n in _FN) else f
    out[("forces", "normal_force")] = np.linalg.norm(fn, axis=2)
    return out


def _secforc(th: TimeHistory) -> dict | None:
    got = _summed(th, SECTIO)
    if got is None:
        return None
    ids, v, f = got
    out: dict = {"time": th.time, "ids": ids}
    for k, axis in enumerate("xyz"):
        out[f"{axis}_force"] = f[:, :, k]
    out["total_force"] = np.linalg.norm(f, axis=2)
    if all(n in v for n in ("MX", "MY", "MZ")):
        m = np.stack([v[n] for n in ("MX", "MY", "MZ")], axis=2)
        for k, axis in enumerate("xyz"):
            out[f"{axis}_moment"] = m[:, :, k]
        out["total_moment"] = np.linalg.norm(m, axis=2)
    return out


def _rcforc(th: TimeHistory) -> dict | None:
    got = _summed(th, INTER)
    if got is None:
        return None
    ids, v, f = got
    n, m = f.shape[:2]
    both = np.stack([-f, f], axis=2).reshape(n, 2 * m, 3)  # secondary (slave) 1, main 1, secondary 2 ...
    out: dict = {"time": th.time, "ids": np.repeat(ids, 2), "side": np.tile([0, 1], m)}
    for k, axis in enumerate("xyz"):
        out[f"{axis}_force"] = both[:, :, k]
    return out


def categories(th: TimeHistory) -> dict:
    """The time history as LS-DYNA categories (lasso-python Binout names):
    glstat always, matsum, nodout, rwforc, secforc and rcforc where the
    file holds parts, nodes, rigid walls, sections, interfaces."""
    out = {"glstat": _glstat(th)}
    for name, make in (
        ("matsum", _matsum),
        ("nodout", _nodout),
        ("rwforc", _rwforc),
        ("secforc", _secforc),
        ("rcforc", _rcforc),
    ):
        data = make(th)
        if data is not None:
            out[name] = data
    return out


def find(folder: Path | str) -> list[Path]:
    """The OpenRadioss time-history files (``*T01``) in a folder."""
    p = Path(folder)
    return sorted(f for f in p.glob("*T01") if f.is_file())


def is_time_history(path: Path | str) -> bool:
    """A file named like an OpenRadioss time history (``<run>T01``)."""
    p = Path(path)
    return p.is_file() and p.name.endswith("T01") and len(p.name) > 3
