"""The pedestrian as a keyword deck: a main file with one include per body region.

Files (in the output folder): ``pedestrian.k`` (control, gravity, floor,
outputs, includes), ``materials.k`` (materials, sections, tissue curves),
``trunk.k``, ``head_neck.k``, ``leg_l.k``, ``leg_r.k``, ``arm_l.k``,
``arm_r.k`` (nodes, elements, parts of the region; side l = the body's
left, y > 0) and ``joints.k`` (joint nodes, extra nodes, joints, their
coordinate systems, stiffnesses and curves, the pelvis-sacrum merge).

Ids: node = index + 1 (joint and history nodes after the mesh's); elements
numbered part by part from 1; part ids in the order the parts were made;
materials 1.. by kind, rigid parts 1000 + pid (each its own density);
sections 1 (solids) and 10.. (shells by thickness).
"""

from __future__ import annotations

import textwrap

import numpy as np

from hollowbody.body import anatomy as an
from hollowbody.body.joints import DAMPING, STOP_STIFFNESS, joint_specs, walking_tone
from hollowbody.body.knee import Knee, knee_springs, lower_leg_mass
from hollowbody.body.materials import MATERIALS
from hollowbody.body.pedestrian import Body, part_density, rigid_bodies
from hollowbody.io.keyword import (
    ConstrainedExtraNodesNode,
    ConstrainedJoint,
    ConstrainedRigidBodies,
    ControlTermination,
    ControlTimestep,
    DatabaseAscii,
    DatabaseBinaryD3plot,
    DatabaseHistoryNode,
    Deck,
    DefineCoordinateSystem,
    DefineCurve,
    Hourglass,
    JointStiffnessGeneralized,
    LoadBody,
    MatElastic,
    MatPlasticKinematic,
    MatRigid,
    MatSimplifiedRubber,
    Part,
    PartInertia,
    RawKeyword,
    RigidwallPlanar,
    SectionShell,
    SectionSolid,
    SetNodeList,
)
from hollowbody.tissues import tissue

GRAVITY = 9.81e-3  # mm/ms^2
#: Hourglass control of the solids (IHQ, QH): assumed strain, physical stiffness.
HOURGLASS = (6, 1.0)
REGIONS = ("trunk", "head_neck", "leg_l", "leg_r", "arm_l", "arm_r")
LCID_GRAVITY = 1
LCID_TISSUE = {"muscle": 2, "fat": 3}


def comment(lines: list[str]) -> RawKeyword:
    """*COMMENT with ``lines`` (read back as an ignored keyword)."""
    return RawKeyword(keyword="COMMENT", lines=[t[:80] for t in lines], unsupported=False)


