"""Contact work of a crush case split by mechanism (diagnostic; nothing in src changes).

Wraps :meth:`hollowbody.contact.ContactRuntime.add_forces` for the run. Per
pass row i (a node and its segment) the cycle's increment of the contact
energy is split exactly by rows,

    dW_i = -1/2 F_i,prev . (dx_node - sum_a N_a,prev dx_a,prev)
           -1/2 F_i . (dx_node - sum_a N_a dx_a)

(last cycle's force with last cycle's segment and weights, this cycle's with
this cycle's), which sums to the runtime's own increment (checked every cycle:
``mismatch`` counts the cycles where it did not). A spring that stores what it
is given has ``dW_i = dU_i`` with ``U = F_n^2 / (2 k) + |f_t|^2 / (2 k)`` (k
recovered from the held penetration: ``k = F_n / (g - odel)``), so
``D_i = dW_i - dU_i`` is the energy the cycle's transition created (< 0) or
dissipated (> 0). D is summed per contact by the row's transition:

* ``same``: the same segment, k unchanged; ``same_kchg``: the same segment, k
  changed while loaded (the stability cap);
* ``switch``: on to another segment (force carried over); ``flip``: the
  contact normal reversed (a two-sided shell's other side);
* ``fresh``: a new contact (its stored energy at once is ``ufresh_max`` at
  most); ``release``: dropped while loaded;
* ``fric``: the tangential (friction) part of every row.

``W`` is the contact energy (the sum of dW), ``U`` the energy still stored.
U leaves out the stiffened zone's force F_d (its stored energy depends on the
path): its loading counts as dissipated, its unloading as created, in the row
of the mechanism it happens in (a force carried over a change of segment and
given back later shows under ``same``).

The rows that created most (largest -D, one a cycle each) are kept with the
cycle, node id, mechanism, segment element / part, gaps and forces
(``--rows N`` prints the N worst): that is how a mechanism is found.

    NUMBA_NUM_THREADS=1 python benchmarks/contact_work_split.py CASE-NAME
        [--drilling F] [--crush FRACTION] [--out DIR] [--rows N]
    NUMBA_NUM_THREADS=1 python benchmarks/contact_work_split.py --cli validate shoulder
        --speed 7 --tissue solid --end-time 6 --out DIR   (any hollowbody command)

CASE-NAME is a name of ``bench_crush.cases()`` (docs/crush.md).
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from dataclasses import replace
from pathlib import Path

import numpy as np

from hollowbody.contact.runtime import ContactRuntime

MECHANISMS = ("same", "same_kchg", "switch", "flip", "fresh", "release", "fric")


def _relative(p, dx: np.ndarray, rows: np.ndarray, segs: np.ndarray, w: np.ndarray
              ) -> np.ndarray:
    """(m, 3) mm displacement of the rows' nodes relative to their contact points."""
    r = dx[p.nodes[rows]].copy()
    for a in range(4):
        wa = w[rows, a].copy()
        if a == 3:
            wa[p.seg[segs, 3] == p.seg[segs, 2]] = 0.0
        r -= wa[:, None] * dx[p.seg[segs, a]]
    return r


def _work(p, dx, so, wo, fo, sn, wn, fn) -> np.ndarray:
    """(ns,) J per row: the trapezoidal work of last cycle's and this cycle's force."""
    out = np.zeros(p.nodes.shape[0])
    po = np.nonzero(so >= 0)[0]
    if po.size:
        out[po] -= 0.5 * np.einsum("ij,ij->i", fo[po], _relative(p, dx, po, so[po], wo))
    pn = np.nonzero(sn >= 0)[0]
    if pn.size:
        out[pn] -= 0.5 * np.einsum("ij,ij->i", fn[pn], _relative(p, dx, pn, sn[pn], wn))
    return out


def _stored(f2: np.ndarray, k: np.ndarray, on: np.ndarray) -> np.ndarray:
    return np.where(on & (k > 0.0), f2 / (2.0 * np.where(k > 0.0, k, 1.0)), 0.0)


#: Rows kept per cycle and contact pass for the list of the worst (most created).
KEEP = 3
#: Rows kept in all (the list is cut back to these when it grows 20 times longer).
WORST_MAX = 500


