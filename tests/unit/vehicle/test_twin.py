"""The elastic twin of a cut model: what changes and what does not."""

import numpy as np
import pytest
from _structures import RHO, shell_model, tube_mesh

from crashlite import read_deck, write_deck
from crashlite.vehicle.car.records import id_list, record
from crashlite.vehicle.connection.twin import elastic_twin
from crashlite.vehicle.steps.cut import cut_behind


@pytest.fixture
def model():
    """A tube along x 0..600 in three parts: 1 (MAT_024) from 400 on, 2
    (MAT_003) 150..400, across the cut at x = 300, 3 (rigid) before 150;
    part sets as _LIST and _GENERATE, a contact naming part 2 directly."""
    xyz, q = tube_mesh(50.0, 600.0, 2, 24)
    cx = xyz[q].mean(axis=1)[:, 0]
    pids = np.where(cx > 400.0, 1, np.where(cx > 150.0, 2, 3))
    m = shell_model(xyz, q, thickness=1.5, pids=pids)
    m.curves[1] = record("DEFINE_CURVE", lcid=1, rows={"a1": np.array([0.0, 1.0]), "o1": np.array([300.0, 400.0])})
    m.materials[1] = record(
        "MAT_PIECEWISE_LINEAR_PLASTICITY_TITLE", card_title="DP600", mid=1, ro=RHO, e=2.1e5, pr=0.3, sigy=300.0, lcss=1
    )
    m.materials[2] = record("MAT_PLASTIC_KINEMATIC", mid=2, ro=RHO, e=2.0e5, pr=0.29, sigy=200.0, etan=1000.0)
    m.materials[3] = record("MAT_RIGID", mid=3, ro=RHO, e=2.1e5, pr=0.3)
    for p in (1, 2, 3):
        m.parts[p].values["mid"] = p
    m.sets[("PART", 1)] = id_list("SET_PART_LIST_TITLE", 1, [1, 2, 3], title="tube")
    m.sets[("PART", 2)] = record("SET_PART_LIST_GENERATE", sid=2, rows={"b1beg": np.array([2]), "b1end": np.array([3])})
    m.keywords.append(record("CONTACT_AUTOMATIC_SURFACE_TO_SURFACE", ssid=2, msid=1, sstyp=3, mstyp=3))
    m.keywords.append(
        record(
            "ELEMENT_MASS_PART", rows={"pid": np.array([2]), "addmass": np.array([0.002]), "finmass": np.array([0.0])}
        )
    )
    return m


def test_replaced_metal_becomes_elastic_with_the_same_constants(model):
    cut = cut_behind(model, x=300.0)
    tw = elastic_twin(cut)
    m, sh = tw.model, tw.model.shells
    behind = cut.replaced["shells"]
    orig = model.shells.pid
    # kept elements keep their parts and materials
    assert np.array_equal(sh.pid[~behind], orig[~behind])
    # part 2 crosses the cut: its replaced elements go to a new part above the deck's largest ID
    new = tw.elastic_parts[2]
    assert new == 4 and set(np.unique(sh.pid[behind & (orig == 2)])) == {new}
    assert m.parts[new]["secid"] == m.parts[2]["secid"] and m.parts[new]["hgid"] == m.parts[2]["hgid"]
    mat = m.materials[m.parts[new]["mid"]]
    assert mat.keyword == "MAT_ELASTIC"
    assert (mat["ro"], mat["e"], mat["pr"]) == (RHO, 2.0e5, 0.29)
    assert m.parts[2]["mid"] == 2  # the kept half stays plastic
    # the rigid part is left as it is, and said so; nothing of part 1 lies behind
    assert set(tw.elastic_parts) == {2} and m.parts[3]["mid"] == 3
    assert any("MAT_RIGID" in n for n in tw.notes)
    assert tw.elements == int((behind & (orig == 2)).sum())
    # the full model is untouched
    assert np.array_equal(model.shells.pid, orig) and model.parts[2]["mid"] == 2 and 4 not in model.materials


def test_twin_parts_join_the_part_sets_and_direct_names_are_reported(model):
    tw = elastic_twin(cut_behind(model, x=300.0))
    m = tw.model
    assert list(m.set_members("PART", 1)) == [1, 2, 3, 4]
    assert list(m.set_members("PART", 2)) == [2, 3, 4]
    assert m.sets[("PART", 1)].title == "tube"
    assert any("CONTACT_AUTOMATIC_SURFACE_TO_SURFACE names part 2" in n for n in tw.notes)
    assert list(model.set_members("PART", 2)) == [2, 3]


def test_a_part_wholly_behind_turns_elastic_in_place(model):
    tw = elastic_twin(cut_behind(model, x=450.0))  # part 2 wholly behind, part 1 across
    assert tw.elastic_parts[2] == 2 and tw.model.materials[tw.model.parts[2]["mid"]].keyword == "MAT_ELASTIC"
    assert tw.elastic_parts[1] == 4
    # one elastic material per plastic one
    assert len(tw.materials) == 2 and tw.summary()["parts_split"] == 1


def test_twin_deck_reads_back_with_the_mass_where_it_was(model, tmp_path):
    """Mass and CoG of the twin deck are the full model's: part 2's
    *ELEMENT_MASS_PART (2 kg on a 0.6 kg part) is shared with its twin
    part by element mass."""
    tw = elastic_twin(cut_behind(model, x=300.0))
    path = write_deck(tw.model, tmp_path / "twin.k")[0]
    back = read_deck(path)
    assert not back.warnings
    full, twin = model.mass_properties(), back.mass_properties()
    assert twin.mass == pytest.approx(full.mass, rel=1e-12)
    np.testing.assert_allclose(twin.cog, full.cog, atol=1e-9)
    rows = back.find("ELEMENT_MASS_PART")[0].rows
    assert list(rows["pid"]) == [2, 4] and rows["addmass"].sum() == pytest.approx(0.002, rel=1e-12)
    # part 2 runs from x = 150 to 400: 100 mm of it kept, 150 behind the cut
    np.testing.assert_allclose(rows["addmass"], [0.002 * 0.4, 0.002 * 0.6], rtol=1e-12)
    assert back.materials[back.parts[4]["mid"]].keyword == "MAT_ELASTIC"