def pedestrian_deck(body: Body, end_time: float = 150.0, output_dt: float = 1.0,
                    title: str = "hollowbody open pedestrian", omit: tuple[str, ...] = (),
                    tone: bool = True) -> tuple[Deck, dict]:
    """(main deck with its includes, info) for ``body``; info: history node ids by
    name, joint ids by name, element counts, omitted part ids.

    ``omit``: arm segments (:data:`OMITTABLE`, e.g. ``("forearm_l", "hand_l")``) whose
    parts, nodes and joints are left out of the deck (a segment test that removes an
    arm's distal segments; the other ids stay as in the whole body); ValueError for
    another label. Default: the whole body (the output does not change).
    """
    mesh = body.mesh
    x = mesh.coords()
    gone = omitted_parts(body, omit)
    parts = [p for p in mesh.parts if p.pid not in gone]
    main = Deck()
    main.title = title
    main.add(ControlTermination(endtim=end_time))
    main.add(ControlTimestep(tssfac=0.9))
    main.add(DefineCurve(lcid=LCID_GRAVITY, points=[[0.0, 1.0], [1.0e6, 1.0]], title="gravity"))
    main.add(LoadBody(axis="Z", lcid=LCID_GRAVITY, sf=GRAVITY))
    for name in ("GLSTAT", "MATSUM", "RBDOUT", "NODOUT", "JNTFORC", "RWFORC", "DEFORC"):
        main.add(DatabaseAscii(name=name, dt=output_dt))
    main.add(DatabaseBinaryD3plot(dt=max(output_dt, end_time / 30.0)))
    files = {r: Deck() for r in REGIONS}
    mats = Deck()
    materials(mats, body, parts if gone else None)
    # node regions: the region of the first part that uses the node
    region_of = np.full(x.shape[0], -1)
    for p in parts:
        idx = np.unique(p.conn)
        free = idx[region_of[idx] < 0]
        region_of[free] = REGIONS.index(p.region)
    counts = {"solid": 0, "shell": 0}
    for r, name in enumerate(REGIONS):
        sel = np.flatnonzero(region_of == r)
        if sel.size:
            files[name].add_nodes(sel + 1, x[sel])
    eid = 1
    secs = shell_sections(body)
    for p in mesh.parts:
        n = p.conn.shape[0]
        ids = np.arange(eid, eid + n)
        eid += n
        if p.pid in gone:
            continue
        d = files[p.region]
        if p.kind == "solid":
            d.add_solids(ids, p.pid, p.conn + 1)
        else:
            d.add_shells(ids, p.pid, p.conn + 1)
        counts[p.kind] += n
        mid = material_id(p)
        secid = 1 if p.kind == "solid" else secs[p.thickness]
        hg = 1 if p.kind == "solid" else 0
        if p.inertia is not None:
            m, c, inertia = p.inertia
            d.add(PartInertia(pid=p.pid, secid=secid, mid=mid, title=p.name, xc=c[0],
                              yc=c[1], zc=c[2], tm=m, ixx=inertia[0, 0], ixy=inertia[0, 1],
                              ixz=inertia[0, 2], iyy=inertia[1, 1], iyz=inertia[1, 2],
                              izz=inertia[2, 2]))
        else:
            d.add(Part(pid=p.pid, secid=secid, mid=mid, hgid=hg, title=p.name))
    joints = Deck()
    info = _joints(joints, body, x.shape[0] + 1, gone, tone, first_eid=eid)
    feet = np.unique(np.concatenate([body.parts[f"foot_{s}"].conn.ravel() for s in "lr"])) + 1
    joints.add(SetNodeList(sid=1, nodes=feet, title="feet (floor contact)"))
    main.add(RigidwallPlanar(nsid=1, xh=0.0, yh=0.0, zh=1.0, fric=0.6))
    hist = info["history"]
    main.add(comment(textwrap.wrap("history nodes: " + ", ".join(f"{k} {v}" for k, v in
                                                                  hist.items()), 80)))
    main.add(DatabaseHistoryNode(ids=list(hist.values())))
    main.add_include("materials.k", mats)
    for name in REGIONS:
        main.add_include(f"{name}.k", files[name])
    main.add_include("joints.k", joints)
    info["elements"] = counts
    info["omitted_parts"] = sorted(gone)
    return main, info


#: Segments that may be left out of the deck (the arms' distal segments).
OMITTABLE = tuple(f"{s}_{side}" for side in "lr" for s in ("upper_arm", "forearm", "hand"))


def omitted_parts(body: Body, omit: tuple[str, ...]) -> set[int]:
    """Part ids of the segments ``omit`` (labels of :data:`OMITTABLE`, e.g.
    ``forearm_l``, ``hand_l``); ValueError for another label."""
    gone: set[int] = set()
    for label in omit:
        if label not in OMITTABLE:
            raise ValueError(f"cannot leave out segment {label!r}; these can be: "
                             f"{', '.join(OMITTABLE)}")
        gone.update(p.pid for p in body.mesh.parts if set(p.segment.tolist()) == {label})
    return gone


def shell_sections(body: Body) -> dict[float, int]:
    """Shell section id by thickness (mm): 10, 11, ... in ascending thickness."""
    ts = sorted({p.thickness for p in body.mesh.parts if p.kind == "shell"})
    return {t: 10 + i for i, t in enumerate(ts)}