def install(worst: list[dict] | None = None) -> dict[int, dict[str, float]]:
    """Wrap ContactRuntime.add_forces; returns the totals per contact id (filled as the
    run goes). ``worst``: a list to append the rows that created energy to."""
    totals: dict[int, dict[str, float]] = {}
    add_forces = ContactRuntime.add_forces

    def split(self, x, v, dt, cycle, f):
        old = [(p.oseg.copy(), p.ow.copy(), p.of.copy(), p.ofn.copy(), p.nprev.copy(),
                p.ft.copy(), getattr(p, "_k_split", np.zeros(p.nodes.shape[0])),
                p.ogap.copy(), p.ofd.copy()) for p in self.passes]
        xprev = self._xprev.copy()
        first = self._first
        e0 = self.energy
        add_forces(self, x, v, dt, cycle, f)
        dx = np.zeros_like(xprev) if first else self._xl - xprev
        t = totals.setdefault(self.cid, dict.fromkeys(
            (*MECHANISMS, "W", "U", "ufresh_max", "nfresh", "mismatch"), 0.0))
        dw_all = 0.0
        for ip, (p, (so, wo, fo, fno, no, fto, ko, go, fdo)) in enumerate(zip(self.passes,
                                                                            old)):
            sn = p.oseg
            on = sn >= 0
            k = np.zeros(sn.shape[0])
            den = p.ogap - p.odel
            ok = on & (p.ofn > 0.0) & (den > 0.0)
            k[ok] = p.ofn[ok] / den[ok]
            p._k_split = k
            dw = _work(p, dx, so, wo, fo, sn, p.ow, p.of)
            dwt = _work(p, dx, so, wo, fto, sn, p.ow, p.ft)
            dw_all += dw.sum()
            un_o, ut_o = _stored(fno**2, ko, so >= 0), _stored((fto**2).sum(1), ko, so >= 0)
            un_n, ut_n = _stored(p.ofn**2, k, on), _stored((p.ft**2).sum(1), k, on)
            dn = (dw - dwt) - (un_n - un_o)
            t["fric"] += float((dwt - (ut_n - ut_o)).sum())
            same = (so >= 0) & (sn == so)
            kchg = same & (np.abs(k - ko) > 1.0e-6 * np.maximum(k, ko)) & (p.ofn > 0) & (fno > 0)
            flip = (so >= 0) & on & ((p.nprev * no).sum(1) < 0.0)
            fresh = (so < 0) & on
            switch = (so >= 0) & on & (sn != so) & ~flip
            groups = {"same_kchg": kchg, "flip": flip, "switch": switch,
                      "same": same & ~kchg & ~flip, "fresh": fresh, "release": (so >= 0) & ~on}
            for name, sel in groups.items():
                t[name] += float(dn[sel].sum())
                if worst is not None:
                    bad = np.nonzero(sel & (dn < 0.0))[0]
                    for i in bad[np.argsort(dn[bad])][:KEEP]:
                        s = int(sn[i]) if sn[i] >= 0 else int(so[i])
                        worst.append({
                            "D": float(dn[i]), "cycle": int(cycle), "time": self.time,
                            "contact": self.cid, "pass": ip + 1, "mechanism": name,
                            "node": int(self._node_ids[self.nodes[p.nodes[i]]]),
                            "element": int(p.seg_eid[s]), "part": int(p.seg_pid[s]),
                            "gap": (float(go[i]), float(p.ogap[i])),
                            "F_spring": (float(fno[i]), float(p.ofn[i])),
                            "F_stiff": (float(fdo[i]), float(p.ofd[i]))})
            t["W"] += float(dw.sum())
            t["U"] += float((un_n + ut_n).sum() - (un_o + ut_o).sum())
            t["nfresh"] += int(fresh.sum())
            if fresh.any():
                t["ufresh_max"] = max(t["ufresh_max"], float(un_n[fresh].max()))
        if worst is not None and len(worst) > 20 * WORST_MAX:
            worst.sort(key=lambda r: r["D"])
            del worst[WORST_MAX:]
        de = self.energy - e0
        if abs(dw_all - de) > 1.0e-9 + 1.0e-6 * abs(de):
            t["mismatch"] += 1

    ContactRuntime.add_forces = split
    return totals


def _print(totals: dict[int, dict[str, float]], worst: list[dict], rows: int) -> None:
    for cid, t in totals.items():
        print(f"contact {cid}: " + " ".join(f"{k} {v:.3f}" for k, v in t.items()))
    worst.sort(key=lambda r: r["D"])
    for r in worst[:rows]:
        print(" ".join(f"{k} {v:.4g}" if isinstance(v, float) else
                       f"{k} ({v[0]:.4g}, {v[1]:.4g})" if isinstance(v, tuple) else f"{k} {v}"
                       for k, v in r.items()))


def main() -> None:
    if "--cli" in sys.argv:  # any hollowbody command, e.g. validate shoulder ...
        at = sys.argv.index("--cli")
        rows = int(sys.argv[sys.argv.index("--rows") + 1]) if "--rows" in sys.argv[:at] else 20
        worst: list[dict] = []
        totals = install(worst)
        from hollowbody.cli.main import main as cli

        try:
            cli(sys.argv[at + 1:])
        finally:
            _print(totals, worst, rows)
        return
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("case", help="a case name of bench_crush.cases()")
    ap.add_argument("--drilling", type=float, default=None, help="shell drilling factor")
    ap.add_argument("--crush", type=float, default=None, help="crush distance / length")
    ap.add_argument("--out", default=None, help="run folder (default: a temporary one)")
    ap.add_argument("--rows", type=int, default=0, help="print the N rows that created most")
    args = ap.parse_args()
    sys.path.insert(0, str(Path(__file__).parent))
    from bench_crush import cases
    from hollowbody.scenarios.crush import run_crush

    found = [c for c in cases() if c.name == args.case]
    if not found:
        sys.exit(f"no case {args.case!r}; one of: " + ", ".join(c.name for c in cases()))
    case = found[0] if args.crush is None else replace(found[0], crush=args.crush)
    worst = []
    totals = install(worst if args.rows else None)
    out = args.out or tempfile.mkdtemp(prefix="work-split-")
    res = run_crush(case, out, threads=1, drilling=args.drilling)
    print(f"{case.name} drilling {args.drilling}: {res.status}; internal {res.internal:.1f} J, "
          f"hourglass {res.hourglass:.1f} J, contact {res.contact:.2f} J "
          f"({res.contact_share:.2%}), energy ratio {res.energy_ratio:.4f}, "
          f"mean force {res.mean_force:.2f} kN ({res.ratio:.3f} x)")
    _print(totals, worst, args.rows)


if __name__ == "__main__":
    main()
