"""Engine discovery and the command lines of a run (no engine is run here).

Discovery is tested on folders laid out as OpenRadioss's release package
(``exec/starter_linux64_gf``, ...) holding empty files marked executable: the
test checks which file names are picked, never runs them.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from hollowbody.engines.commands import (
    BASE_WORDS,
    lsdyna_memory,
    lsdyna_plan,
    openradioss_plan,
    words,
)
from hollowbody.engines.discovery import (
    EngineNotFound,
    LsDynaInstall,
    find_lsdyna,
    find_openradioss,
    is_mpp_name,
    platform_arch,
)
from hollowbody.errors import UserInputError

ARCH = "linux64_gf"


def _touch_exe(p: Path) -> Path:
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text("")
    p.chmod(0o755)
    return p


def _radioss_tree(root: Path, mpi: bool = True, converters: bool = True) -> Path:
    names = [f"starter_{ARCH}", f"engine_{ARCH}"]
    names += [f"engine_{ARCH}_ompi"] if mpi else []
    names += [f"th_to_csv_{ARCH}", f"anim_to_vtk_{ARCH}"] if converters else []
    for n in names:
        _touch_exe(root / "exec" / n)
    (root / "hm_cfg_files").mkdir()
    (root / "extlib" / "hm_reader" / "linux64").mkdir(parents=True)
    return root


def test_platform_names():
    assert platform_arch("Linux", "x86_64") == "linux64_gf"
    assert platform_arch("Linux", "aarch64") == "linuxa64"
    assert platform_arch("Windows", "AMD64") == "win64"


def test_openradioss_found_through_the_variable_root_exec_or_starter(tmp_path):
    root = _radioss_tree(tmp_path / "OpenRadioss")
    env = {"OPENRADIOSS_PATH": str(root), "PATH": ""}
    inst = find_openradioss(env=env, arch=ARCH)
    assert inst.starter == root / "exec" / f"starter_{ARCH}"
    assert inst.engine == root / "exec" / f"engine_{ARCH}"
    assert inst.engine_mpi == root / "exec" / f"engine_{ARCH}_ompi"
    assert inst.th_to_csv.name == f"th_to_csv_{ARCH}"
    assert inst.env["RAD_CFG_PATH"] == str(root / "hm_cfg_files")
    assert inst.env["OMP_STACKSIZE"] == "400m"
    assert str(root / "extlib" / "hm_reader" / "linux64") in inst.env["LD_LIBRARY_PATH"]
    for given in (root, root / "exec", root / "exec" / f"starter_{ARCH}"):
        assert find_openradioss(given, env={"PATH": ""}, arch=ARCH).root == root
    # on the PATH
    env = {"PATH": str(root / "exec")}
    assert find_openradioss(env=env, arch=ARCH).root == root
    # single precision executables
    _touch_exe(root / "exec" / f"starter_{ARCH}_sp")
    _touch_exe(root / "exec" / f"engine_{ARCH}_sp")
    sp = find_openradioss(root, env={"PATH": ""}, precision="sp", arch=ARCH)
    assert sp.starter.name == f"starter_{ARCH}_sp" and sp.engine_mpi is None


def test_openradioss_not_found_names_where_it_looked(tmp_path):
    with pytest.raises(EngineNotFound, match="OPENRADIOSS_PATH"):
        find_openradioss(env={"PATH": str(tmp_path)}, arch=ARCH)
    (tmp_path / "exec").mkdir()
    _touch_exe(tmp_path / "exec" / f"starter_{ARCH}")
    with pytest.raises(EngineNotFound, match=f"engine_{ARCH}"):
        find_openradioss(tmp_path, env={"PATH": ""}, arch=ARCH)
    assert issubclass(EngineNotFound, UserInputError)


def test_openradioss_command_lines(tmp_path):
    root = _radioss_tree(tmp_path / "or")
    inst = find_openradioss(root, env={"PATH": "", "OMP_STACKSIZE": "1g"}, arch=ARCH)
    work = tmp_path / "run"
    plan = openradioss_plan(inst, work / "block.k", work, np_=1, threads=3)
    starter, engine, th, anim = plan.commands
    assert starter.argv() == [str(inst.starter), "-i", "block.k", "-np", "1"]
    assert engine.argv() == [str(inst.engine), "-i", "block_0001.rad"]
    assert engine.env["OMP_NUM_THREADS"] == "3" and engine.env["OMP_STACKSIZE"] == "1g"
    assert starter.cwd == work and engine.cwd == work
    assert th.each == "blockT[0-9][0-9]" and th.argv("blockT01") == [str(inst.th_to_csv),
                                                                      "blockT01"]
    assert anim.stdout == "{}.vtk"
    # several domains: the MPI engine under mpirun
    inst = type(inst)(**{**inst.__dict__, "mpirun": "/usr/bin/mpirun"})
    plan = openradioss_plan(inst, work / "block.k", work, np_=4, threads=2)
    assert plan.commands[0].argv()[-2:] == ["-np", "4"]
    assert plan.commands[1].argv() == ["/usr/bin/mpirun", "-np", "4", str(inst.engine_mpi),
                                       "-i", "block_0001.rad"]
    text = plan.describe()
    assert "mpirun -np 4" in text and "env OMP_NUM_THREADS=2" in text and f"cd {work}" in text


def test_openradioss_without_mpi_refuses_several_domains(tmp_path):
    inst = find_openradioss(_radioss_tree(tmp_path / "or", mpi=False), env={"PATH": ""},
                            arch=ARCH)
    with pytest.raises(EngineNotFound, match="no MPI engine"):
        openradioss_plan(inst, tmp_path / "b.k", tmp_path, np_=2)
    with pytest.raises(UserInputError, match="--np"):
        openradioss_plan(inst, tmp_path / "b.k", tmp_path, np_=0)


def test_lsdyna_found_smp_or_mpp(tmp_path):
    smp = _touch_exe(tmp_path / "ls-dyna_smp_d_R13")
    mpp = _touch_exe(tmp_path / "ls-dyna_mpp_d_R13_openmpi")
    assert find_lsdyna(env={"LSDYNA": str(smp), "PATH": ""}).mpp is False
    assert find_lsdyna(mpp, env={"PATH": ""}).mpp is True
    assert is_mpp_name("mppdyna_d") and not is_mpp_name("lsdyna")
    with pytest.raises(EngineNotFound, match="LSDYNA"):
        find_lsdyna(env={"PATH": str(tmp_path / "none")})
    with pytest.raises(EngineNotFound, match="not an executable"):
        find_lsdyna(tmp_path / "missing", env={"PATH": ""})


def test_lsdyna_command_lines(tmp_path):
    work = tmp_path
    smp = LsDynaInstall(Path("/opt/lsdyna/lsdyna_smp"), mpp=False)
    cmd, = lsdyna_plan(smp, work / "deck.k", work, 1, 4, (250_000_000, 250_000_000)).commands
    assert cmd.argv() == ["/opt/lsdyna/lsdyna_smp", "i=deck.k", "ncpu=4", "memory=250m"]
    with pytest.raises(UserInputError, match="SMP"):
        lsdyna_plan(smp, work / "deck.k", work, 2, 1)
    mpp = LsDynaInstall(Path("/opt/lsdyna/lsdyna_mpp"), mpp=True, mpirun="/usr/bin/mpirun")
    cmd, = lsdyna_plan(mpp, work / "deck.k", work, 8, 1, (400_000_000, 60_000_000)).commands
    assert cmd.argv() == ["/usr/bin/mpirun", "-np", "8", "/opt/lsdyna/lsdyna_mpp", "i=deck.k",
                          "memory=400m", "memory2=60m"]
    no_mpi = LsDynaInstall(Path("/opt/lsdyna/lsdyna_mpp"), mpp=True, mpirun=None)
    with pytest.raises(EngineNotFound, match="mpirun"):
        lsdyna_plan(no_mpi, work / "deck.k", work, 2, 1)


def test_lsdyna_memory_rule():
    # 20 M words + 300 per node + 600 per element, memory2 = 20 M + the share per rank
    assert lsdyna_memory(0, 0) == (BASE_WORDS, BASE_WORDS)
    mem, mem2 = lsdyna_memory(1_500_000, 1_300_000, 16)
    assert mem == 20_000_000 + 450_000_000 + 780_000_000
    assert mem2 == 20_000_000 + 77_000_000  # 1230e6 / 16 = 76.875e6, rounded up
    assert lsdyna_memory(10, 10) == (21_000_000, 21_000_000)  # rounded up to whole M words
    assert words(250_000_000) == "250m" and words(1234) == "1234"


def test_environment_is_added_to_the_callers(tmp_path):
    from hollowbody.engines.commands import run_env

    inst = find_openradioss(_radioss_tree(tmp_path / "or"), env={"PATH": ""}, arch=ARCH)
    cmd = openradioss_plan(inst, tmp_path / "b.k", tmp_path).commands[1]
    env = run_env(cmd, {"HOME": "/home/u", "OMP_NUM_THREADS": "8"})
    assert env["HOME"] == "/home/u" and env["OMP_NUM_THREADS"] == "1"
    assert os.pathsep not in env["RAD_CFG_PATH"]


def test_a_source_build_of_the_mpi_engine_only_runs_one_domain_on_it(tmp_path):
    """A build of OpenRadioss's sources with the open reader and the MPI engine only:
    the open reader's library is in exec/ (on the library path), and --np 1 starts
    the MPI engine alone (one domain) instead of the missing OpenMP-only engine."""
    from hollowbody.engines.commands import openradioss_plan

    root = tmp_path / "src"
    for n in (f"starter_{ARCH}", f"engine_{ARCH}_ompi"):
        _touch_exe(root / "exec" / n)
    (root / "exec" / "libopen_reader_linux64.so").write_text("")
    inst = find_openradioss(root, env={"PATH": ""}, arch=ARCH)
    assert inst.engine is None and inst.engine_mpi == root / "exec" / f"engine_{ARCH}_ompi"
    assert inst.env["LD_LIBRARY_PATH"].split(":")[0] == str(root / "exec")
    plan = openradioss_plan(inst, tmp_path / "d_0000.rad", tmp_path, 1, 1)
    eng = next(c for c in plan.commands if c.step == "engine")
    assert eng.argv() == [str(inst.engine_mpi), "-i", "d_0001.rad"]
    # without any engine it is not found
    (root / "exec" / f"engine_{ARCH}_ompi").unlink()
    with pytest.raises(EngineNotFound, match=f"engine_{ARCH}"):
        find_openradioss(root, env={"PATH": ""}, arch=ARCH)