def material_id(part: an.PartMesh) -> int:
    """Material id of a part: 1.. by kind (:data:`MATERIALS` order), rigid parts 1000 + pid."""
    return 1000 + part.pid if part.rigid else list(MATERIALS).index(part.material) + 1


def materials(d: Deck, body: Body, parts: list[an.PartMesh] | None = None) -> None:
    """Sections, hourglass control, tissue curves and materials into ``d``: those of
    ``parts`` only (ids as in the whole body's deck), or all (None, the pedestrian's)."""
    every = parts is None
    parts = body.mesh.parts if parts is None else parts
    kinds = {p.kind for p in parts}
    thick = {p.thickness for p in parts if p.kind == "shell"}
    used = {p.material for p in parts if not p.rigid}
    if every or "solid" in kinds:
        d.add(SectionSolid(secid=1, elform=1))
    for t, sid in shell_sections(body).items():
        if every or t in thick:
            d.add(SectionShell(secid=sid, elform=2, nip=3, t1=t, t2=t, t3=t, t4=t))
    if every or "solid" in kinds:
        # assumed-strain hourglass stiffness: IHQ 4's scales with the bulk modulus and
        # locks nearly incompressible tissue (docs/elements.md, docs/pedestrian.md)
        d.add(Hourglass(hgid=1, ihq=HOURGLASS[0], qm=HOURGLASS[1]))
    tissues = {m.tissue for k, m in MATERIALS.items() if k in used and m.law == "rubber"}
    for name, lcid in LCID_TISSUE.items():
        if every or name in tissues:
            ts = tissue(name)
            d.add(DefineCurve(lcid=lcid, points=np.column_stack([ts.strain, ts.stress]).tolist(),
                              title=f"{name}: engineering stress [GPa] vs strain"))
    for i, (key, m) in enumerate(MATERIALS.items(), start=1):
        if not (every or key in used):
            continue
        if m.law == "cortical":
            d.add(MatPlasticKinematic(mid=i, ro=m.density, e=m.e, pr=m.pr, sigy=m.sigy,
                                      etan=m.etan, beta=1.0, title=m.title))
        elif m.law == "rubber":
            d.add(MatSimplifiedRubber(mid=i, ro=m.density,
                                      km=m.bulk or tissue(m.tissue).bulk_modulus,
                                      lcid=LCID_TISSUE[m.tissue], title=m.title))
        elif m.law == "elastic":
            d.add(MatElastic(mid=i, ro=m.density, e=m.e, pr=m.pr, title=m.title))
    for p in parts:
        if p.rigid:
            d.add(MatRigid(mid=1000 + p.pid, ro=part_density(body, p),
                           e=MATERIALS["rigid"].e, pr=MATERIALS["rigid"].pr,
                           title=f"rigid: {p.name}"))


