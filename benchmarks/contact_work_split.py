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

    NUMBA_NUM_THREADS=1 python benchmarks/contact_work_split.py CASE-NAME
        [--drilling F] [--crush FRACTION] [--out DIR]

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


def install() -> dict[int, dict[str, float]]:
    """Wrap ContactRuntime.add_forces; returns the totals per contact id (filled as the
    run goes)."""
    totals: dict[int, dict[str, float]] = {}
    add_forces = ContactRuntime.add_forces

    def split(self, x, v, dt, cycle, f):
        old = [(p.oseg.copy(), p.ow.copy(), p.of.copy(), p.ofn.copy(), p.nprev.copy(),
                p.ft.copy(), getattr(p, "_k_split", np.zeros(p.nodes.shape[0])))
               for p in self.passes]
        xprev = self._xprev.copy()
        first = self._first
        e0 = self.energy
        add_forces(self, x, v, dt, cycle, f)
        dx = np.zeros_like(xprev) if first else self._xl - xprev
        t = totals.setdefault(self.cid, dict.fromkeys(
            (*MECHANISMS, "W", "U", "ufresh_max", "nfresh", "mismatch"), 0.0))
        dw_all = 0.0
        for p, (so, wo, fo, fno, no, fto, ko) in zip(self.passes, old):
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
            t["W"] += float(dw.sum())
            t["U"] += float((un_n + ut_n).sum() - (un_o + ut_o).sum())
            t["nfresh"] += int(fresh.sum())
            if fresh.any():
                t["ufresh_max"] = max(t["ufresh_max"], float(un_n[fresh].max()))
        de = self.energy - e0
        if abs(dw_all - de) > 1.0e-9 + 1.0e-6 * abs(de):
            t["mismatch"] += 1

    ContactRuntime.add_forces = split
    return totals


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("case", help="a case name of bench_crush.cases()")
    ap.add_argument("--drilling", type=float, default=None, help="shell drilling factor")
    ap.add_argument("--crush", type=float, default=None, help="crush distance / length")
    ap.add_argument("--out", default=None, help="run folder (default: a temporary one)")
    args = ap.parse_args()
    sys.path.insert(0, str(Path(__file__).parent))
    from bench_crush import cases
    from hollowbody.scenarios.crush import run_crush

    found = [c for c in cases() if c.name == args.case]
    if not found:
        sys.exit(f"no case {args.case!r}; one of: " + ", ".join(c.name for c in cases()))
    case = found[0] if args.crush is None else replace(found[0], crush=args.crush)
    totals = install()
    out = args.out or tempfile.mkdtemp(prefix="work-split-")
    res = run_crush(case, out, threads=1, drilling=args.drilling)
    print(f"{case.name} drilling {args.drilling}: {res.status}; internal {res.internal:.1f} J, "
          f"hourglass {res.hourglass:.1f} J, contact {res.contact:.2f} J "
          f"({res.contact_share:.2%}), energy ratio {res.energy_ratio:.4f}, "
          f"mean force {res.mean_force:.2f} kN ({res.ratio:.3f} x)")
    for cid, t in totals.items():
        print(f"contact {cid}: " + " ".join(f"{k} {v:.3f}" for k, v in t.items()))


if __name__ == "__main__":
    main()
