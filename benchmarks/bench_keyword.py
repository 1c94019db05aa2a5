"""Keyword reader throughput: lines per second on a ~1-million-line deck.

Generates a block mesh (~500k nodes, ~500k hexahedra) with the deck-building
API, writes it once, reads it once to warm up (the compiled bulk parsers are
compiled on first use and cached on disk), then reads it three times and
prints the median throughput (wall and CPU time).
Plain script: ``python benchmarks/bench_keyword.py [--n 80]``.
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np

from hollowbody.io.keyword import (
    ControlTermination,
    Deck,
    MatElastic,
    Nodes,
    Part,
    SectionSolid,
    read_deck,
    write_deck,
)


def block_deck(n: int) -> Deck:
    """Deck of an n x n x (n-1) node grid of unit hexahedra (1 mm)."""
    nx, ny, nz = n, n, n - 1
    i, j, k = np.meshgrid(np.arange(nx), np.arange(ny), np.arange(nz), indexing="ij")
    xyz = np.column_stack([i.ravel(), j.ravel(), k.ravel()]).astype(np.float64) * 1.0
    nid = np.arange(1, xyz.shape[0] + 1).reshape(nx, ny, nz)
    a = nid[:-1, :-1, :-1].ravel()
    b = nid[1:, :-1, :-1].ravel()
    c = nid[1:, 1:, :-1].ravel()
    d = nid[:-1, 1:, :-1].ravel()
    conn = np.column_stack([a, b, c, d, a + 1, b + 1, c + 1, d + 1])
    deck = Deck()
    deck.add(ControlTermination(endtim=1.0))
    deck.add(Part(pid=1, secid=1, mid=1, title="block"))
    deck.add(SectionSolid(secid=1))
    deck.add(MatElastic(mid=1, ro=1.0e-6, e=0.01, pr=0.45))
    deck.add_nodes(np.arange(1, xyz.shape[0] + 1), xyz)
    deck.add_solids(np.arange(1, conn.shape[0] + 1), 1, conn)
    return deck


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=80, help="nodes per edge (default 80)")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "bench.k"
        t0 = time.perf_counter()
        write_deck(block_deck(args.n), path)
        t_write = time.perf_counter() - t0
        with open(path, "rb") as f:
            n_lines = sum(1 for _ in f)
        read_deck(path)  # warm-up
        times, cpu = [], []
        for _ in range(args.repeat):
            t0, c0 = time.perf_counter(), time.process_time()
            deck = read_deck(path)
            times.append(time.perf_counter() - t0)
            cpu.append(time.process_time() - c0)
        n_nodes = sum(len(it.ids) for it in deck.of_type(Nodes))
        t, c = statistics.median(times), statistics.median(cpu)
        print(f"deck: {n_lines} lines ({path.stat().st_size / 1e6:.0f} MB), {n_nodes} nodes; "
              f"written in {t_write:.2f} s")
        print(f"read: median of {args.repeat}: {t:.3f} s wall ({n_lines / t / 1e6:.2f} million "
              f"lines/s), {c:.3f} s CPU ({n_lines / c / 1e6:.2f} million lines/s)")


if __name__ == "__main__":
    main()
