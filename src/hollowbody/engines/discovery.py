"""Find an installed OpenRadioss or LS-DYNA.

OpenRadioss (release package or a build of its public sources) is a folder
(``OPENRADIOSS_PATH``) whose ``exec/`` holds, for the platform ``ARCH``
(``linux64_gf``, ``linuxa64``, ``win64``):

- ``starter_ARCH`` the starter (reads and checks the deck, splits it into domains);
- ``engine_ARCH`` the engine for one domain (OpenMP threads only);
- ``engine_ARCH_ompi`` (``_impi`` on Windows) the engine for MPI + OpenMP runs;
- ``th_to_csv_ARCH`` and ``anim_to_vtk_ARCH`` the converters of its time-history
  and animation files;

each with an ``_sp`` variant (extended single precision). The folder is taken
from the path given (``--engine-path``: the root, its ``exec`` folder or the
starter itself), else from ``OPENRADIOSS_PATH``, else from the starter found on
the PATH. LS-DYNA is one executable (its name says SMP or MPP, e.g.
``ls-dyna_mpp_d_R13...``): the path given, else ``LSDYNA``, else ``lsdyna`` /
``ls-dyna`` on the PATH. ``mpirun`` (or ``mpiexec``) comes from the PATH and is
needed only for runs on more than one MPI rank.

A missing engine is an :class:`EngineNotFound` (a UserInputError: one line,
exit code 2) saying where it was looked for.
"""

from __future__ import annotations

import os
import platform
import shutil
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

from hollowbody.errors import UserInputError

#: Environment variables naming the engines.
OPENRADIOSS_ENV = "OPENRADIOSS_PATH"
LSDYNA_ENV = "LSDYNA"


class EngineNotFound(UserInputError):
    """The engine asked for is not installed where hollowbody looked (exit code 2)."""


def platform_arch(system: str | None = None, machine: str | None = None) -> str:
    """OpenRadioss's name of this platform: ``linux64_gf``, ``linuxa64`` or ``win64``."""
    system = system or platform.system()
    machine = (machine or platform.machine()).lower()
    if system == "Windows":
        return "win64"
    if machine in ("aarch64", "arm64"):
        return "linuxa64"
    return "linux64_gf"


def _exe(arch: str) -> str:
    return ".exe" if arch == "win64" else ""


def _mpi_suffix(arch: str) -> str:
    return "_impi" if arch == "win64" else "_ompi"


def _executable(path: Path) -> bool:
    return path.is_file() and os.access(path, os.X_OK)


def find_mpirun(env: Mapping[str, str] | None = None) -> str | None:
    """``mpirun`` (else ``mpiexec``) on the PATH of ``env``, or None."""
    search = (env if env is not None else os.environ).get("PATH")
    for name in ("mpirun", "mpiexec"):
        found = shutil.which(name, path=search)
        if found:
            return found
    return None


@dataclass(frozen=True)
class OpenRadiossInstall:
    """An OpenRadioss installation: its root folder and executables.

    engine, engine_mpi, th_to_csv, anim_to_vtk: None when the installation lacks
    them (an OpenMP-only build has no MPI engine, an MPI-only source build no
    OpenMP-only engine: one domain then runs on the MPI engine); env: variables the
    executables
    need (``RAD_CFG_PATH``, ``OMP_STACKSIZE``, library path), set on top of the
    caller's environment.
    """

    root: Path
    arch: str
    starter: Path
    engine: Path | None
    engine_mpi: Path | None = None
    th_to_csv: Path | None = None
    anim_to_vtk: Path | None = None
    mpirun: str | None = None
    env: dict[str, str] = field(default_factory=dict)


def _radioss_root(path: Path) -> Path:
    """The installation root from the path given: the root, its exec folder or a
    file in exec (the starter)."""
    if path.is_file():
        path = path.parent
    if path.name == "exec" and not (path / "exec").is_dir():
        return path.parent
    return path


def _radioss_env(root: Path, arch: str, base: Mapping[str, str]) -> dict[str, str]:
    """Variables OpenRadioss's executables read (its INSTALL notes): the folder of the
    input configuration files, the OpenMP stack size, and the shared libraries of a
    release package (``lib``) or a source build (``extlib/hm_reader``, ``extlib/h3d``,
    and ``exec`` where the open reader's library is built)."""
    plat = "win64" if arch == "win64" else ("linuxa64" if arch == "linuxa64" else "linux64")
    env = {OPENRADIOSS_ENV: str(root), "OMP_STACKSIZE": base.get("OMP_STACKSIZE", "400m")}
    if (root / "hm_cfg_files").is_dir():
        env["RAD_CFG_PATH"] = str(root / "hm_cfg_files")
    h3d = root / "extlib" / "h3d" / "lib" / plat
    if h3d.is_dir():
        env["RAD_H3D_PATH"] = str(h3d)
    libs = [p for p in (root / "lib", root / "extlib" / "hm_reader" / plat, h3d) if p.is_dir()]
    if any((root / "exec").glob("libopen_reader*")):  # a source build with the open reader
        libs.insert(0, root / "exec")
    if libs and arch != "win64":
        old = base.get("LD_LIBRARY_PATH", "")
        env["LD_LIBRARY_PATH"] = os.pathsep.join([*map(str, libs), *([old] if old else [])])
    return env


