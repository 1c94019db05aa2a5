"""A run gives the same numbers whether its process compiled the shell kernel or loaded
it from the kernel cache.

With fast-math reassociation and FMA contraction the element loop compiled in the running
process and the same kernel loaded from the disk cache differed in round-off (element
forces by up to 4e-15 kN after a few cycles of a crushing hollow block), which a crush
amplified into another cycle count. Two processes share a fresh cache folder: the first
compiles, the second loads; every shell force of the first cycles must agree bit for bit.
"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap

import numpy as np

SCRIPT = textwrap.dedent('''
    import sys
    import numpy as np
    import hollowbody.elements.shell_group as sg
    from hollowbody.scenarios.block import BlockConfig, block_impact

    forces = []
    kernel = sg.bt_shell_forces

    def recording(law, x, v, w, dt, geom, state, params, history, kp, out):
        kernel(law, x, v, w, dt, geom, state, params, history, kp, out)
        forces.append(out[0].copy())

    sg.bt_shell_forces = recording
    cfg = BlockConfig(tissue="muscle", structure="hollow", speed_kmh=100, end_time=0.4,
                      hollow_E=76.73, hollow_yield=47.7, hollow_etan=45.18,
                      wall_hourglass_ihq=4)
    block_impact(cfg, sys.argv[2], vtk=False, quiet=True)
    np.save(sys.argv[1], np.concatenate([f.ravel() for f in forces]))
''')


def _run(tmp_path, name, cache):
    env = {**os.environ, "NUMBA_CACHE_DIR": str(cache), "NUMBA_NUM_THREADS": "1"}
    out = tmp_path / f"{name}.npy"
    subprocess.run([sys.executable, "-c", SCRIPT, str(out), str(tmp_path / name)], env=env,
                   check=True, capture_output=True, timeout=600)
    return np.load(out)


def test_compiled_and_cached_shell_kernels_give_the_same_forces(tmp_path):
    cache = tmp_path / "kernels"
    compiled = _run(tmp_path, "compiled", cache)  # compiles into the empty cache
    cached = _run(tmp_path, "cached", cache)  # loads the kernels compiled above
    assert compiled.size == cached.size > 0
    assert np.count_nonzero(compiled) > 0.1 * compiled.size  # the walls are loaded
    assert np.array_equal(compiled, cached)
