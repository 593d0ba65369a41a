"""The layout of the generic compact car: its parts as lattice pieces.

Axes: x forward (the car drives in +x), y to the left, z up; the front
axle at x = 0, the ground at z = 0; millimetres. Overall 3.83 m long
(bumper face x = 830, rear panel x = −3000), 1.69 m wide over the doors,
1.40 m high; wheelbase 2.48 m (rear axle x = −2480).

Load paths, front to back: bumper beam → crash boxes → front rails (closed
boxes) → firewall, rail extensions, floor longitudinals, tunnel, sills;
the upper rails (aprons) from the radiator support to the firewall beside
the hinge pillars. The rigid engine and gearbox block sits between the
rails on two mount brackets. The exhaust hangs in the tunnel on two
hangers, clear of the engine: a real exhaust's flexible joint lets the
engine move back without pushing it, so it is no load path.
Behind the firewall: hinge pillars and A-pillars, cowl, windshield, roof
with rails and headers, B-pillars, sills, floor halves with longitudinals
and seat cross members, tunnel, doors (outboard of the body side on hinges
and a latch), heel kick, rear floor on the rear rails, rigid rear axle
between the rear rails, rear side panels, C-pillars, rear window, tail cross member,
rear panel.

The passenger cell is built to stay nearly elastic in a 56 km/h full-width
crash (the premise of the simplified vehicle): the rail extension steps down
to the floor longitudinal in two stages; the toe pan and the front end of
the floor longitudinal, where that step turns the rail's load, are thicker
and stronger than the floor behind; torque boxes under the floor take part
of it out to the sills, whose front ends are closed; the floor longitudinals
run on under the rear rails' front ends (the kick-up), and the heel kick is
closed by the rear seat cross member, which also takes the tunnel's end; the
doors' hinge ends are reinforced and their hinges and latches are weld
patches. The engine's rear face leaves 120 mm to the firewall.

Joints: pieces that touch share their nodes (the lattice is conforming);
the doors are the only separate bodies (5 mm outboard of the body side),
held by two hinges and a latch (patches of *CONSTRAINED_SPOTWELD pairs).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from math import hypot

from .lattice import Plate, Ruled, Tube

DOOR_GAP = 5.0  # [mm] door inner panel to body side
DOOR_DEPTH = 80.0  # [mm] door box, inner panel to outer skin
HINGE_REACH = 40.0  # [mm] half the height of a hinge or latch plate (its weld patch)


@dataclass(frozen=True)
class PartDef:
    """One part: its pieces, sheet grade and thickness [mm], the assembly it
    belongs to (the paper's groups for the interface sections), a rigid
    translation ``shift`` [mm] (doors) and, for rigid parts, the mass [kg]."""

    name: str
    assembly: str
    grade: str
    thickness: float
    pieces: tuple
    shift: tuple = (0.0, 0.0, 0.0)
    mass: float = 0.0


@dataclass(frozen=True)
class MassGroup:
    """Lumped masses spread evenly over the nodes of ``parts`` inside the box
    ``lo``..``hi`` [mm]; ``nominal`` [kg] is the starting guess that the
    trim (``trim.solve``) moves as little as it can."""

    name: str
    parts: tuple
    lo: tuple
    hi: tuple
    nominal: float


def _bx(x0, x1, y0, y1, z0, z1):
    """Closed box tube along x."""
    return Tube(0, x0, x1, ((y0, z0), (y1, z0), (y1, z1), (y0, z1)))


def _by(y0, y1, x0, x1, z0, z1):
    """Closed box tube along y (profile in x, z)."""
    return Tube(1, y0, y1, ((x0, z0), (x1, z0), (x1, z1), (x0, z1)))


def _bz(z0, z1, x0, x1, y0, y1):
    """Closed box tube along z (profile in x, y)."""
    return Tube(2, z0, z1, ((x0, y0), (x1, y0), (x1, y1), (x0, y1)))


def _px(x, y0, y1, z0, z1):
    return Plate(0, x, (y0, z0), (y1, z1))


def _py(y, x0, x1, z0, z1):
    return Plate(1, y, (x0, z0), (x1, z1))


def _pz(z, x0, x1, y0, y1):
    return Plate(2, z, (x0, y0), (x1, y1))


def _hat_x(x0, x1, y0, y1, z_base, z_top):
    """Hat section along x closed by a sheet at ``z_base`` (walls at y0, y1)."""
    return Tube(0, x0, x1, ((y0, z_base), (y0, z_top), (y1, z_top), (y1, z_base)), closed=False)


def _sides():
    return (("left", 1.0), ("right", -1.0))


def _y(s, a, b):
    """The lateral interval a..b (a, b > 0 on the left) on side s, increasing."""
    return (a, b) if s > 0 else (-b, -a)


A_LENGTH = hypot(820.0, 550.0)  # cowl top rear edge (x −330, z 850) to roof front (x −1150, z 1400)
C_LENGTH = hypot(400.0, 450.0)  # rear header (x −2600, z 1300) to tail member (x −3000, z 850)


# bumper beams: sheet thickness [mm] and the x of its back (its face at x = 830); "stiff" is the second front
# a barrier is checked under (a thicker, shallower beam), so that it is not tuned to one car
FRONTS = {"generic": (1.6, 760.0), "stiff": (2.5, 785.0)}


def parts(engine_mass: float = 170.0, axle_mass: float = 73.0, front: str = "generic") -> list[PartDef]:
    """The parts of the car, front to back (rigid masses in kg); ``front``
    one of FRONTS (the crash boxes reach the bumper beam's back)."""
    if front not in FRONTS:
        raise ValueError(f"front must be one of {', '.join(FRONTS)}, got {front!r}")
    t_bumper, x_back = FRONTS[front]
    P = []

    def add(*a, **k):
        P.append(PartDef(*a, **k))

    # --- front structure ----------------------------------------------------------------------
    add("bumper beam", "bumper beam", "MS1200", t_bumper, (_by(-680.0, 680.0, x_back, 830.0, 390.0, 500.0),))
    for side, s in _sides():
        y0, y1 = _y(s, 410.0, 490.0)
        add(f"crash box {side}", f"crash box {side}", "DP600", 1.2, (_bx(610.0, x_back, y0, y1, 390.0, 500.0),))
        add(f"front rail {side}", f"front rail {side}", "DP600", 1.6, (_bx(-250.0, 610.0, y0, y1, 390.0, 500.0),))
        # behind the firewall the rail goes on as a tall hat on the floor (the toe-board box), stiffer than
        # the rail so that the rail folds in front of it
        # it steps down in two stages so that no section has to turn the whole rail load through the
        # height between rail and floor longitudinal at once
        add(
            f"rail extension {side}",
            f"front rail {side}",
            "DP800",
            2.0,
            (
                _hat_x(-400.0, -250.0, y0, y1, 250.0, 500.0),
                _px(-400.0, y0, y1, 350.0, 500.0),
                _hat_x(-550.0, -400.0, y0, y1, 250.0, 350.0),
                _px(-550.0, y0, y1, 250.0, 350.0),
            ),
        )
        # torque box: from the rail's floor longitudinal out to the sill, under the floor behind the firewall
        t0, t1 = _y(s, 490.0, 640.0)
        add(
            f"torque box {side}",
            f"floor {side}",
            "DP800",
            2.0,
            (Tube(1, t0, t1, ((-400.0, 250.0), (-400.0, 150.0), (-250.0, 150.0), (-250.0, 250.0)), closed=False),),
        )
    add(
        "radiator support",
        "radiator support",
        "HX340LAD",
        1.2,
        (
            _by(-680.0, 680.0, 560.0, 610.0, 700.0, 750.0),
            _by(-410.0, 410.0, 560.0, 610.0, 390.0, 460.0),
            _bz(500.0, 700.0, 560.0, 610.0, 410.0, 490.0),
            _bz(500.0, 700.0, 560.0, 610.0, -490.0, -410.0),
        ),
    )
    for side, s in _sides():
        y0, y1 = _y(s, 600.0, 680.0)
        add(f"upper rail {side}", f"upper rail {side}", "DP600", 1.5, (_bx(-250.0, 560.0, y0, y1, 700.0, 750.0),))
        w0, w1 = _y(s, 490.0, 600.0)
        add(f"wheelhouse {side}", f"upper rail {side}", "DC04", 0.8, (_px(0.0, w0, w1, 390.0, 750.0),))
    add(
        "engine and gearbox",
        "engine and gearbox",
        "rigid",
        3.0,
        (
            _bx(-130.0, 350.0, -300.0, 330.0, 300.0, 700.0),
            _px(-130.0, -300.0, 330.0, 300.0, 700.0),
            _px(350.0, -300.0, 330.0, 300.0, 700.0),
        ),
        mass=engine_mass,
    )
    add(
        "engine mounts",
        "engine and gearbox",
        "HX340LAD",
        3.0,
        (_pz(500.0, 100.0, 200.0, 330.0, 410.0), _pz(500.0, 100.0, 200.0, -410.0, -300.0)),
    )
    add(
        "firewall",
        "firewall",
        "DC04",
        1.2,
        (
            _px(-250.0, -680.0, -110.0, 250.0, 750.0),
            _px(-250.0, 110.0, 680.0, 250.0, 750.0),
            _px(-250.0, -110.0, 110.0, 460.0, 750.0),
        ),
    )
    add("cowl", "firewall", "HX340LAD", 1.0, (_by(-680.0, 680.0, -330.0, -250.0, 750.0, 850.0),))

    # --- passenger cell ------------------------------------------------------------------------
    for side, s in _sides():
        y0, y1 = _y(s, 680.0, 760.0)
        yi, yo = s * 680.0, s * 760.0
        add(
            f"hinge pillar {side}",
            f"A-pillar {side}",
            "PHS1500",
            1.8,
            (_bz(300.0, 850.0, -330.0, -250.0, y0, y1), _pz(850.0, -330.0, -250.0, y0, y1)),
        )
        # the A-pillar leaves the hinge pillar's rear face (top 100 mm) for the roof rail's front end
        bottom = (
            (-330.0, yi, 850.0),
            (-330.0, yo, 850.0),
            (-330.0, yo, 750.0),
            (-330.0, yi, 750.0),
            (-330.0, yi, 850.0),
        )
        top = (
            (-1150.0, yi, 1400.0),
            (-1150.0, yo, 1400.0),
            (-1150.0, yo, 1300.0),
            (-1150.0, yi, 1300.0),
            (-1150.0, yi, 1400.0),
        )
        add(f"A-pillar {side}", f"A-pillar {side}", "PHS1500", 1.4, (Ruled(bottom, top, A_LENGTH, closed=True),))
        # the sill's front end is closed by a bulkhead below the hinge pillar (beside the firewall's foot)
        add(
            f"sill {side}",
            f"door sill {side}",
            "DP800",
            1.8,
            (
                _bx(-2000.0, -250.0, *_y(s, 640.0, 760.0), 150.0, 300.0),
                _px(-250.0, *_y(s, 640.0, 760.0), 150.0, 250.0),
                _px(-250.0, *_y(s, 680.0, 760.0), 250.0, 300.0),
            ),
        )
        # the front floor (toe pan) and the front end of the floor longitudinal take the rail's load
        # down from rail height to the floor: thicker and stronger than the floor behind them
        f0, f1 = _y(s, 110.0, 640.0)
        add(f"toe pan {side}", f"floor {side}", "DP800", 1.6, (_pz(250.0, -800.0, -250.0, f0, f1),))
        add(f"floor {side}", f"floor {side}", "DP600", 1.2, (_pz(250.0, -2000.0, -800.0, f0, f1),))
        l0, l1 = _y(s, 410.0, 490.0)
        add(
            f"floor longitudinal front {side}",
            f"floor {side}",
            "PHS1500",
            2.0,
            (_hat_x(-800.0, -250.0, l0, l1, 250.0, 150.0), _px(-250.0, l0, l1, 150.0, 250.0)),
        )
        add(
            f"floor longitudinal {side}",
            f"floor {side}",
            "DP800",
            1.8,
            (_hat_x(-2000.0, -800.0, l0, l1, 250.0, 150.0), _px(-2000.0, l0, l1, 150.0, 250.0)),
        )
        ya, yb = s * 110.0, s * 640.0
        add(
            f"seat cross members {side}",
            f"floor {side}",
            "DP600",
            1.5,
            tuple(
                Tube(1, ya, yb, ((xa, 250.0), (xa, 300.0), (xb, 300.0), (xb, 250.0)), closed=False)
                for xa, xb in ((-1230.0, -1150.0), (-1700.0, -1600.0))
            ),
        )
    add(
        "tunnel",
        "tunnel",
        "DP800",
        1.5,
        (
            Tube(0, -2000.0, -250.0, ((110.0, 250.0), (110.0, 460.0), (-110.0, 460.0), (-110.0, 250.0)), closed=False),
            _px(-2000.0, -110.0, 110.0, 350.0, 460.0),
        ),
    )
    # starts 150 mm inside the tunnel: the engine stops at the firewall before it can reach it
    add("exhaust", "exhaust", "X2CrTi12", 1.2, (_bx(-1850.0, -400.0, -40.0, 40.0, 300.0, 350.0),))
    add(
        "exhaust hangers",
        "exhaust",
        "DC04",
        1.0,
        (_py(0.0, -900.0, -800.0, 350.0, 460.0), _py(0.0, -1700.0, -1600.0, 350.0, 460.0)),
    )
    for side, s in _sides():
        shift = (0.0, s * (760.0 - 680.0 + DOOR_GAP), 0.0)  # door inner panel DOOR_GAP outboard of y = 760
        yi, yo = s * 680.0, s * 760.0
        y0, y1 = _y(s, 680.0, 760.0)
        inner = ((yo, 300.0), (yi, 300.0), (yi, 850.0), (yo, 850.0))
        # the hinge end of the door inner is a reinforcement that spreads the hinges' load into the door
        add(
            f"door hinge reinforcement {side}",
            f"door {side}",
            "DP600",
            2.0,
            (Tube(0, -450.0, -330.0, inner, closed=False), _px(-330.0, y0, y1, 300.0, 850.0)),
            shift=shift,
        )
        add(
            f"door inner {side}",
            f"door {side}",
            "DC04",
            1.0,
            (Tube(0, -1450.0, -450.0, inner, closed=False), _px(-1450.0, y0, y1, 300.0, 850.0)),
            shift=shift,
        )
        add(f"door outer {side}", f"door {side}", "DC04", 0.7, (_py(yo, -1450.0, -330.0, 300.0, 850.0),), shift=shift)
    add(
        "windshield",
        "windshield",
        "glass",
        4.5,
        (
            Ruled(
                ((-330.0, -680.0, 850.0), (-330.0, 680.0, 850.0)),
                ((-1150.0, -680.0, 1400.0), (-1150.0, 680.0, 1400.0)),
                A_LENGTH,
            ),
        ),
    )
    for side, s in _sides():
        add(f"roof rail {side}", "roof", "PHS1500", 1.4, (_bx(-2600.0, -1150.0, *_y(s, 680.0, 760.0), 1300.0, 1400.0),))
    add("roof", "roof", "DC04", 0.7, (_pz(1400.0, -2600.0, -1150.0, -680.0, 680.0),))
    add(
        "roof headers",
        "roof",
        "HX340LAD",
        1.0,
        (
            Tube(
                1,
                -680.0,
                680.0,
                ((-1150.0, 1400.0), (-1150.0, 1300.0), (-1230.0, 1300.0), (-1230.0, 1400.0)),
                closed=False,
            ),
            Tube(
                1,
                -680.0,
                680.0,
                ((-2520.0, 1400.0), (-2520.0, 1300.0), (-2600.0, 1300.0), (-2600.0, 1400.0)),
                closed=False,
            ),
        ),
    )
    for side, s in _sides():
        add(
            f"B-pillar {side}",
            "B-pillars",
            "PHS1500",
            1.6,
            (_bz(300.0, 1300.0, -1530.0, -1450.0, *_y(s, 680.0, 760.0)),),
        )

    # --- rear structure ------------------------------------------------------------------------
    # heel kick: the riser between floor and rear floor, closed by the rear seat cross member in front of
    # it, which also takes the tunnel's rear end
    add("heel kick", "rear floor", "DP600", 1.2, (_px(-2000.0, -640.0, 640.0, 250.0, 350.0),))
    add(
        "rear seat cross member",
        "rear floor",
        "DP600",
        1.5,
        (Tube(1, -640.0, 640.0, ((-2000.0, 350.0), (-1920.0, 350.0), (-1920.0, 250.0)), closed=False),),
    )
    add("rear floor", "rear floor", "HX340LAD", 0.9, (_pz(350.0, -3000.0, -2000.0, -760.0, 760.0),))
    for side, s in _sides():
        y0, y1 = _y(s, 410.0, 490.0)
        add(f"rear rail {side}", "rear rails", "DP600", 1.6, (_hat_x(-3000.0, -2000.0, y0, y1, 350.0, 250.0),))
        # the rear rail's kick-up: the floor longitudinal goes on under the rail's front end, so the rear
        # structure's load passes from one to the other over 300 mm instead of at a corner
        add(
            f"rear rail kick {side}",
            "rear rails",
            "DP800",
            1.8,
            (_hat_x(-2300.0, -2000.0, y0, y1, 250.0, 150.0), _px(-2300.0, y0, y1, 150.0, 250.0)),
        )
    add(
        "rear axle",
        "rear axle",
        "rigid",
        3.0,
        (Tube(1, -410.0, 410.0, ((-2520.0, 250.0), (-2440.0, 250.0), (-2440.0, 300.0), (-2520.0, 300.0))),),
        mass=axle_mass,
    )
    for side, s in _sides():
        yi, yo = s * 680.0, s * 760.0
        add(f"rear side panel {side}", "rear body", "DC04", 0.8, (_py(yo, -2920.0, -1530.0, 300.0, 850.0),))
        add(
            f"rear pillar {side}",
            "rear body",
            "HX340LAD",
            1.2,
            (_bz(350.0, 850.0, -3000.0, -2920.0, *_y(s, 680.0, 760.0)),),
        )
        # the C-pillar leaves the roof rail's underside for the rear pillar's top
        top = (
            (-2600.0, yi, 1300.0),
            (-2600.0, yo, 1300.0),
            (-2520.0, yo, 1300.0),
            (-2520.0, yi, 1300.0),
            (-2600.0, yi, 1300.0),
        )
        bottom = (
            (-3000.0, yi, 850.0),
            (-3000.0, yo, 850.0),
            (-2920.0, yo, 850.0),
            (-2920.0, yi, 850.0),
            (-3000.0, yi, 850.0),
        )
        add(f"C-pillar {side}", "rear body", "HX340LAD", 1.2, (Ruled(top, bottom, C_LENGTH, closed=True),))
    add(
        "rear window",
        "rear body",
        "glass",
        3.5,
        (
            Ruled(
                ((-2600.0, -680.0, 1300.0), (-2600.0, 680.0, 1300.0)),
                ((-3000.0, -680.0, 850.0), (-3000.0, 680.0, 850.0)),
                C_LENGTH,
            ),
        ),
    )
    add("tail cross member", "rear body", "HX340LAD", 1.2, (_by(-680.0, 680.0, -3000.0, -2920.0, 750.0, 850.0),))
    add("rear panel", "rear body", "DC04", 0.8, (_px(-3000.0, -680.0, 680.0, 250.0, 750.0),))
    return P


# interface assemblies of the paper (section forces at the interface)
INTERFACE_ASSEMBLIES = (
    "A-pillar left",
    "A-pillar right",
    "door sill left",
    "door sill right",
    "floor left",
    "floor right",
    "tunnel",
    "exhaust",
    "door left",
    "door right",
    "windshield",
)


def mass_groups() -> list[MassGroup]:
    """Non-structural masses of the car (wheels, seats and occupants, trim,
    fluids), each over the nodes of a few parts near where it sits."""
    big = 1e5
    G = [
        MassGroup(
            "front wheel and suspension left", ("front rail left",), (-80.0, 0.0, 0.0), (100.0, big, 395.0), 32.0
        ),
        MassGroup(
            "front wheel and suspension right", ("front rail right",), (-80.0, -big, 0.0), (100.0, 0.0, 395.0), 32.0
        ),
        MassGroup("rear wheel left", ("rear rail left",), (-2620.0, 0.0, 0.0), (-2380.0, big, 255.0), 25.0),
        MassGroup("rear wheel right", ("rear rail right",), (-2620.0, -big, 0.0), (-2380.0, 0.0, 255.0), 25.0),
        MassGroup("cooling module", ("radiator support",), (-big, -big, -big), (big, big, big), 18.0),
        MassGroup("battery", ("upper rail left",), (300.0, 0.0, 0.0), (560.0, big, big), 15.0),
        MassGroup("instrument panel and steering", ("cowl",), (-big, -big, -big), (big, big, big), 35.0),
        MassGroup(
            "front seat and occupant left",
            ("seat cross members left", "B-pillar left"),
            (-1750.0, 0.0, 250.0),
            (-1100.0, big, 1100.0),
            95.0,
        ),
        MassGroup(
            "front seat and occupant right",
            ("seat cross members right", "B-pillar right"),
            (-1750.0, -big, 250.0),
            (-1100.0, 0.0, 1100.0),
            95.0,
        ),
        MassGroup("rear seat", ("heel kick", "rear floor"), (-2400.0, -big, -big), (-1990.0, big, big), 30.0),
        MassGroup("fuel tank", ("rear rail left", "rear rail right"), (-2400.0, -big, -big), (-2000.0, big, big), 35.0),
        MassGroup("luggage and spare wheel", ("rear floor",), (-3000.0, -big, -big), (-2620.0, big, big), 20.0),
        MassGroup(
            "headliner and roof trim", ("roof rail left", "roof rail right"), (-big, -big, -big), (big, big, big), 10.0
        ),
        MassGroup("door trim left", ("door inner left",), (-big, 0.0, -big), (big, big, big), 12.0),
        MassGroup("door trim right", ("door inner right",), (-big, -big, -big), (big, 0.0, big), 12.0),
        MassGroup(
            "carpet and centre console",
            ("floor left", "floor right", "tunnel"),
            (-big, -big, -big),
            (big, big, big),
            25.0,
        ),
    ]
    return G


@dataclass(frozen=True)
class Hinge:
    """A door joint: the node of ``door_part`` nearest to ``door`` (before
    the door's shift) welded to the node of ``body_part`` nearest to ``body``."""

    name: str
    door_part: str
    door: tuple
    body_part: str
    body: tuple


def door_joints() -> list[Hinge]:
    out = []
    for side, s in _sides():
        for name, door, pillar, x, z in (
            ("upper hinge", "door hinge reinforcement", "hinge pillar", -330.0, 700.0),
            ("lower hinge", "door hinge reinforcement", "hinge pillar", -330.0, 450.0),
            ("latch", "door inner", "B-pillar", -1450.0, 650.0),
        ):
            out.append(
                Hinge(f"door {side} {name}", f"{door} {side}", (x, s * 680.0, z), f"{pillar} {side}", (x, s * 760.0, z))
            )
    return out


@dataclass(frozen=True)
class Sensor:
    """A history node: the node of ``parts`` nearest to ``at`` [mm] (all parts when empty)."""

    name: str
    at: tuple
    parts: tuple = field(default_factory=tuple)


def sensors(cog_x: float, cog_z: float) -> list[Sensor]:
    return [
        Sensor("engine top", (160.0, 15.0, 700.0), ("engine and gearbox",)),
        Sensor("vehicle CoG", (cog_x, 0.0, cog_z), ("tunnel",)),
        Sensor("rear seat left", (-2200.0, 350.0, 350.0), ("rear floor",)),
        Sensor("rear seat right", (-2200.0, -350.0, 350.0), ("rear floor",)),
        Sensor("B-pillar sill left", (-1490.0, 700.0, 300.0), ("sill left",)),
        Sensor("B-pillar sill right", (-1490.0, -700.0, 300.0), ("sill right",)),
    ]
