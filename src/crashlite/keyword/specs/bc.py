"""Boundary conditions, initial velocities, body loads and rigid walls."""

from ..layout import Card, Layout, Spec, card, register

_IDCARD = card("id:i heading:s70")


def _rows_with_id(data):
    """_ID puts one ID card (naming the whole definition) before the data cards."""
    return lambda options: Layout(head=(_IDCARD,) if "ID" in options else (), row=(data,))


def _spc(data):
    """*BOUNDARY_SPC: one ID card with _ID; _BIRTH_DEATH follows each data
    card with the constraint's activation and deactivation times."""
    life = card("birth:f=0 death:f~1e20")
    return lambda options: Layout(
        head=(_IDCARD,) if "ID" in options else (), row=(data, life) if "BIRTH" in options else (data,)
    )


def _motion_rows(data):
    """*BOUNDARY_PRESCRIBED_MOTION: with _ID every motion carries its own ID
    card before its data card (LS-DYNA reads ID/data pairs: a deck with four
    pairs under one keyword is echoed in d3hsp as motions ID5 … ID8)."""
    return lambda options: Layout(row=(_IDCARD, data) if "ID" in options else (data,))


_DOFS = "dofx:i=0 dofy:i=0 dofz:i=0 dofrx:i=0 dofry:i=0 dofrz:i=0"
register(
    Spec(
        "BOUNDARY_SPC_NODE",
        _spc(card(f"nid:i@node cid:i=0@coord {_DOFS}")),
        options=("ID", "BIRTH", "DEATH"),
        doc="Nodal single-point constraints (1 fixes a DOF); _BIRTH_DEATH: active from BIRTH to DEATH.",
    )
)
register(
    Spec(
        "BOUNDARY_SPC_SET",
        _spc(card(f"nsid:i@set_node cid:i=0@coord {_DOFS}")),
        options=("ID", "BIRTH", "DEATH"),
        doc="Single-point constraints on a node set; _BIRTH_DEATH: active from BIRTH to DEATH.",
    )
)
_MOTION = "dof:i=0 vad:i=0 lcid:i=0@curve sf:f~1 vid:i=0@vector death:f~1e28 birth:f=0"
register(
    Spec(
        "BOUNDARY_PRESCRIBED_MOTION_NODE",
        _motion_rows(card(f"nid:i@node {_MOTION}")),
        options=("ID",),
        doc="Prescribed velocity (VAD 0), acceleration (1) or displacement (2).",
    )
)
register(
    Spec(
        "BOUNDARY_PRESCRIBED_MOTION_SET",
        _motion_rows(card(f"nsid:i@set_node {_MOTION}")),
        options=("ID",),
        doc="Prescribed motion of a node set.",
    )
)
register(
    Spec(
        "BOUNDARY_PRESCRIBED_MOTION_RIGID",
        _motion_rows(card(f"pid:i@part {_MOTION}")),
        options=("ID",),
        doc="Prescribed motion of a rigid part.",
    )
)

register(
    Spec(
        "INITIAL_VELOCITY",
        lambda o: Layout(
            head=(
                card("nsid:i=0@set_node nsidex:i=0@set_node boxid:i=0 irigid:i=0 icid:i=0@coord"),
                card("vx:f=0 vy:f=0 vz:f=0 vxr:f=0 vyr:f=0 vzr:f=0"),
                Card(
                    card("vxe:f=0 vye:f=0 vze:f=0 vxre:f=0 vyre:f=0 vzre:f=0").fields,
                    when=lambda v, o: (v.get("nsidex") or 0) > 0,
                ),
            )
        ),
        doc="Initial velocity of a node set (NSID 0: all nodes) except NSIDEX.",
    )
)
register(
    Spec(
        "INITIAL_VELOCITY_NODE",
        lambda o: Layout(row=(card("nid:i@node vx:f=0 vy:f=0 vz:f=0 vxr:f=0 vyr:f=0 vzr:f=0 icid:i=0@coord"),)),
        doc="Initial velocity per node.",
    )
)
register(
    Spec(
        "INITIAL_VELOCITY_GENERATION",
        lambda o: Layout(
            head=(
                card("id:i styp:i=2 omega:f=0 vx:f=0 vy:f=0 vz:f=0 ivatn:i=0 icid:i=0@coord"),
                card("xc:f=0 yc:f=0 zc:f=0 nx:f=0 ny:f=0 nz:f=0 phase:i=0 irigid:i=0"),
            )
        ),
        doc="Initial translation plus rotation OMEGA about an axis through (XC, YC, ZC); "
        "STYP 1 part set, 2 part, 3 node set.",
    )
)
register(
    Spec(
        "INITIAL_VELOCITY_RIGID_BODY",
        lambda o: Layout(row=(card("pid:i@part vx:f=0 vy:f=0 vz:f=0 vxr:f=0 vyr:f=0 vzr:f=0 lcid:i=0@coord"),)),
        title_option=False,
        doc="Initial translational (VX, VY, VZ) and angular velocity (VXR, VYR, VZR, about the centre of "
        "mass) of a rigid part; LCID: the local system they are given in.",
    )
)
for _axis in "XYZ":
    register(
        Spec(
            f"LOAD_BODY_{_axis}",
            lambda o: Layout(head=(card("lcid:i@curve sf:f~1 lciddr:i=0@curve xc:f=0 yc:f=0 zc:f=0 cid:i=0@coord"),)),
            doc=f"Body acceleration along {_axis} (e.g. gravity).",
        )
    )

