"""Materials the method needs, hourglass controls and sections."""

import math

from ..layout import Card, Layout, Spec, card, fixed, register


def _mat(name, alias, *cards_, doc=""):
    register(Spec(name, fixed(*cards_), aliases=(alias,), group="materials", id_field="mid", doc=doc))


_mat("MAT_ELASTIC", "MAT_001", card("mid:i@mat ro:f e:f pr:f=0 da:f=0 db:f=0 k:f=0"), doc="Isotropic elastic.")
_mat(
    "MAT_PLASTIC_KINEMATIC",
    "MAT_003",
    card("mid:i@mat ro:f e:f pr:f=0 sigy:f etan:f=0 beta:f=0"),
    card("src:f=0 srp:f=0 fs:f~1e20 vp:f=0", optional=True),
    doc="Bilinear elastic-plastic, kinematic/isotropic hardening, Cowper-Symonds rate effect.",
)
_mat(
    "MAT_RIGID",
    "MAT_020",
    card("mid:i@mat ro:f e:f pr:f=0 n:f=0 couple:f=0 m:f=0 alias:s"),
    card("cmo:f=0 con1:f=0 con2:f=0", optional=True),
    card("lco:f=0 a2:f=0 a3:f=0 v1:f=0 v2:f=0 v3:f=0", optional=True),
    doc="Rigid body; CMO/CON1/CON2 constrain its motion.",
)
_mat(
    "MAT_PIECEWISE_LINEAR_PLASTICITY",
    "MAT_024",
    card("mid:i@mat ro:f e:f pr:f=0 sigy:f etan:f=0 fail:f~1e21 tdel:f=0"),
    card("c:f=0 p:f=0 lcss:i=0@curve lcsr:i=0@curve vp:f=0 lcf:i=0@curve"),
    card(" ".join(f"eps{i}:f=0" for i in range(1, 9)), optional=True),
    card(" ".join(f"es{i}:f=0" for i in range(1, 9)), optional=True),
    doc="Elasto-plastic with a stress-strain curve (LCSS) or 8 points, strain rate, failure.",
)
_mat(
    "MAT_PLASTICITY_WITH_DAMAGE",
    "MAT_081",
    card("mid:i@mat ro:f e:f pr:f=0 sigy:f etan:f=0 eppf:f~1e12 tdel:f=0"),
    card("c:f=0 p:f=0 lcss:i=0@curve lcsr:i=0@curve eppfr:f~1e14 vp:f=0 lcdm:i=0@curve numint:i=0"),
    card(" ".join(f"eps{i}:f=0" for i in range(1, 9)), optional=True),
    card(" ".join(f"es{i}:f=0" for i in range(1, 9)), optional=True),
    doc="MAT_024's plasticity with damage: the stress scaled by 1 - D from EPPF (softening begins) "
    "to EPPFR (rupture), D linear or the curve LCDM; NUMINT failed points delete a shell (0: all).",
)
_mat(
    "MAT_HONEYCOMB",
    "MAT_026",
    card("mid:i@mat ro:f e:f pr:f=0 sigy:f vf:f mu:f~0.05 bulk:f=0"),
    card(
        "lca:i@curve lcb:i=0@curve lcc:i=0@curve lcs:i=0@curve lcab:i=0@curve lcbc:i=0@curve "
        "lcca:i=0@curve lcsr:i=0@curve"
    ),
    card("eaau:f ebbu:f=0 eccu:f=0 gabu:f=0 gbcu:f=0 gcau:f=0 aopt:f=0 macf:i~1"),
    card("xp:f=0 yp:f=0 zp:f=0 a1:f=0 a2:f=0 a3:f=0", optional=True),
    card("d1:f=0 d2:f=0 d3:f=0 tsef:f=0 ssef:f=0 v1:f=0 v2:f=0 v3:f=0", optional=True),
    doc="Honeycomb: uncoupled uniaxial crush curves until compaction (VF), then elastic.",
)
register(
    Spec(
        "MAT_MODIFIED_HONEYCOMB",
        fixed(
            card("mid:i@mat ro:f e:f pr:f=0 sigy:f vf:f mu:f~0.05 bulk:f=0"),
            card(
                "lca:i lcb:i=0@curve lcc:i=0@curve lcs:i=0@curve lcab:i=0@curve lcbc:i=0@curve lcca:i=0@curve lcsr:i=0"
            ),
            card("eaau:f ebbu:f=0 eccu:f=0 gabu:f=0 gbcu:f=0 gcau:f=0 aopt:f=0 macf:i~1"),
            card("xp:f=0 yp:f=0 zp:f=0 a1:f=0 a2:f=0 a3:f=0", optional=True),
            card("d1:f=0 d2:f=0 d3:f=0 tsef:f=0 ssef:f=0 vref:f=0 tref:f=0 shdflg:f=0", optional=True),
            Card(card("v1:f=0 v2:f=0 v3:f=0").fields, True, lambda v, o: (v.get("aopt") or 0.0) in (3.0, 4.0)),
            Card(
                card("lcsra:i=0 lcsrb:i=0 lcsrc:i=0 lcsrab:i=0 lcsrbc:i=0 lcsrca:i=0").fields,
                True,
                lambda v, o: (v.get("lcsr") or 0) == -1,
            ),
        ),
        aliases=("MAT_126",),
        group="materials",
        id_field="mid",
        doc="Honeycomb as MAT_026 (LCA > 0); LCA < 0: yield stress by the angle off the cell axis "
        "(|LCA|), strong- and weak-axis hardening LCB, LCC vs volumetric strain, shear damage "
        "factors LCAB, LCBC, LCCA (or LCS) vs shear strain (SHDFLG).",
    )
)
_mat(
    "MAT_CRUSHABLE_FOAM",
    "MAT_063",
    card("mid:i@mat ro:f e:f pr:f=0 lcid:i@curve tsc:f=0 damp:f~0.1"),
    doc="Crushable foam: yield stress vs volumetric strain curve LCID.",
)
_mat("MAT_SPRING_ELASTIC", "MAT_S01", card("mid:i@mat k:f"), doc="Linear spring, stiffness K.")
_mat("MAT_DAMPER_VISCOUS", "MAT_S02", card("mid:i@mat dc:f"), doc="Linear damper, constant DC.")
_mat(
    "MAT_SPRING_NONLINEAR_ELASTIC",
    "MAT_S04",
    card("mid:i@mat lcd:i@curve lcr:i=0@curve"),
    doc="Non-linear elastic spring: force vs deflection curve LCD.",
)
_mat(
    "MAT_SPRING_GENERAL_NONLINEAR",
    "MAT_S06",
    card("mid:i@mat lcdl:i@curve lcdu:i@curve beta:f=0 tyi:f=0 cyi:f=0"),
    doc="Loading (LCDL) and unloading (LCDU) curves with hardening BETA.",
)
_mat(
    "MAT_SPRING_INELASTIC",
    "MAT_S08",
    card("mid:i@mat lcfd:i@curve ku:f ctf:f~1"),
    doc="Inelastic spring: loads along LCFD, unloads with stiffness KU; CTF tension/compression.",
)
register(
    Spec(
        "HOURGLASS",
        fixed(card("hgid:i@hg ihq:i=0 qm:f~0.1 ibq:i=0 q1:f~1.5 q2:f~0.06 qb:f qw:f")),
        group="hourglasses",
        id_field="hgid",
        doc="Hourglass control: type IHQ (1-3 viscous, 4-6 stiffness), coefficient QM.",
    )
)

