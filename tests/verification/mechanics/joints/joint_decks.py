"""Rigid bodies on joints for the joint verification tests (built with the Deck API).

Every body is one rigid hexahedron (its elements only carry the nodes and set the
run's step through *MAT_RIGID's E, PR and density); its mass properties come from
*PART_INERTIA, so the analytical values use exactly the mass, centre and inertia
the solver uses. Gravity is *LOAD_BODY_Z, scaled (``g`` argument) so that a
pendulum period takes about a thousand cycles instead of millions.
"""

from __future__ import annotations

import numpy as np

from hollowbody.build import build_model
from hollowbody.io.keyword import (
    ConstrainedJoint,
    ControlTermination,
    Deck,
    DefineCoordinateSystem,
    DefineCurve,
    JointStiffnessFlexionTorsion,
    JointStiffnessGeneralized,
    LoadBody,
    LoadRigidBody,
    MatRigid,
    Part,
    PartInertia,
    SectionSolid,
)
from hollowbody.solver.energies import energies, kinetic_energy
from hollowbody.solver.setup import assemble
from hollowbody.solver.state import init_state
from hollowbody.solver.step import start, step

#: *MAT_RIGID of the bodies: E (GPa) and density (kg/mm^3) that give a 10 mm hexahedron
#: a step of about 0.045 ms (TSSFAC 0.9); they set nothing else.
E_STEP, RHO_STEP = 0.03, 1.0e-6
G_EARTH = 9.81e-3


def hexa(corner: np.ndarray, size: float = 10.0) -> np.ndarray:
    """(8, 3) nodes of the cube [corner, corner + size], LS-DYNA order."""
    c = np.asarray(corner, float)
    unit = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                     [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], float)
    return c + size * unit


def add_body(deck: Deck, pid: int, corner, *, fixed: bool = False,  # noqa: ANN001
             mass: float = 1.0, centre=(0.0, 0.0, 0.0), inertia=(1.0, 1.0, 1.0),
             size: float = 10.0, v0=(0.0, 0.0, 0.0), w0=(0.0, 0.0, 0.0),
             products=(0.0, 0.0, 0.0)) -> np.ndarray:
    """One rigid hexahedron body, part ``pid`` (nodes 100 pid + 1..8, element pid);
    returns its node ids. ``fixed``: all 6 DOFs fixed (CMO = 1, CON1 = CON2 = 7);
    otherwise *PART_INERTIA mass (kg), centre (mm), principal inertia (kg*mm^2) about
    global axes (with ``products`` IXY, IXZ, IYZ), initial velocity v0 (mm/ms) and
    angular velocity w0 (rad/ms)."""
    ids = 100 * pid + np.arange(1, 9)
    deck.add_nodes(ids, hexa(corner, size))
    deck.add_solids(np.array([pid]), pid, ids[None, :])
    deck.add(SectionSolid(secid=1)) if not any(
        isinstance(i, SectionSolid) for i in deck.items) else None
    deck.add(MatRigid(mid=pid, ro=RHO_STEP, e=E_STEP, pr=0.3,
                      **({"cmo": 1, "con1": 7, "con2": 7} if fixed else {})))
    if fixed:
        deck.add(Part(pid=pid, secid=1, mid=pid, title=f"body {pid}"))
    else:
        deck.add(PartInertia(pid=pid, secid=1, mid=pid, title=f"body {pid}",
                             xc=centre[0], yc=centre[1], zc=centre[2], tm=mass,
                             ixx=inertia[0], iyy=inertia[1], izz=inertia[2],
                             ixy=products[0], ixz=products[1], iyz=products[2],
                             vtx=v0[0], vty=v0[1], vtz=v0[2], vrx=w0[0], vry=w0[1], vrz=w0[2]))
    return ids


def gravity(deck: Deck, g: float) -> None:
    """Gravity g (mm/ms^2) in -z: *LOAD_BODY_Z SF = g on a constant curve 1."""
    deck.add(DefineCurve(lcid=1, points=[[0.0, 1.0], [1.0e6, 1.0]]))
    deck.add(LoadBody(axis="Z", lcid=1, sf=g))