_NODAL_LOAD = "dof:i lcid:i@curve sf:f~1 cid:i=0@coord m1:i=0@node m2:i=0@node m3:i=0@node"
register(
    Spec(
        "LOAD_NODE_POINT",
        lambda o: Layout(row=(card(f"nid:i@node {_NODAL_LOAD}"),)),
        doc="Nodal force (DOF 1-3), follower force (4), moment (5-7) or follower moment (8) from a load curve.",
    )
)
register(
    Spec(
        "LOAD_NODE_SET",
        lambda o: Layout(row=(card(f"nsid:i@set_node {_NODAL_LOAD}"),)),
        doc="Nodal load on every node of a node set.",
    )
)

_RWID = card("rwid:i@rigidwall heading:s70")


def _planar(options: frozenset) -> Layout:
    head = [_RWID] if "ID" in options else []
    head += [
        card("nsid:i=0@set_node nsidex:i=0@set_node boxid:i=0 offset:f=0 birth:f=0 death:f~1e20 rwksf:f~1"),
        card("xt:f=0 yt:f=0 zt:f=0 xh:f=0 yh:f=0 zh:f=0 fric:f=0 wvel:f=0"),
    ]
    if "FINITE" in options:
        head.append(card("xhev:f=0 yhev:f=0 zhev:f=0 lenl:f=0 lenm:f=0"))
    if "MOVING" in options:
        head.append(card("mass:f=0 v0:f=0"))
    if "FORCES" in options:
        head.append(card("soft:i=0 ssid:i=0@set_segment n1:i=0@node n2:i=0@node n3:i=0@node n4:i=0@node"))
    return Layout(head=tuple(head))


register(
    Spec(
        "RIGIDWALL_PLANAR",
        _planar,
        options=("ID", "FINITE", "MOVING", "FORCES"),
        id_field="rwid",
        title_option=False,
        doc="Planar rigid wall: normal from tail (XT..) to head (XH..); _MOVING gives "
        "it a mass and initial velocity, _FINITE a size, _FORCES a force segment.",
    )
)


def _cylinder(options: frozenset) -> Layout:
    head = [_RWID] if "ID" in options else []
    head += [
        card("nsid:i=0@set_node nsidex:i=0@set_node boxid:i=0 birth:f=0 death:f~1e20"),
        card("xt:f=0 yt:f=0 zt:f=0 xh:f=0 yh:f=0 zh:f=0 fric:f=0"),
        card("radcyl:f lencyl:f=0"),
    ]
    if "MOTION" in options:
        head.append(card("lcid:i=0@curve opt:i=0 vx:f=0 vy:f=0 vz:f=0"))
    if "DISPLAY" in options:
        head.append(card("pid:i=0 ro:f~1e-9 e:f~1e-4 pr:f~0.3"))
    return Layout(head=tuple(head))


register(
    Spec(
        "RIGIDWALL_GEOMETRIC_CYLINDER",
        _cylinder,
        options=("ID", "MOTION", "DISPLAY"),
        id_field="rwid",
        title_option=False,
        doc="Cylindrical rigid wall (axis from tail to head, radius RADCYL, length LENCYL).",
    )
)