# --- sections -----------------------------------------------------------------

_SHELL1 = card("secid:i@sec elform:i~2 shrf:f~1 nip:i~2 propt:f~1 qr:f=0 icomp:i=0 setyp:i~1")
_SHELL2 = card("t1:f=0 t2:f=0 t3:f=0 t4:f=0 nloc:f=0 marea:f=0 idof:f=0 edgset:i=0")


def _angles(k):
    return Card(
        card(" ".join(f"b{8 * k + i}:f=0" for i in range(1, 9))).fields,
        when=lambda v, o, k=k: (v.get("icomp") or 0) == 1 and (v.get("nip") or 2) > 8 * k,
    )


_SHELL = Layout(head=(_SHELL1, _SHELL2, *[_angles(k) for k in range(math.ceil(100 / 8))]))
register(
    Spec(
        "SECTION_SHELL",
        lambda o: _SHELL,
        group="sections",
        id_field="secid",
        doc="Shell section: formulation, integration points, thicknesses T1-T4, angles B1.. for composites (ICOMP=1).",
    )
)
register(
    Spec(
        "SECTION_SOLID",
        fixed(card("secid:i@sec elform:i~1 aet:i=0")),
        group="sections",
        id_field="secid",
        doc="Solid section: ELFORM 1 is one-point with hourglass control.",
    )
)


def _elform(*forms):
    return lambda v, o: (v.get("elform") if v.get("elform") is not None else 1) in forms


_INTEGRATED = (1, 4, 5, 9, 11, 14)
_BEAM = Layout(
    head=(
        card("secid:i@sec elform:i~1 shrf:f~1 qr:f~2 cst:f=0 scoor:f=0 nsm:f=0 naupd:f=0"),
        Card(card("ts1:f=0 ts2:f=0 tt1:f=0 tt2:f=0 nsloc:f=0 ntloc:f=0").fields, when=_elform(*_INTEGRATED)),
        Card(card("a:f=0 iss:f=0 itt:f=0 irr:f=0 sa:f=0 iist:f=0").fields, when=_elform(2, 12, 13)),
        Card(card("a:f=0 rampt:f=0 stress:f=0").fields, when=_elform(3)),
        Card(
            card("vol:f=0 iner:f=0 cid:i=0@coord ca:f=0 offset:f=0 rrcon:f=0 srcon:f=0 trcon:f=0").fields,
            when=_elform(6),
        ),
    )
)
register(
    Spec(
        "SECTION_BEAM",
        lambda o: _BEAM,
        group="sections",
        id_field="secid",
        doc="Beam section; card 2 depends on ELFORM (1 Hughes-Liu, 2 resultant, 3 truss, 6 discrete beam).",
    )
)
register(
    Spec(
        "SECTION_DISCRETE",
        fixed(card("secid:i@sec dro:i=0 kd:f=0 v0:f=0 cl:f=0 fd:f=0"), card("cdl:f=0 tdl:f=0", optional=True)),
        group="sections",
        id_field="secid",
        doc="Discrete element section: DRO 0 translational, 1 rotational.",
    )
)
