"""Command lines of a run on an external engine (what ``--dry-run`` prints).

OpenRadioss (its INSTALL notes): the starter reads the deck and splits it into
``np`` domains, ``starter -i DECK -np N``; it writes the restart files and, for
a keyword deck, the engine input ``ROOT_0001.rad`` (ROOT: the deck's name
without extension). The engine then runs with ``OMP_NUM_THREADS=T`` threads per
domain: ``engine -i ROOT_0001.rad`` on one domain, ``mpirun -np N
engine_ompi -i ROOT_0001.rad`` on several. After the run ``th_to_csv ROOTT01``
converts the time history and ``anim_to_vtk ROOTAnnn`` each animation state
(written to ``ROOTAnnn.vtk``).

LS-DYNA: SMP ``lsdyna i=DECK ncpu=T memory=M``; MPP ``mpirun -np N lsdyna_mpp
i=DECK memory=M memory2=M2`` (rank 0 reads and decomposes the whole model with
``memory``, every rank then runs its domain with ``memory2``). Memory is in
words (8 bytes in double precision) and is set from the model's size by
:func:`lsdyna_memory` unless given.
"""

from __future__ import annotations

import math
import os
import shlex
from dataclasses import dataclass, field
from pathlib import Path

from hollowbody.engines.discovery import EngineNotFound, LsDynaInstall, OpenRadiossInstall


@dataclass(frozen=True)
class Command:
    """One program to run: ``program`` with ``args`` in folder ``cwd``.

    env: variables set on top of the caller's environment; stdout: file (in
    ``cwd``) the program's output is written to (None: read by the runner);
    step: what the command does (``starter``, ``engine``, ``th_to_csv``, ...);
    each: a glob pattern in ``cwd``: the command runs once per matching file,
    ``{}`` in ``args`` and ``stdout`` standing for its name (converters of the
    files a run wrote).
    """

    step: str
    program: str
    args: tuple[str, ...]
    cwd: Path
    env: dict[str, str] = field(default_factory=dict)
    stdout: str | None = None
    each: str | None = None

    def argv(self, item: str | None = None) -> list[str]:
        """Program and arguments (``{}`` replaced by ``item``)."""
        args = [a.replace("{}", item) for a in self.args] if item is not None else \
            list(self.args)
        return [self.program, *args]

    def describe(self) -> list[str]:
        """The command as the lines ``--dry-run`` prints: the shell line, its folder and
        the environment it sets."""
        line = shlex.join(self.argv())
        if self.stdout:
            line += f" > {shlex.quote(self.stdout)}"
        out = [f"[{self.step}]" + (f" for each {self.each}" if self.each else ""),
               f"  cd {shlex.quote(str(self.cwd))}",
               f"  {line}"]
        out += [f"  env {k}={shlex.quote(v)}" for k, v in sorted(self.env.items())]
        return out


@dataclass(frozen=True)
class RunPlan:
    """The commands of a run, in order, and what they read and write."""

    engine: str
    deck: Path
    workdir: Path
    commands: tuple[Command, ...]
    notes: tuple[str, ...] = ()

    def describe(self) -> str:
        lines = [f"engine: {self.engine}", f"deck: {self.deck}", f"work folder: {self.workdir}"]
        lines += [f"note: {n}" for n in self.notes]
        for c in self.commands:
            lines += c.describe()
        return "\n".join(lines)


def _check_counts(np_: int, threads: int) -> None:
    from hollowbody.errors import UserInputError

    if np_ < 1:
        raise UserInputError(f"--np must be at least 1 (got {np_})")
    if threads < 1:
        raise UserInputError(f"--threads must be at least 1 for an external engine "
                             f"(got {threads})")


def radioss_root(deck: Path) -> str:
    """OpenRadioss's run name of a starter input: ``ROOT`` of a native ``ROOT_0000.rad``,
    a keyword deck's file name without extension."""
    name = Path(deck).name
    if name.endswith("_0000.rad"):
        return name[:-len("_0000.rad")]
    return Path(deck).stem