def pendulum(kind: str = "SPHERICAL", theta0: float = 5.0, d: float = 100.0,
             radius_gyration: float = 30.0, mass: float = 1.0, end: float = 1.0,
             rps: float = 1.0, damp: float = 1.0, g: float | None = None) -> Deck:
    """A ground body (fixed, part 1) and a pendulum (part 2) on a joint at the origin.

    The pendulum's centre of mass is at distance d (mm) from the joint, at angle
    theta0 (degrees) from the downward vertical in the x-z plane; its inertia is
    isotropic (radius of gyration in mm); gravity g (mm/ms^2) in -z when given.
    SPHERICAL: N1 = node 102 (ground, at the origin), N2 = node 205 (pendulum, at
    the origin); REVOLUTE adds the pair on the y axis (ground node 103 and pendulum
    node 208 at (0, 10, 0)).
    """
    deck = Deck()
    deck.title = f"{kind.lower()} pendulum"
    gr = add_body(deck, 1, (-10.0, 0.0, 0.0), fixed=True)
    # ground cube [-10,0]x[0,10]x[0,10]: its node 2 is the origin, node 3 (0, 10, 0)
    th = np.radians(theta0)
    centre = (d * np.sin(th), 0.0, -d * np.cos(th))
    i = mass * radius_gyration ** 2
    p = add_body(deck, 2, (0.0, 0.0, -10.0), mass=mass, centre=centre, inertia=(i, i, i))
    # pendulum cube [0,10]x[0,10]x[-10,0]: node 5 is the origin, node 8 (0, 10, 0)
    if kind == "SPHERICAL":
        deck.add(ConstrainedJoint(kind=kind, n1=int(gr[1]), n2=int(p[4]), rps=rps, damp=damp))
    elif kind == "REVOLUTE":
        deck.add(ConstrainedJoint(kind=kind, n1=int(gr[1]), n2=int(p[4]), n3=int(gr[2]),
                                  n4=int(p[7]), rps=rps, damp=damp))
    else:
        raise ValueError(kind)
    deck.add(ControlTermination(endtim=end))
    if g is not None:
        gravity(deck, g)
    return deck


class Driver:
    """A model stepped directly (no output files): ``run_to(t)`` advances the State."""

    def __init__(self, deck: Deck) -> None:
        self.model = build_model(deck)
        self.plan = assemble(self.model)
        self.state = init_state(self.model, self.plan)
        start(self.model, self.plan, self.state)
        self.state.e0 = kinetic_energy(self.plan, self.state)
        self.joint = next(t for t in self.plan.terms if hasattr(t, "joints"))

    def step(self) -> None:
        step(self.model, self.plan, self.state, self.state.dt_next)

    def run_to(self, t_end: float, every=None) -> None:  # noqa: ANN001
        """Step until t >= t_end; ``every(driver)`` after each cycle."""
        while self.state.t < t_end:
            self.step()
            if every is not None:
                every(self)

    def energies(self) -> dict[str, float]:
        return energies(self.plan, self.state)

    def body(self, pid: int):  # noqa: ANN201
        return next(b for b in self.plan.bodies if b.pid == pid)


#: Nodes of the two-cube layout of :func:`joint_pair`: ground cube [-10,0]x[0,10]x[0,10]
#: (part 1, fixed) and body cube [0,10]^3 (part 2) share the face x = 0.
PAIR_NODES = {
    "SPHERICAL": (102, 201),
    "REVOLUTE": (102, 201, 103, 204),
    "CYLINDRICAL": (102, 201, 103, 204),
    "UNIVERSAL": (102, 201, 103, 205),
    "TRANSLATIONAL": (102, 201, 103, 204, 106, 205),
    "LOCKING": (102, 201, 103, 204, 106, 205),
}
#: Centre of mass of body 2 in :func:`joint_pair`: on the joint's axis (y) or point.
PAIR_CENTRE = {"SPHERICAL": (0.0, 0.0, 0.0), "UNIVERSAL": (0.0, 0.0, 0.0),
               "REVOLUTE": (0.0, 5.0, 0.0), "CYLINDRICAL": (0.0, 5.0, 0.0),
               "TRANSLATIONAL": (0.0, 5.0, 5.0), "LOCKING": (0.0, 5.0, 5.0)}