def _joints(d: Deck, body: Body, first_node: int, gone: set[int], use_tone: bool = True,
            first_eid: int = 1) -> dict:
    sk = body.skeleton
    pid = rigid_bodies(body)
    nid = first_node
    curves: dict[float, int] = {}

    def curve(slope: float, title: str) -> int:
        if slope not in curves:
            curves[slope] = 100 + len(curves)
            d.add(DefineCurve(lcid=curves[slope], points=[[-4.0, -4.0 * slope], [0.0, 0.0],
                                                          [4.0, 4.0 * slope]], title=title))
        return curves[slope]

    jids, knee_nodes, knees = {}, {}, []
    nodes, xyz = [], []
    damp = curve(DAMPING * 1000.0, "joint damping [kN mm] vs angle rate [rad/ms]")
    tone = walking_tone(sk) if use_tone else {}
    for j, spec in enumerate(joint_specs(tone), start=1):
        n1, n2 = nid, nid + 1
        nid += 2  # ids as in the whole body, also when a joint is left out
        if pid[spec.body_a] in gone or pid[spec.body_b] in gone:
            continue
        c = sk.point(spec.centre)
        fr = sk.frames[spec.frame]
        nodes += [n1, n2]
        xyz += [c, c]
        d.add(ConstrainedExtraNodesNode(pid=pid[spec.body_a], nid=n1))
        d.add(ConstrainedExtraNodesNode(pid=pid[spec.body_b], nid=n2))
        knee = spec.name.startswith("knee")
        if knee:  # not tied: translational springs (body/knee.py) and the stiffness
            knees.append(Knee(spec.name, n1, n2, fr))
        else:
            d.add(ConstrainedJoint(kind="SPHERICAL", n1=n1, n2=n2, jid=j, heading=spec.name))
        d.add(DefineCoordinateSystem(cid=j, xo=c[0], yo=c[1], zo=c[2], xl=c[0] + fr[0, 0],
                                     yl=c[1] + fr[0, 1], zl=c[2] + fr[0, 2],
                                     xp=c[0] + fr[1, 0], yp=c[1] + fr[1, 1],
                                     zp=c[2] + fr[1, 2], title=spec.name))
        lc = [curve(k, f"joint moment [kN mm] vs angle [rad], {k:g} N m/rad") for k in spec.k]
        (n_ph, p_ph), (n_t, p_t), (n_ps, p_ps) = spec.stops
        d.add(JointStiffnessGeneralized(
            jsid=j, pida=pid[spec.body_a], pidb=pid[spec.body_b], cida=j, cidb=0,
            jid=0 if knee else j,
            lcidph=lc[0], lcidt=lc[1], lcidps=lc[2], dlcidph=damp, dlcidt=damp,
            dlcidps=damp, esph=STOP_STIFFNESS, est=STOP_STIFFNESS, esps=STOP_STIFFNESS,
            nsaph=n_ph, psaph=p_ph, nsat=n_t, psat=p_t, nsaps=n_ps, psaps=p_ps,
            title=spec.name))
        jids[spec.name] = j
        if knee:
            knee_nodes[spec.name] = n1
    hist = {}
    for name, body_name, point in (("head_cg", "head", body.parts["head"].inertia[1]),
                                   ("T1", "T1", _zone_centre(body, "T1")),
                                   ("T8", "T8", _zone_centre(body, "T8")),
                                   ("sacrum", "sacrum", _zone_centre(body, "sacrum"))):
        d.add(ConstrainedExtraNodesNode(pid=pid[body_name], nid=nid))
        nodes.append(nid)
        xyz.append(point)
        hist[name] = nid
        nid += 1
    hist["knee_l"] = knee_nodes["knee_l"]
    hist["knee_r"] = knee_nodes["knee_r"]
    # the tibia-side knee nodes: the knee's shear is their displacement relative to knee_l/r
    hist["knee_l_tibia"] = knee_nodes["knee_l"] + 1
    hist["knee_r_tibia"] = knee_nodes["knee_r"] + 1
    springs = knee_springs(d, knees, lower_leg_mass(sk),
                           first_pid=max(p.pid for p in body.mesh.parts) + 1,
                           first_eid=first_eid)
    d.add_nodes(np.array(nodes), np.array(xyz))
    d.add(ConstrainedRigidBodies(pidm=pid["pelvis"], pids=pid["sacrum_part"]))
    for rigid, carrier in body.carriers.items():  # inertia carriers (body/inertia_fit.py)
        if carrier not in gone:
            lead = pid["pelvis"] if rigid == pid["sacrum_part"] else rigid
            d.add(ConstrainedRigidBodies(pidm=lead, pids=carrier))
    return {"history": hist, "joints": jids, "tone": tone, "knee": springs}


def _zone_centre(body: Body, zone: str) -> np.ndarray:
    p = body.parts[f"trunk_spine_{zone}"]
    return body.mesh.coords()[np.unique(p.conn)].mean(axis=0)