def find_openradioss(path: str | Path | None = None, env: Mapping[str, str] | None = None,
                     precision: str = "dp", arch: str | None = None) -> OpenRadiossInstall:
    """The OpenRadioss installation at ``path``, ``$OPENRADIOSS_PATH`` or on the PATH.

    precision: ``"dp"`` (double) or ``"sp"`` (the ``_sp`` executables). Raises
    :class:`EngineNotFound` naming where it looked when the starter or the
    engine is missing.
    """
    env = dict(os.environ if env is None else env)
    arch = arch or platform_arch()
    sp = "_sp" if precision == "sp" else ""
    ext = _exe(arch)
    starter_name = f"starter_{arch}{sp}{ext}"
    looked: list[str] = []
    root: Path | None = None
    if path is not None:
        root = _radioss_root(Path(path).expanduser())
        looked.append(f"--engine-path {path}")
    elif env.get(OPENRADIOSS_ENV):
        root = _radioss_root(Path(env[OPENRADIOSS_ENV]).expanduser())
        looked.append(f"{OPENRADIOSS_ENV}={env[OPENRADIOSS_ENV]}")
    else:
        found = shutil.which(starter_name, path=env.get("PATH"))
        looked.append(f"{starter_name} on the PATH")
        if found:
            root = _radioss_root(Path(found).resolve())
    if root is None:
        raise EngineNotFound(
            f"OpenRadioss not found ({'; '.join(looked)}): install it and set "
            f"{OPENRADIOSS_ENV} to its folder (the one holding exec/), or give --engine-path")
    exec_dir = root / "exec" if (root / "exec").is_dir() else root

    def pick(name: str) -> Path | None:
        p = exec_dir / name
        return p if _executable(p) else None

    starter = pick(starter_name)
    engine = pick(f"engine_{arch}{sp}{ext}")
    engine_mpi = pick(f"engine_{arch}{_mpi_suffix(arch)}{sp}{ext}")
    missing = [n for n, p in ((starter_name, starter),
                              (f"engine_{arch}{sp}{ext}", engine or engine_mpi)) if p is None]
    if missing:
        raise EngineNotFound(f"OpenRadioss at {root} ({'; '.join(looked)}) has no "
                             f"{' nor '.join(missing)} in {exec_dir}")
    return OpenRadiossInstall(
        root=root, arch=arch, starter=starter, engine=engine,
        engine_mpi=engine_mpi,
        th_to_csv=pick(f"th_to_csv_{arch}{ext}"), anim_to_vtk=pick(f"anim_to_vtk_{arch}{ext}"),
        mpirun=find_mpirun(env), env=_radioss_env(root, arch, env))


@dataclass(frozen=True)
class LsDynaInstall:
    """An LS-DYNA executable; ``mpp``: built for MPI (from its name, or as told)."""

    executable: Path
    mpp: bool
    mpirun: str | None = None


def is_mpp_name(name: str) -> bool:
    """Whether an LS-DYNA executable's name says MPP (``ls-dyna_mpp_d_...``, ``mppdyna``)."""
    return "mpp" in name.lower()


def find_lsdyna(path: str | Path | None = None, env: Mapping[str, str] | None = None,
                mpp: bool | None = None) -> LsDynaInstall:
    """The LS-DYNA executable at ``path``, ``$LSDYNA`` or on the PATH (``lsdyna``,
    ``ls-dyna``). mpp: None guesses SMP/MPP from the name. Raises
    :class:`EngineNotFound` naming where it looked."""
    env = dict(os.environ if env is None else env)
    if path is not None:
        cand, looked = Path(path).expanduser(), f"--engine-path {path}"
    elif env.get(LSDYNA_ENV):
        cand, looked = Path(env[LSDYNA_ENV]).expanduser(), f"{LSDYNA_ENV}={env[LSDYNA_ENV]}"
    else:
        found = next((f for f in (shutil.which(n, path=env.get("PATH"))
                                  for n in ("lsdyna", "ls-dyna")) if f), None)
        looked = "lsdyna / ls-dyna on the PATH"
        if found is None:
            raise EngineNotFound(f"LS-DYNA not found ({looked}): set {LSDYNA_ENV} to its "
                                 "executable, or give --engine-path")
        cand = Path(found)
    if not _executable(cand):
        raise EngineNotFound(f"LS-DYNA not found ({looked}): {cand} is not an executable "
                             "file")
    return LsDynaInstall(executable=cand, mpp=is_mpp_name(cand.name) if mpp is None else mpp,
                         mpirun=find_mpirun(env))
