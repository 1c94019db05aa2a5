"""Generate the open pedestrian: deck, report (JSON and Markdown) and picture.

:func:`generate` builds the body (:mod:`hollowbody.body.pedestrian`) in the
chosen posture, writes the deck with its includes
(:mod:`hollowbody.body.deck`), for ``tissue="hollow"`` converts the limb
muscle and the torso's subcutaneous fat with
:func:`hollowbody.hollow.convert.hollowize` (30 mm cells, 1.5 mm walls, the
paper's Table 1 wall materials, no self-contact, unless ``hollow_options``
says otherwise;
everything else, joints included, unchanged), checks it as a run would
(mass, element counts, first time step, unsupported keywords, initial
penetrations between segments) and writes ``report.json``, ``report.md``
and ``pedestrian.png``.
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from hollowbody.body.anthropometry import DEFAULT_MASS, DEFAULT_STATURE
from hollowbody.body.deck import pedestrian_deck
from hollowbody.body.mass_report import mass_table
from hollowbody.body.pedestrian import build_body
from hollowbody.body.penetration import penetrations
from hollowbody.io.keyword import Deck, write_deck

DEFAULT_MESH = 30.0
#: Joint centres listed in the report.
JOINT_CENTRES = ("HJC", "KJC", "AJC", "SJC", "EJC", "WJC")


@dataclass
class PedestrianOptions:
    """tissue solid|hollow; posture standing|walking; height mm; mass kg; mesh mm
    (soft-tissue element size); end_time ms; struck side l|r (walking); picture; tone
    (walking: the postural tone of :mod:`hollowbody.body.tone`)."""

    tissue: str = "solid"
    posture: str = "standing"
    height: float = DEFAULT_STATURE
    mass: float = DEFAULT_MASS
    mesh: float = DEFAULT_MESH
    end_time: float = 150.0
    struck: str = "l"
    picture: bool = True
    tone: bool = True

    def validate(self) -> None:
        """ValueError naming the first bad option."""
        if self.tissue not in ("solid", "hollow"):
            raise ValueError(f"--tissue must be solid or hollow (got {self.tissue!r})")
        if self.posture not in ("standing", "walking"):
            raise ValueError(f"--posture must be standing or walking (got {self.posture!r})")
        if not 1000.0 <= self.height <= 2300.0:
            raise ValueError(f"--height must be between 1000 and 2300 mm (got {self.height:g})")
        if not 20.0 <= self.mass <= 200.0:
            raise ValueError(f"--mass must be between 20 and 200 kg (got {self.mass:g})")
        if not 10.0 <= self.mesh <= 50.0:  # coarser: the polygonal thighs touch
            raise ValueError(f"--mesh must be between 10 and 50 mm (got {self.mesh:g})")
        if not self.end_time > 0.0:
            raise ValueError(f"--end-time must be positive (got {self.end_time:g} ms)")


def build_deck(opts: PedestrianOptions, hollow_options=None,  # noqa: ANN001
               omit: tuple[str, ...] = ()) -> tuple[Deck, dict]:
    """(deck, info) of the pedestrian; info: body, skeleton, history nodes, joints,
    omitted part ids, hollow conversion report (or None). ``omit``: arm segments left
    out of the deck (:func:`hollowbody.body.deck.pedestrian_deck`)."""
    opts.validate()
    body = build_body(opts.height, opts.mass, opts.mesh, opts.posture, opts.struck)
    deck, info = pedestrian_deck(
        body, opts.end_time, title=f"hollowbody open pedestrian: {opts.tissue}, "
        f"{opts.posture}, {opts.height:g} mm, {opts.mass:g} kg", omit=tuple(omit),
        tone=opts.tone)
    info["body"] = body
    info["conversion"] = None
    if opts.tissue == "hollow":
        from hollowbody.hollow.convert import HollowOptions, Selection, hollowize

        pids = [p for p in hollow_parts(body) if p not in info["omitted_parts"]]
        # no self-contact by default, as the generated limb (docs/hollowize.md): it
        # pushes tied wall edges apart and costs most of the run
        deck, rep = hollowize(deck, Selection(parts=pids),
                              hollow_options or HollowOptions(self_contact=False))
        info["conversion"] = rep
    return deck, info


def hollow_parts(body) -> list[int]:  # noqa: ANN001 - Body
    """Part ids the hollow variant converts: the limb muscle and the torso's fat."""
    return [p.pid for p in body.mesh.parts
            if (p.material == "muscle" and p.region != "trunk") or p.material == "fat"]


