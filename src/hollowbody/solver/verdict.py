"""The quality of a finished run: ``"ok"``, ``"warning"`` or ``"suspect"``, with reasons.

:func:`assess` reads a run's summary (the dict written to ``summary.json``) and
checks seven indicators against :class:`Thresholds`; each has a warning and a
suspect limit (the physical argument for each default is in docs/solver.md):

- energy ratio (total / (initial kinetic + external work + mass-scaling work))
  outside a band around 1: energy created or lost by the integration;
- hourglass energy as a share of internal energy: work done by zero-energy
  modes instead of by the element's real stiffness;
- negative hourglass energy as a share of the total energy: viscous forms
  dissipate and stiffness forms store energy >= 0, so a negative sum is energy
  the hourglass control created;
- negative contact energy as a share of the total energy: penalty springs
  store energy >= 0 and friction dissipates, so a negative sum is energy the
  contact created;
- smallest time step over the initial one: a collapsing element;
- mass added by mass scaling in % of the model's mass: the inertia changed;
- nodes pushed through a contact surface, as a share of the model's nodes.

An error termination whose last energy record is the collapse itself (balanced just
before) is graded on the record before it (:func:`before_error`), the failing cycle
named as a warning.

The verdict is the worst of the indicators. It needs only the summary, so it
can be recomputed for runs written before it existed (:func:`quality_of`).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, fields, replace

OK = "ok"
WARNING = "warning"
SUSPECT = "suspect"
_RANK = {OK: 0, WARNING: 1, SUSPECT: 2}


@dataclass(frozen=True)
class Thresholds:
    """Limits of the run verdict (dimensionless; ``*_percent`` in %).

    energy_ratio_warn / energy_ratio_suspect: half-widths of the bands around 1
    (0.1: 0.9-1.1). hourglass_warn / hourglass_suspect: hourglass / internal
    energy. hourglass_negative_warn / _suspect: -hourglass / total energy.
    contact_negative_warn / _suspect: -contact / total energy.
    dt_drop_warn / _suspect: dt_min / dt_initial below which. added_mass_warn_percent /
    _suspect_percent: mass-scaling added mass. pass_through_warn /
    _suspect: nodes pushed through a surface / model nodes (warn: any node when 0).
    negligible: indicators built on an energy share are skipped when that
    energy is below this share of the reference energy (nothing deformed).
    """

    energy_ratio_warn: float = 0.10
    energy_ratio_suspect: float = 0.20
    hourglass_warn: float = 0.10
    hourglass_suspect: float = 0.30
    hourglass_negative_warn: float = 0.02
    hourglass_negative_suspect: float = 0.10
    contact_negative_warn: float = 0.02
    contact_negative_suspect: float = 0.10
    dt_drop_warn: float = 0.01
    dt_drop_suspect: float = 0.001
    added_mass_warn_percent: float = 2.0
    added_mass_suspect_percent: float = 5.0
    pass_through_warn: float = 0.0
    pass_through_suspect: float = 0.01
    negligible: float = 0.01

    @classmethod
    def parse(cls, items: list[str] | tuple[str, ...] | None) -> Thresholds:
        """Thresholds from ``key=value`` strings (e.g. ``hourglass_warn=0.15``);
        ValueError naming the key for an unknown key or a non-number."""
        known = {f.name for f in fields(cls)}
        values: dict[str, float] = {}
        for item in items or ():
            key, sep, value = item.partition("=")
            key = key.strip()
            if not sep or key not in known:
                raise ValueError(f"unknown quality threshold {item!r}; known: "
                                 f"{', '.join(sorted(known))}")
            try:
                values[key] = float(value)
            except ValueError:
                raise ValueError(f"quality threshold {key}: {value!r} is not a number") \
                    from None
        return replace(cls(), **values)

    def to_dict(self) -> dict[str, float]:
        return asdict(self)


def _num(v: object) -> float | None:
    try:
        f = float(v)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        return None
    return f if math.isfinite(f) else None


def _fmt(value: float | None, spec: str) -> str:
    """A number formatted, or 'not finite' for None (a NaN or infinity read as None)."""
    return "not finite" if value is None else format(value, spec)


def _grade(value: float, warn: float, suspect: float) -> str | None:
    """SUSPECT / WARNING / None for a value that is worse the larger it is."""
    if value > suspect:
        return SUSPECT
    if value > warn:
        return WARNING
    return None


#: how far off 1 an error termination's last energy ratio must be, one output interval
#: after a balanced record, to be read as the collapse itself (the energy more than
#: doubled or gone; measured collapses: 1e12-1e39) rather than a drift out of balance
COLLAPSE_JUMP = 1.0


def before_error(status: str, last: dict, prev: dict,
                 thresholds: Thresholds | None = None) -> dict:
    """Summary fields of an error termination whose last energy record is blown up
    (energy ratio off 1 by more than :data:`COLLAPSE_JUMP`, or not finite) while the
    record before it, one output interval earlier, is within the warning band (an
    element collapsing in the last interval): ``energies_before_error_J`` (that record,
    with its ``time_ms``); {} otherwise."""
    th = thresholds or Thresholds()
    if status == "normal termination" or not prev or "energy_ratio" not in prev:
        return {}
    r_last, r_prev = _num(last.get("energy_ratio")), _num(prev.get("energy_ratio"))
    if r_prev is None or abs(r_prev - 1.0) > th.energy_ratio_warn:
        return {}
    if r_last is not None and abs(r_last - 1.0) <= COLLAPSE_JUMP:
        return {}  # not a collapse: a run drifting out of balance is graded as it ends
    return {"energies_before_error_J": dict(prev)}


def assess(summary: dict, thresholds: Thresholds | None = None) -> tuple[str, list[dict]]:
    """(quality, reasons) of a run from its summary (see the module docstring).

    A reason: {"indicator", "level" ("warning" | "suspect"), "value", "message"};
    listed worst first.
    """
    th = thresholds or Thresholds()
    e = summary.get("energies_J") or {}
    reasons: list[dict] = []

    def add(level: str | None, indicator: str, value: float, message: str) -> None:
        if level is not None:
            reasons.append({"indicator": indicator, "level": level, "value": value,
                            "message": message})

    ratio = _num(summary.get("energy_ratio"))
    before = summary.get("energies_before_error_J")
    if before:  # graded on the last balanced record; the failing cycle's named
        e = before
        r_ok, t_ok = _num(before.get("energy_ratio")), _num(before.get("time_ms"))
        add(WARNING, "failing_cycle", ratio,
            f"energy ratio {_fmt(ratio, '.3g')} in the failing cycle; {_fmt(r_ok, '.5g')}"
            f" at t={_fmt(t_ok, '.6g')} ms, one output interval before")
        ratio = r_ok
    if ratio is not None:
        add(_grade(abs(ratio - 1.0), th.energy_ratio_warn, th.energy_ratio_suspect),
            "energy_ratio", ratio, f"energy ratio {ratio:.3g}")
    total, ie, hg = _num(e.get("total")), _num(e.get("internal")), _num(e.get("hourglass"))
    ref = max(abs(total or 0.0), abs(ie or 0.0) + abs(hg or 0.0))
    if hg is not None and hg < 0.0 and total is not None and total > 0.0:
        share = -hg / total
        add(_grade(share, th.hourglass_negative_warn, th.hourglass_negative_suspect),
            "hourglass_negative", hg, f"hourglass energy {hg:.3g} J ({_pct(-share)} of total)")
    if hg is not None and ref > 0.0 and hg > th.negligible * ref:
        share = hg / ie if ie is not None and ie > 0.0 else math.inf
        add(_grade(share, th.hourglass_warn, th.hourglass_suspect), "hourglass", share,
            f"hourglass {_pct(share)} of internal energy")
    ce = _num(e.get("contact"))
    if ce is not None and ce < 0.0 and total is not None and total > 0.0:
        share = -ce / total
        add(_grade(share, th.contact_negative_warn, th.contact_negative_suspect),
            "contact_energy", ce, f"contact energy {ce:.3g} J ({_pct(-share)} of total)")
    dt0, dtmin = _num(summary.get("dt_initial_ms")), _num(summary.get("dt_min_ms"))
    if dt0 is not None and dtmin is not None and dt0 > 0.0:
        drop = dtmin / dt0
        level = SUSPECT if drop < th.dt_drop_suspect else \
            WARNING if drop < th.dt_drop_warn else None
        add(level, "time_step", drop, f"time step fell to {drop:.2g} of the initial")
    added = _num((summary.get("mass_scaling") or {}).get("added_mass_percent"))
    if added is not None:
        add(_grade(added, th.added_mass_warn_percent, th.added_mass_suspect_percent),
            "added_mass", added, f"mass scaling added {added:.3g} % mass")
    passed = _pass_through_nodes(summary)
    nodes = _num(summary.get("nodes"))
    if passed and nodes:
        share = passed / nodes
        add(_grade(share, th.pass_through_warn, th.pass_through_suspect), "pass_through",
            passed, f"{passed} node(s) pushed through a contact surface")
    reasons.sort(key=lambda r: -_RANK[r["level"]])
    quality = max((r["level"] for r in reasons), key=_RANK.__getitem__, default=OK)
    return quality, reasons


def verdict_of(summary: dict | None) -> tuple[str | None, list[dict]]:
    """(quality, reasons) of a summary: those it holds, else recomputed with the
    default thresholds (a summary written before the verdict existed); (None, [])
    without a summary or energies (e.g. a surrogate's)."""
    if not summary:
        return None, []
    q = summary.get("quality")
    if q in _RANK:
        return q, list(summary.get("quality_reasons") or [])
    if "energies_J" not in summary and "energy_ratio" not in summary:
        return None, []
    return assess(summary)


def quality_of(summary: dict | None) -> str | None:
    """The quality of :func:`verdict_of`."""
    return verdict_of(summary)[0]


def is_suspect(summary: dict | None) -> bool:
    """True when the run's verdict is ``suspect``."""
    return quality_of(summary) == SUSPECT


def headline(quality: str, reasons: list[dict]) -> str:
    """The verdict in one line, e.g. ``SUSPECT: energy ratio 10.1, hourglass 106 % of
    internal energy`` (``quality ok`` when there is no reason)."""
    if quality == OK or not reasons:
        return "quality ok"
    worst = [r["message"] for r in reasons if r["level"] == quality]
    rest = [r["message"] for r in reasons if r["level"] != quality]
    text = f"{quality.upper()}: {', '.join(worst)}"
    return text + (f" (also {', '.join(rest)})" if rest else "")


def _pct(share: float) -> str:
    return "inf %" if math.isinf(share) else f"{100.0 * share:.3g} %"


def _pass_through_nodes(summary: dict) -> int:
    c = summary.get("contact_pass_through")
    if not isinstance(c, dict):
        return 0
    try:
        return int(sum(int((v or {}).get("nodes", 0)) for v in c.values()))
    except (TypeError, ValueError, AttributeError):
        return 0
