"""Step 4: truncation and the spring–mass surrogate, on tubes with known answers."""

import numpy as np
import pytest
from _structures import NU, RHO, E, shell_model, tube_mesh

from crashlite import read_deck
from crashlite.model.mesh import Masses
from crashlite.solver import run
from crashlite.vehicle.car.records import id_list, record
from crashlite.vehicle.steps.cut import cut_behind
from crashlite.vehicle.steps.massprops import replaced_mass
from crashlite.vehicle.steps.stiffness import longitudinal_stiffness, structure_stiffness, transverse_stiffness
from crashlite.vehicle.steps.surrogate import build_surrogate
from crashlite.vehicle.steps.truncate import truncate

B, L, T = 50.0, 500.0, 1.5  # tube side (mid-line), length, wall [mm]
M_FRONT, M_REAR = 0.1, 0.1  # point masses at the front and rear ends [t]


def _tube(per_side=4, n_len=20, length=L, masses=True):
    """A tube along x (rear end x = 0, front x = length) with point masses
    on both end rings, the rear ring as a node set "axle", history nodes at
    both ends."""
    xyz, quads = tube_mesh(B, length, per_side, n_len)
    m = shell_model(xyz, quads, thickness=T)
    rear = np.flatnonzero(np.isclose(xyz[:, 0], 0.0))
    front = np.flatnonzero(np.isclose(xyz[:, 0], length))
    if masses:
        node = np.concatenate([front, rear])
        ms = Masses.zeros(len(node))
        ms.ids = np.arange(1, len(node) + 1) + 1000
        ms.node = node.astype(np.int32)
        ms.mass = np.concatenate([np.full(len(front), M_FRONT / len(front)), np.full(len(rear), M_REAR / len(rear))])
        m.masses = ms
    m.sets[("NODE", 1)] = id_list("SET_NODE_LIST_TITLE", 1, m.nodes.ids[rear], title="axle")
    m.keywords.append(
        record(
            "DATABASE_HISTORY_NODE_ID",
            rows={"id": m.nodes.ids[[front[0], rear[0]]], "heading": np.array(["front", "rear"], object)},
        )
    )
    return m, front, rear


def test_truncation_keeps_the_front_and_mends_references():
    m, front, rear = _tube()
    cut = cut_behind(m, x=L / 2)
    tr = truncate(cut)
    k = tr.model
    assert len(k.shells) == len(m.shells) // 2
    assert k.nodes.xyz[:, 0].min() == pytest.approx(L / 2)  # the cut ring is the rearmost
    assert ("NODE", 1) not in k.sets  # the rear ring (axle) went with the replaced half
    hist = k.find("DATABASE_HISTORY_NODE")[0]
    assert hist.rows["id"].tolist() == [m.nodes.ids[front[0]]]
    assert any("axle" in n for n in tr.notes)
    kept = k.mass_properties().mass
    rep = replaced_mass(cut).structure.mass
    assert kept + rep == pytest.approx(m.mass_properties().mass, rel=1e-12)


def _surrogate(m, shares=None, transverse=None, **kw):
    cut = cut_behind(m, x=L / 2)
    rm = replaced_mass(cut, axle_nodes="axle")
    k = longitudinal_stiffness(cut, "axle")
    asm = {"tube": [1]}
    return cut, rm, k, build_surrogate(cut, asm, shares or {"tube": 1.0}, k.stiffness, rm, transverse, **kw)