def generate(out: str | Path, opts: PedestrianOptions, hollow_options=None  # noqa: ANN001
             ) -> dict:
    """Write the deck, report and picture into ``out``; returns the report (a dict)."""
    from hollowbody.build import build_model
    from hollowbody.model.summary import summarize, unsupported_entries
    from hollowbody.solver.preflight import first_time_step

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    deck, info = build_deck(opts, hollow_options)
    body = info["body"]
    write_deck(deck, out / "pedestrian.k", flatten=False)
    model = build_model(deck)
    summ = summarize(model)
    step = first_time_step(model)
    step.pop("threads", None)
    rows = mass_table(body)
    sk = body.skeleton
    report = {
        "options": asdict(opts),
        "deck": "pedestrian.k",
        "notes": list(sk.notes),
        "joint_centres_mm": {f"{j}_{s}": sk.point(f"{j}_{s}").round(2).tolist()
                             for j in JOINT_CENTRES for s in ("l", "r")}
        | {k: sk.point(k).round(2).tolist()
           for k in ("C7T1", "T4T5", "T9T10", "T12L1", "L3L4", "L5S1", "OC", "VERT")},
        "mass": {"target_kg": float(opts.mass), "model_kg": float(summ["mass_kg"]),
                 "error_pct": 100.0 * (summ["mass_kg"] / opts.mass - 1.0),
                 "segments": rows, "flesh_scales": body.scales},
        "elements": {"solid": int(sum(g.conn.shape[0] for g in model.solid_groups)),
                     "shell": int(sum(g.conn.shape[0] for g in model.shell_groups)),
                     "nodes": int(model.node_ids.size), "parts": len(summ["parts"])},
        "time_step_ms": {"run_dt": step["run_dt"], "tssfac": step["tssfac"],
                         "solid": step["solid"], "shell": step["shell"],
                         "cycles_to_end": int(np.ceil(opts.end_time / step["run_dt"]))},
        "unsupported_keywords": [e["keyword"] for e in unsupported_entries(model)],
        "penetrations": penetrations(body.mesh),
        "history_nodes": info["history"],
        "joints": info["joints"],
        "postural_tone_Nm_per_rad": info.get("tone", {}),
        "knee": knee_report(info.get("knee", {})),
    }
    if info["conversion"] is not None:
        rep = info["conversion"]
        report["hollow"] = {"parts": [{"pid": p.pid, "title": p.title,
                                       "mass_before_kg": p.mass_before["mass_kg"],
                                       "mass_after_kg": p.mass_after["mass_kg"],
                                       "shells_added": p.shells_added}
                                      for p in rep.parts],
                            "warnings": list(rep.warnings)}
    if opts.picture:
        from hollowbody.body.picture import picture

        picture({f"{opts.tissue}, {opts.posture}": deck}, out / "pedestrian.png",
                f"open pedestrian {opts.height:g} mm, {opts.mass:g} kg")
        report["picture"] = "pedestrian.png"
    (out / "report.json").write_text(json.dumps(report, indent=1, default=_jsonable) + "\n")
    (out / "report.md").write_text(markdown(report))
    return report


def knee_report(springs: dict) -> dict:
    """The knees' springs for the report: element ids (springs x, y, z along the shank's
    axes, then dampers x, y, z), part ids and the values (:mod:`hollowbody.body.knee`)."""
    from hollowbody.body import knee

    return {"elements": springs.get("elements", {}), "parts": springs.get("parts", {}),
            "shear_kN_per_mm": knee.SHEAR_STIFFNESS, "shear_stop_mm": knee.SHEAR_STOP,
            "stop_kN_per_mm": knee.STOP_STIFFNESS, "axial_kN_per_mm": knee.AXIAL_STIFFNESS,
            "damping_kN_ms_per_mm": list(springs.get("damping", (0.0, 0.0)))}