def joint_pair(kind: str, v0=(0.0, 0.0, 0.0), w0=(0.0, 0.0, 0.0), end: float = 1.0,  # noqa: ANN001
               mass: float = 1.0, inertia: float = 100.0, products=(0.0, 0.0, 0.0),
               axis: str = "y") -> Deck:
    """A fixed ground cube (part 1) and a free cube (part 2, isotropic inertia in
    kg*mm^2, centre :data:`PAIR_CENTRE`) on a joint of type ``kind`` whose axis is
    the global y axis (N1 = origin, N3 = (0, 10, 0)); N5 = (0, 0, 10); the universal
    joint's arms are y (ground) and z (body). Initial velocity v0 / w0 of body 2.
    ``axis="z"``: a revolute joint about z instead (N3 = N5's node, centre (0, 0, 5))."""
    deck = Deck()
    deck.title = f"{kind.lower()} joint"
    add_body(deck, 1, (-10.0, 0.0, 0.0), fixed=True)
    z = axis == "z" and kind == "REVOLUTE"
    add_body(deck, 2, (0.0, 0.0, 0.0), mass=mass,
             centre=(0.0, 0.0, 5.0) if z else PAIR_CENTRE[kind],
             inertia=(inertia, inertia, inertia), v0=v0, w0=w0, products=products)
    nodes = dict(zip(("n1", "n2", "n3", "n4", "n5", "n6"),
                     (102, 201, 106, 205) if z else PAIR_NODES[kind]))
    deck.add(ConstrainedJoint(kind=kind, **nodes))
    deck.add(ControlTermination(endtim=end))
    return deck


def curve(deck: Deck, lcid: int, f, lo: float = -1.5, hi: float = 1.5,  # noqa: ANN001
          n: int = 121) -> np.ndarray:
    """*DEFINE_CURVE ``lcid`` sampling f on [lo, hi] (n points); returns the points."""
    x = np.linspace(lo, hi, n)
    pts = np.column_stack([x, [f(v) for v in x]])
    deck.add(DefineCurve(lcid=lcid, points=pts.tolist()))
    return pts


def stiffness_pair(kind: str = "GENERALIZED", dof: int = 5, moment=(), inertia: float = 10.0,
                   end: float = 100.0, **cards) -> Deck:  # noqa: ANN001, ANN003
    """The joint of :func:`joint_pair` (body 2's centre on it, isotropic inertia) with a
    joint stiffness between parts 1 and 2 in the global system (CID 1 for both
    bodies; ``cards`` are its fields) and a moment about global axis DOF 5 / 6 / 7
    (x / y / z) on body 2: *LOAD_RIGID_BODY on curve 90 with the points ``moment``
    ((t ms, kN*mm) pairs). The joint is spherical, except for moments about y
    (theta, the middle Cardan angle): a revolute joint about y. On a spherical joint
    a fixed-direction moment about y balanced by a theta spring alone is unstable
    (a rotation delta about z tilts the spring's moment axis by phi = -tan(theta)
    delta, and the unbalanced part M phi turns the body further about z: growth rate
    sqrt(M tan(theta) / I), about 0.5 /ms here), as the solver rightly shows; so is
    a fixed-direction torque about z on a torsion spring with free bending (torque
    buckling): moments about z use a revolute joint about z."""
    kind_axis = {5: ("SPHERICAL", "y"), 6: ("REVOLUTE", "y"), 7: ("REVOLUTE", "z")}[dof]
    deck = joint_pair(kind_axis[0], end=end, inertia=inertia, axis=kind_axis[1])
    deck.add(DefineCoordinateSystem(cid=1, xl=1.0, yp=1.0))
    cls = JointStiffnessGeneralized if kind == "GENERALIZED" else JointStiffnessFlexionTorsion
    deck.add(cls(jsid=1, pida=1, pidb=2, cida=1, jid=1, **cards))
    deck.add(DefineCurve(lcid=90, points=[list(p) for p in moment]))
    deck.add(LoadRigidBody(pid=2, dof=dof, lcid=90, sf=1.0))
    return deck