def test_surrogate_mass_stiffness_and_deck():
    m, front, rear = _tube()
    cut, rm, k, s = _surrogate(m)
    # K of the rear half is that of the tube: E·A/l (A = 4·b·t) within the shell model's 1 %
    assert k.stiffness == pytest.approx(E * 4 * B * T / (L / 2), rel=0.01)
    (sp,) = s.springs
    np.testing.assert_allclose(sp.direction, [-1.0, 0.0, 0.0], atol=1e-12)
    assert sp.k == pytest.approx((1 - 1e-3) * k.stiffness, rel=1e-12)
    # everything replaced is the rear body's: the total mass and CoG stay the full model's
    nrb = s.model.find("CONSTRAINED_NODAL_RIGID_BODY_INERTIA")[0]
    kept = s.model.mass_properties()
    full = m.mass_properties()
    assert kept.mass + nrb["tm"] == pytest.approx(full.mass, rel=1e-12)  # the beam's mass is in the kept model
    cog = (kept.mass * kept.cog + nrb["tm"] * np.array([nrb["xc"], nrb["yc"], nrb["zc"]])) / (kept.mass + nrb["tm"])
    np.testing.assert_allclose(cog, full.cog, atol=1e-3)
    # the rear history node rides with the rear body
    rear_id = int(m.nodes.ids[rear[0]])
    assert rear_id in s.model.set_members("NODE", int(nrb["nsid"]))
    # the written deck reads back to the same model, and its surrogate part is as stiff as K
    path = s.write(_tmp() / "surrogate.k")
    back = read_deck(path)
    assert back == s.model
    body = ("set", int(nrb["nsid"]))
    iface = s.model.find("CONSTRAINED_NODAL_RIGID_BODY")[0]
    assert "INERTIA" not in iface.options
    ks = structure_stiffness(back, body, ("set", int(iface["nsid"])), direction=(-1.0, 0.0, 0.0))
    assert ks.stiffness == pytest.approx(k.stiffness, rel=1e-9)


def _tmp():
    import tempfile
    from pathlib import Path

    return Path(tempfile.mkdtemp())


def test_profile_direction_follows_an_inclined_tube():
    xyz, quads = tube_mesh(B, L, 4, 20)
    ang = np.radians(30.0)
    rot = np.array([[np.cos(ang), 0, -np.sin(ang)], [0, 1, 0], [np.sin(ang), 0, np.cos(ang)]])
    m = shell_model(xyz @ rot.T, quads, thickness=T)
    rear = np.flatnonzero(np.isclose(xyz[:, 0], 0.0))
    m.sets[("NODE", 1)] = id_list("SET_NODE_LIST_TITLE", 1, m.nodes.ids[rear], title="axle")
    cut = cut_behind(m, x=L / 2 * np.cos(ang))
    rm = replaced_mass(cut, axle_nodes="axle")
    s = build_surrogate(cut, {"tube": [1]}, {"tube": 1.0}, 1000.0, rm)
    np.testing.assert_allclose(s.springs[0].direction, -rot[:, 0], atol=0.02)
    assert any("off the vehicle axis" in n for n in s.notes)


def test_transverse_stiffness_of_a_clamped_tube():
    """Shear (Timoshenko cantilever, tip free to rotate) and torsion (Bredt)
    of the replaced half, clamped at its rear ring, within 4 %."""
    m, _, _ = _tube(per_side=8, n_len=40, masses=False)
    cut = cut_behind(m, x=L / 2)
    t = transverse_stiffness(cut, "axle")
    g = E / (2 * (1 + NU))
    ln = L / 2
    i = 2.0 / 3.0 * T * B**3
    bend = 1.0 / (ln**3 / (3 * E * i) + ln / (g * 2 * B * T))
    assert t["vertical"] == pytest.approx(bend, rel=0.04)
    assert t["lateral"] == pytest.approx(bend, rel=0.04)
    j = 4 * (B * B) ** 2 * T / (4 * B)
    assert t["roll"] == pytest.approx(g * j / ln, rel=0.04)


def _oscillator(model, rear_nodes, v0=-2000.0, end=0.006):
    """The model with the rear nodes moving away at v0 [mm/s], the front at rest."""
    sid = 99
    model.sets[("NODE", sid)] = id_list("SET_NODE_LIST", sid, model.nodes.ids[rear_nodes])
    model.keywords += [
        record("INITIAL_VELOCITY", nsid=sid, vx=v0),
        record("CONTROL_TERMINATION", endtim=end),
        record("CONTROL_TIMESTEP", tssfac=0.9),
        record("DATABASE_NODOUT", dt=2e-5),
        record("DATABASE_GLSTAT", dt=2e-5),
    ]
    return run(model, output_dt=2e-5)