def openradioss_plan(install: OpenRadiossInstall, deck: Path, workdir: Path, np_: int = 1,
                     threads: int = 1, engine_file: str | None = None) -> RunPlan:
    """Starter, engine and converters of an OpenRadioss run of ``deck`` (a file in
    ``workdir``) on ``np_`` MPI domains of ``threads`` OpenMP threads each.

    engine_file: the engine input (default ``ROOT_0001.rad``, written by the starter
    or by :mod:`hollowbody.engines.radioss_deck`). More than one domain needs the
    MPI engine and ``mpirun`` (:class:`EngineNotFound` otherwise).
    """
    _check_counts(np_, threads)
    root = radioss_root(deck)
    engine_file = engine_file or f"{root}_0001.rad"
    env = dict(install.env)
    env["OMP_NUM_THREADS"] = str(threads)
    starter = Command("starter", str(install.starter), ("-i", deck.name, "-np", str(np_)),
                      workdir, env, stdout=f"{root}_starter.log")
    if np_ == 1:  # the OpenMP engine, else the MPI one started alone (one domain)
        exe = install.engine if install.engine is not None else install.engine_mpi
        engine = Command("engine", str(exe), ("-i", engine_file), workdir, env,
                         stdout=f"{root}_engine.log")
    else:
        if install.engine_mpi is None:
            raise EngineNotFound(f"OpenRadioss at {install.root} has no MPI engine "
                                 f"(engine_{install.arch}_ompi): run with --np 1, or install "
                                 "the MPI build")
        if install.mpirun is None:
            raise EngineNotFound("mpirun (or mpiexec) not found on the PATH: needed for "
                                 f"--np {np_}")
        engine = Command("engine", install.mpirun,
                         ("-np", str(np_), str(install.engine_mpi), "-i", engine_file),
                         workdir, env, stdout=f"{root}_engine.log")
    commands = [starter, engine]
    notes = []
    if install.th_to_csv is not None:
        commands.append(Command("th_to_csv", str(install.th_to_csv), ("{}",), workdir,
                                dict(install.env), each=f"{root}T[0-9][0-9]"))
    else:
        notes.append("th_to_csv not installed: the time history stays binary")
    if install.anim_to_vtk is not None:
        commands.append(Command("anim_to_vtk", str(install.anim_to_vtk), ("{}",), workdir,
                                dict(install.env), stdout="{}.vtk",
                                each=f"{root}A[0-9][0-9][0-9]*"))
    else:
        notes.append("anim_to_vtk not installed: no VTK states")
    return RunPlan("openradioss", deck, workdir, tuple(commands), tuple(notes))


#: Words of memory per node and per element, and the base, of :func:`lsdyna_memory`.
WORDS_PER_NODE = 300
WORDS_PER_ELEMENT = 600
BASE_WORDS = 20_000_000


def lsdyna_memory(nodes: int, elements: int, np_: int = 1) -> tuple[int, int]:
    """(memory, memory2) in words for a model of ``nodes`` nodes and ``elements``
    elements on ``np_`` MPP ranks.

    The rule (hollowbody's, a starting allocation; LS-DYNA grows its memory
    when it can and says so in d3hsp when it cannot): 20 M words + 300 words per
    node + 600 per element for the whole model (``memory``: SMP, and rank 0 of
    MPP which decomposes it), and 20 M words + the whole model's share per rank
    for ``memory2``; both rounded up to whole M words. A 1.5 M-node, 1.3 M-element
    body model: memory 1250 M words (10 GB), memory2 on 16 ranks 97 M words.
    """
    whole = WORDS_PER_NODE * max(nodes, 0) + WORDS_PER_ELEMENT * max(elements, 0)
    mem = BASE_WORDS + whole
    mem2 = BASE_WORDS + whole / max(np_, 1)
    mega = 1_000_000
    return math.ceil(mem / mega) * mega, math.ceil(mem2 / mega) * mega


def words(n: int) -> str:
    """LS-DYNA's notation of a memory size: ``250m`` for 250 M words."""
    return f"{n // 1_000_000}m" if n % 1_000_000 == 0 else str(n)


def lsdyna_plan(install: LsDynaInstall, deck: Path, workdir: Path, np_: int = 1,
                threads: int = 1, memory: tuple[int, int] = (BASE_WORDS, BASE_WORDS)
                ) -> RunPlan:
    """The command of an LS-DYNA run of ``deck`` (a file in ``workdir``).

    SMP executables run ``threads`` threads (``ncpu=``; ``np_`` must be 1); MPP
    ones ``np_`` ranks under ``mpirun`` (``OMP_NUM_THREADS=threads`` for hybrid
    builds). memory: (memory, memory2) words, see :func:`lsdyna_memory`.
    """
    from hollowbody.errors import UserInputError

    _check_counts(np_, threads)
    mem, mem2 = memory
    env = {"OMP_NUM_THREADS": str(threads)}
    if not install.mpp:
        if np_ > 1:
            raise UserInputError(f"{install.executable.name} is an SMP executable: use "
                                 "--threads for its cores, or an MPP executable for --np")
        cmd = Command("lsdyna", str(install.executable),
                      (f"i={deck.name}", f"ncpu={threads}", f"memory={words(mem)}"),
                      workdir, env, stdout="lsdyna.log")
    else:
        if install.mpirun is None:
            raise EngineNotFound("mpirun (or mpiexec) not found on the PATH: needed for an "
                                 "MPP LS-DYNA")
        cmd = Command("lsdyna", install.mpirun,
                      ("-np", str(np_), str(install.executable), f"i={deck.name}",
                       f"memory={words(mem)}", f"memory2={words(mem2)}"),
                      workdir, env, stdout="lsdyna.log")
    return RunPlan("lsdyna", deck, workdir, (cmd,))


def run_env(cmd: Command, base: dict[str, str] | None = None) -> dict[str, str]:
    """The full environment of ``cmd``: the caller's (``base``) with its variables set."""
    env = dict(os.environ if base is None else base)
    env.update(cmd.env)
    return env