def _jsonable(v):  # noqa: ANN001, ANN202
    if isinstance(v, np.generic):
        return v.item()
    if isinstance(v, np.ndarray):
        return v.tolist()
    raise TypeError(f"not JSON serialisable: {type(v).__name__}")


def markdown(r: dict) -> str:
    """The report as Markdown."""
    o = r["options"]
    m = r["mass"]
    e = r["elements"]
    t = r["time_step_ms"]
    lines = [f"# Open pedestrian: {o['tissue']}, {o['posture']}", "",
             f"Stature {o['height']:g} mm, mass {o['mass']:g} kg, soft-tissue element size "
             f"{o['mesh']:g} mm. Deck `{r['deck']}` (includes per body region).", ""]
    lines += [f"- {n}" for n in r["notes"]]
    lines += ["", "## Mass (target: de Leva 1996, scaled)", "",
              f"Total: model {m['model_kg']:.3f} kg, target {m['target_kg']:.3f} kg "
              f"({m['error_pct']:+.2f} %).", "",
              "| segment | target kg | model kg | error % | CoM offset mm | target I (x, y, z) "
              "kg mm^2 | model I (x, y, z) kg mm^2 |", "|---|---|---|---|---|---|---|"]
    for s in m["segments"]:
        ti = ", ".join(f"{v:.0f}" for v in s["target_inertia"])
        mi = ", ".join(f"{v:.0f}" for v in s["model_inertia"])
        lines.append(f"| {s['segment']} | {s['target_kg']:.3f} | {s['model_kg']:.3f} | "
                     f"{s['mass_error_pct']:+.2f} | {s['com_offset_mm']:.1f} | {ti} | {mi} |")
    lines += ["", "## Mesh and time step", "",
              f"{e['solid']} solids, {e['shell']} shells, {e['nodes']} nodes, {e['parts']} "
              f"parts. First time step {t['run_dt']:.4g} ms (TSSFAC {t['tssfac']:g}): "
              f"about {t['cycles_to_end']} cycles to {o['end_time']:g} ms.", "",
              "## Checks", "",
              f"- unsupported keywords: {', '.join(r['unsupported_keywords']) or 'none'}",
              f"- initial penetrations between segments: {r['penetrations']['total']}",
              "- history nodes: " + ", ".join(f"{k} {v}" for k, v in
                                              r["history_nodes"].items())]
    k = r.get("knee", {})
    if k.get("elements"):
        lines.append(f"- knees: shear springs {k['shear_kN_per_mm']:g} kN/mm to "
                     f"{k['shear_stop_mm']:g} mm, then {k['stop_kN_per_mm']:g} kN/mm; axial "
                     f"{k['axial_kN_per_mm']:g} kN/mm; dampers "
                     f"{'/'.join(f'{c:g}' for c in k['damping_kN_ms_per_mm'])} kN ms/mm; "
                     "discrete elements (x, y, z springs, x, y, z dampers) " + ", ".join(
                         f"{n} {v[0]}-{v[-1]}" for n, v in k["elements"].items()))
    if r.get("postural_tone_Nm_per_rad"):
        lines.append("- postural tone (stiffness phi/theta/psi, N m/rad): " + ", ".join(
            f"{k} {'/'.join(f'{x:g}' for x in v)}"
            for k, v in r["postural_tone_Nm_per_rad"].items()))
    if "hollow" in r:
        lines += ["", "## Hollow conversion", "", "| part | title | mass before kg | "
                  "mass after kg | shells |", "|---|---|---|---|---|"]
        for p in r["hollow"]["parts"]:
            lines.append(f"| {p['pid']} | {p['title']} | {p['mass_before_kg']:.4f} | "
                         f"{p['mass_after_kg']:.4f} | {p['shells_added']} |")
        lines += [f"- warning: {w}" for w in r["hollow"]["warnings"]]
    return "\n".join(lines) + "\n"