def _first_peak_time(t, v):
    k = int(np.argmax(v[: len(v) * 3 // 4]))
    return t[k]


def test_surrogate_oscillates_like_the_full_tube():
    """Two point masses joined by the tube: the rear mass set moving at v0.
    The front mass's velocity peaks at half the period of the two-mass
    oscillator, T/2 = π·√(μ/k) (μ = m1·m2/(m1+m2), k = E·A/l of the whole
    tube): the full shell tube and the surrogate (front half + spring K of
    the rear half + rear rigid body) within 4 % of it and of each other;
    energy conserved within 1 % in both."""
    m, front, rear = _tube()
    m_tube = RHO * 4 * B * T * L
    cut, rm, k, s = _surrogate(m)
    full = _oscillator(m, np.flatnonzero(m.nodes.xyz[:, 0] < L / 2 - 1e-9))
    sm = s.model
    body = sm.find("CONSTRAINED_NODAL_RIGID_BODY_INERTIA")[0]
    sur = _oscillator(sm, sm.node_index(sm.set_members("NODE", int(body["nsid"]))))
    m1, m2 = M_FRONT + m_tube / 4, M_REAR + m_tube / 4  # the tube's mass shared by the two ends
    mu = m1 * m2 / (m1 + m2)
    half = np.pi * np.sqrt(mu / (E * 4 * B * T / L))
    ids = list(full.history_nodes)
    f_idx = ids.index(int(m.nodes.ids[front[0]]))
    t_full = _first_peak_time(full.time, -full.node_velocity[:, f_idx, 0])
    t_sur = _first_peak_time(
        sur.time, -sur.node_velocity[:, list(sur.history_nodes).index(int(m.nodes.ids[front[0]])), 0]
    )
    assert t_full == pytest.approx(half, rel=0.04)
    assert t_sur == pytest.approx(half, rel=0.04)
    assert t_sur == pytest.approx(t_full, rel=0.04)
    for r in (full, sur):
        assert np.all(np.abs(r.energy_ratio - 1.0) < 0.01)
    # momentum: the rear body's velocity at the start is v0 in both
    r_idx = list(sur.history_nodes).index(int(m.nodes.ids[rear[0]]))
    assert sur.node_velocity[0, r_idx, 0] == pytest.approx(-2000.0, rel=1e-6)


def test_interface_proposal_finds_the_elastic_rear(tmp_path):
    """Field states of a tube whose front 200 mm is shortened by 10 % while
    the rest only translates (a run without recorded strains): every shell
    ahead of x = 300 has εp = 0.1 − σy/E and the plastic work σy·εp·V, none
    behind; the proposal is the foremost candidate plane at or behind 300,
    and each candidate's replaced share is that of the elements behind it."""
    from crashlite.vehicle.connection.interface import propose_interface, shell_measures

    m, _, _ = _tube(per_side=4, n_len=20, masses=False)
    m.materials[1] = record("MAT_PLASTIC_KINEMATIC", mid=1, ro=RHO, e=E, pr=NU, sigy=200.0, etan=0.0, beta=0.0)
    x0 = m.nodes.xyz
    x1 = x0.copy()
    front = x0[:, 0] > 300.0
    x1[front, 0] = 300.0 + 0.9 * (x0[front, 0] - 300.0)
    x1[:, 0] -= 50.0  # the whole tube moves on: no strain from that
    np.savez(
        tmp_path / "results.npz", states_time=np.array([0.0, 0.01]), states_x=np.stack([x0, x1]), node_ids=m.nodes.ids
    )
    eps, work, how = shell_measures(m, tmp_path)
    centre = x0[m.shells.nodes].mean(axis=1)[:, 0]
    assert np.all(eps[centre > 300.0] == pytest.approx(0.1 - 200.0 / E, rel=1e-6))
    assert np.all(eps[centre < 300.0] == 0.0)
    side = B / 4  # 16 shells of 25 x 12.5 mm around
    assert np.all(work[centre > 300.0] == pytest.approx(200.0 * (0.1 - 200.0 / E) * 25.0 * side * T, rel=1e-6))
    assert "estimated" in how["plastic_strain"] and "estimated" in how["energy"]
    p = propose_interface(m, tmp_path, step=50.0)
    assert p.x == pytest.approx(300.0)
    behind = next(c for c in p.candidates if c["x"] == pytest.approx(p.x))
    assert behind["energy_behind_percent"] == 0.0 and behind["strained_area_percent_behind"] == 0.0
    assert behind["replaced_elements_percent"] == pytest.approx(100.0 * np.mean(centre < 300.0))
    ahead = next(c for c in p.candidates if c["x"] == pytest.approx(350.0))
    assert ahead["energy_behind_percent"] == pytest.approx(100.0 * 2 / 8)  # 2 of the 8 strained rings
    assert len(p.notes) == 2  # both measures were estimated, and it says so
    # a plane off the grid is rated as well: one of the 8 strained rings lies behind it
    q = propose_interface(m, tmp_path, step=50.0, also=(337.5,))
    assert q.x == pytest.approx(300.0)
    assert {c["x"]: c for c in q.candidates}[337.5]["energy_behind_percent"] == pytest.approx(100.0 * 1 / 8)


def test_interface_proposal_reports_how_far_the_cut_bends(tmp_path):
    """Field states of the tube whose rear (x < 300) bows back by
    κ·y² while the whole tube moves on: every candidate plane behind 300
    cuts a ring of nodes that bends κ(y² − mean) out of its rigid motion
    (the largest value and the rms over the ring), the planes ahead of it
    cut rings that only translate: no bending."""
    from crashlite.vehicle.connection.interface import propose_interface

    m, _, _ = _tube(per_side=4, n_len=20, masses=False)
    x0 = m.nodes.xyz
    kappa = 1e-3
    x1 = x0.copy()
    x1[:, 0] -= 50.0
    rear = x0[:, 0] < 300.0
    x1[rear, 0] -= kappa * x0[rear, 1] ** 2
    np.savez(
        tmp_path / "results.npz", states_time=np.array([0.0, 0.01]), states_x=np.stack([x0, x1]), node_ids=m.nodes.ids
    )
    ring = x0[np.isclose(x0[:, 0], 200.0), 1] ** 2  # y² of one ring's nodes
    bent = kappa * (ring - ring.mean())
    at = {round(c["x"]): c for c in propose_interface(m, tmp_path, step=50.0).candidates}
    for x in (100, 200, 250):
        assert at[x]["interface_warping_max"] == pytest.approx(np.abs(bent).max(), rel=1e-6)
        assert at[x]["interface_warping_rms"] == pytest.approx(np.sqrt((bent**2).mean()), rel=1e-6)
    for x in (350, 400):
        assert at[x]["interface_warping_max"] < 1e-9
    # without field states (measures given) nothing is said about it
    eps = np.zeros(len(m.shells))
    assert all(
        "interface_warping_max" not in c
        for c in propose_interface(m, None, step=50.0, measures=(eps, eps + 1.0)).candidates
    )


def test_interface_proposal_takes_both_criteria():
    """Given measures on the tube (8 strained rings ahead of x = 300, 1 unit
    of energy per shell): a ring behind that absorbs as much but strains
    only 0.5 % holds 1/9 of the energy and moves the proposal behind it (the
    energy criterion); a ring that strains 2 % with almost no energy moves
    it behind that ring (the strain criterion, 1/12 of the area behind 300);
    relaxed criteria bring it back to 300."""
    from crashlite.vehicle.connection.interface import propose_interface

    m, _, _ = _tube(per_side=4, n_len=20, masses=False)
    centre = m.nodes.xyz[m.shells.nodes].mean(axis=1)[:, 0]
    eps = np.where(centre > 300.0, 0.05, 0.0)
    energy = np.where(centre > 300.0, 1.0, 0.0)
    ring = (centre > 100.0) & (centre < 125.0)
    e1 = np.where(ring, 1.0, energy)
    p = propose_interface(m, None, step=50.0, measures=(np.where(ring, 0.005, eps), e1))
    assert p.x == pytest.approx(100.0)
    at = {round(c["x"]): c for c in p.candidates}
    assert at[150]["energy_behind_percent"] == pytest.approx(100.0 / 9)
    assert at[150]["strained_area_percent_behind"] == 0.0
    assert propose_interface(m, None, step=50.0, energy=0.12, measures=(np.where(ring, 0.005, eps), e1)).x == 300.0
    ring = (centre > 150.0) & (centre < 175.0)
    e2 = np.where(ring, 1e-4, energy)
    p = propose_interface(m, None, step=50.0, measures=(np.where(ring, 0.02, eps), e2))
    assert p.x == pytest.approx(150.0)
    assert {round(c["x"]): c for c in p.candidates}[300]["strained_area_percent_behind"] == pytest.approx(100.0 / 12)
    assert propose_interface(m, None, step=50.0, strain=0.03, measures=(np.where(ring, 0.02, eps), e2)).x == 300.0
    none = propose_interface(m, None, step=50.0, measures=(np.full(len(centre), 0.05), np.ones(len(centre))))
    assert none.x is None and "does not stay elastic" in none.notes[-1]


def _two_tubes():
    """Two tubes (parts 1 and 2) side by side along x, rear rings together
    the node set "axle", a point mass on each front ring."""
    xyz, quads = tube_mesh(B, L, 4, 20)
    xyz2 = xyz + [0.0, 3 * B, 0.0]
    m = shell_model(
        np.vstack([xyz, xyz2]), np.vstack([quads, quads + len(xyz)]), pids=np.repeat([1, 2], len(quads)), thickness=T
    )
    x = m.nodes.xyz
    rear, front = np.flatnonzero(np.isclose(x[:, 0], 0.0)), np.flatnonzero(np.isclose(x[:, 0], L))
    ms = Masses.zeros(len(front))
    ms.ids = np.arange(1, len(front) + 1) + 1000
    ms.node = front.astype(np.int32)
    ms.mass = np.full(len(front), M_FRONT / len(front))
    m.masses = ms
    m.sets[("NODE", 1)] = id_list("SET_NODE_LIST_TITLE", 1, m.nodes.ids[rear], title="axle")
    return m


def test_split_shares_of_disjoint_parts_add_up_to_the_whole():
    from crashlite.vehicle.steps.massprops import split_replaced

    m = _two_tubes()
    m.masses.node[:] = np.flatnonzero(np.isclose(m.nodes.xyz[:, 0], L / 4))[: len(m.masses.node)]  # behind the cut
    cut = cut_behind(m, x=L / 2)
    axle = m.nodes.xyz[np.isclose(m.nodes.xyz[:, 0], 0.0)].mean(axis=0)
    whole = split_replaced(cut, axle)[0]
    parts = [
        split_replaced(cut, axle, only=[1])[0],
        split_replaced(cut, axle, only=[2])[0],
        split_replaced(cut, axle, without=[1, 2])[0],
    ]
    assert parts[0].mass == pytest.approx(parts[1].mass, rel=1e-12) and parts[0].mass > 0
    assert parts[2].mass > 0  # the point masses: only in the rest
    assert sum(p.mass for p in parts) == pytest.approx(whole.mass, rel=1e-12)
    first = sum(p.mass * p.cog for p in parts)
    np.testing.assert_allclose(first, whole.mass * whole.cog, rtol=1e-12, atol=1e-12 * np.abs(first).max())


def test_assembly_bodies_carry_their_own_share_of_the_interface_mass():
    """One interface body per tube: each holds its own tube's share of the
    replaced mass near the interface (as the bar lumping shares it), not
    only its cut ring's nodal masses; the total mass stays the full
    model's."""
    from crashlite.vehicle.steps.massprops import split_replaced

    m = _two_tubes()
    cut = cut_behind(m, x=L / 2)
    rm = replaced_mass(cut, axle_nodes="axle")
    k = longitudinal_stiffness(cut, "axle")
    s = build_surrogate(
        cut, {"tube 1": [1], "tube 2": [2]}, {"tube 1": 0.5, "tube 2": 0.5}, k.stiffness, rm, interface="assembly"
    )
    own = split_replaced(cut, rm.axle_points, only=[1])[0]
    assert own.mass > 0
    it = s.model.inertias
    for name in ("tube 1", "tube 2"):
        nsid = int(
            [
                r
                for r in s.model.find("CONSTRAINED_NODAL_RIGID_BODY")
                if "INERTIA" not in r.options and s.part_ids[f"interface {name}"] == int(r["pid"])
            ][0]["nsid"]
        )
        members = s.model.node_index(s.model.set_members("NODE", nsid))
        held = it.mass[np.isin(it.node, members)]
        assert held.sum() == pytest.approx(own.mass, rel=1e-9)  # its own share (the rest: no elements, no points)
    nrb = s.model.find("CONSTRAINED_NODAL_RIGID_BODY_INERTIA")[0]
    assert s.model.mass_properties().mass + nrb["tm"] == pytest.approx(m.mass_properties().mass, rel=1e-12)
