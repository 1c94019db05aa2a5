"""The native OpenRadioss input written for a deck's contacts, and the reading of
OpenRadioss's time history (``th_to_csv`` files).

The starter file is checked card by card in the fixed columns of OpenRadioss's
starter input (/BEGIN, /INCLUDE_LS-DYNA, /SURF/PART, /INTER/TYPE25 in its 2026
format, /TH/INTER, /TH/NODE): each field is read back from its columns, as the
starter reads it. The LS-DYNA meaning of each contact field is checked through
the mapping of docs/engines.md (values exact: they are copied or multiplied by
exact factors, so the tolerance is that of the 10-significant-digit text).
The time-history files are SYNTHETIC, in the layout ``th_to_csv`` writes (its
sources: a quoted header, "<group title> <id> <object title> <variable>" per
column, %e values, the last value of the last row left out); they test the
reader, not the engine. Runs on a real OpenRadioss are in test_real_engines.py.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from hollowbody.engines.commands import radioss_root
from hollowbody.engines.radioss_contact import NATIVE_ID0, TH_INTER_TITLE, TH_NODE_TITLE
from hollowbody.engines.radioss_deck import history_nodes, rewrite_for_openradioss
from hollowbody.engines.radioss_th import MASTER_SIGN, histories, read_th_csv
from hollowbody.errors import DeckError
from hollowbody.io.keyword import Contact, ControlContact, read_deck, write_deck
from hollowbody.scenarios.block import BlockConfig, build_block_deck


def _block(tmp_path: Path, structure: str, **kw) -> Path:
    deck = build_block_deck(BlockConfig(structure=structure, mesh=15.0, end_time=1.0, **kw))
    path = tmp_path / structure / "deck.k"
    path.parent.mkdir(parents=True, exist_ok=True)
    write_deck(deck, path)
    return path


def _cards(text: str, keyword: str) -> list[str]:
    """The lines of the block starting with ``keyword`` (up to the next keyword)."""
    lines = text.splitlines()
    i = next(k for k, line in enumerate(lines) if line.startswith(keyword))
    j = next((k for k in range(i + 1, len(lines)) if lines[k].startswith(("/", "#"))),
             len(lines))
    return lines[i:j]


def _fields(line: str, widths: list[int]) -> list[str]:
    out, pos = [], 0
    for w in widths:
        out.append(line[pos:pos + w].strip())
        pos += w
    return out


def _inter(text: str, iid: int) -> dict[str, float]:
    """The fields of ``/INTER/TYPE25/iid`` read from their columns (2026 format)."""
    c = _cards(text, f"/INTER/TYPE25/{iid}")
    names = [
        (["s1", "s2", "istf", "ithe", "igap", "irem", "_", "idel", "iedge", "ipstif"],
         [10] * 10),
        (["grnd", "_", "gap_scale", "mesh", "gmax_s", "gmax_m"], [10, 10, 20, 20, 20, 20]),
        (["stmin", "stmax", "igap0", "ishape", "edge", "stfac_mdt"], [20, 20, 10, 10, 20, 20]),
        (["stfac", "fric", "tpfit", "tstart", "tstop"], [20] * 5),
        (["ibc", "_", "ivis2", "inacti", "viss", "ithick", "_", "pmax"],
         [10, 10, 10, 10, 20, 10, 10, 20]),
        (["ifric", "ifiltr", "xfreq", "_", "sens", "dtstif", "_", "fric_id"],
         [10, 10, 20, 10, 10, 20, 10, 10]),
    ]
    out: dict[str, float] = {"title": c[1]}
    for line, (keys, widths) in zip(c[2:8], names):
        for k, v in zip(keys, _fields(line, widths)):
            if k != "_" and k != "ibc":
                out[k] = float(v) if v else 0.0
    out["extra"] = c[8:]
    return out


def test_block_decks_become_a_starter_file_including_the_keyword_deck(tmp_path):
    for structure in ("solid", "hollow"):
        deck = _block(tmp_path, structure)
        starter, notes = rewrite_for_openradioss(deck, tmp_path / structure / "or" / "deck.k")
        assert starter.name == "deck_0000.rad" and radioss_root(starter) == "deck"
        text = starter.read_text()
        lines = text.splitlines()
        assert lines[0] == "#RADIOSS STARTER" and lines[-1] == "/END"
        b = _cards(text, "/BEGIN")
        assert b[1] == "deck" and int(b[2]) == 2026
        assert _fields(b[3], [20] * 3) == ["kg", "mm", "ms"] == _fields(b[4], [20] * 3)
        assert _cards(text, "/INCLUDE_LS-DYNA")[1] == "deck.k"
        kw = (starter.parent / "deck.k").read_text()
        assert "*CONTACT" not in kw and "*DATABASE_HISTORY_NODE" not in kw
        # everything else is the deck as it was
        before = [type(i).__name__ for i in read_deck(deck).iter_items()]
        after = [type(i).__name__ for i in read_deck(starter.parent / "deck.k").iter_items()]
        assert sorted(after) == sorted(n for n in before
                                       if n not in ("Contact", "DatabaseHistoryNode"))
        assert any("TYPE25" in n for n in notes)
        # the impactor node's history and the contacts' forces
        th = _cards(text, "/TH/NODE/")
        assert th[1] == TH_NODE_TITLE and th[2].split() == ["DX", "DY", "DZ", "VX", "VY", "VZ"]
        assert [int(x) for x in _fields(th[3], [10, 10])] == [1_000_001, 0]
        ti = _cards(text, "/TH/INTER/")
        assert ti[1] == TH_INTER_TITLE and ti[2].split()[:3] == ["FNX", "FNY", "FNZ"]
        assert sorted(int(x) for x in ti[3].split()) == ([1] if structure == "solid" else [1, 2])


def test_solid_tissue_against_the_rigid_impactor_keeps_the_lsdyna_meaning(tmp_path):
    starter, _ = rewrite_for_openradioss(_block(tmp_path, "solid"), tmp_path / "o" / "deck.k")
    text = starter.read_text()
    c = _inter(text, 1)
    assert c["title"] == "tissue-impactor"
    # slave: the solid block's outer faces; master: the impactor's shells
    s1, s2 = int(c["s1"]), int(c["s2"])
    assert _cards(text, f"/SURF/PART/EXT/{s1}")[2].split() == ["1"]
    assert _cards(text, f"/SURF/PART/{s2}")[2].split() == ["2"]
    assert s1 >= NATIVE_ID0 and s2 >= NATIVE_ID0
    # PENOPT 1: smaller side stiffness x SLSFAC (0.1 default) x min(SFS, SFM) = 1
    assert (c["istf"], c["stfac"]) == (4, pytest.approx(0.1, rel=1e-9))
    # SOFT=1: mass / time-step stiffness, scale SOFSCL / 2 (SOFSCL default 0.1)
    assert (c["ipstif"], c["stfac_mdt"]) == (1, pytest.approx(0.05, rel=1e-9))
    # FS = FD = 0.2, DC = 0: Coulomb 0.2; shell thickness as gap; BT 0, DT 1e20
    assert (c["ifric"], c["fric"]) == (0, pytest.approx(0.2, rel=1e-9))
    assert (c["igap"], c["gap_scale"]) == (2, 1.0)
    assert (c["tstart"], c["tstop"]) == (0.0, pytest.approx(1e20, rel=1e-9))
    assert (c["inacti"], c["idel"], c["viss"]) == (5, 2, 0.0)
    assert c["extra"] == []


def test_hollow_self_contact_is_a_single_surface_of_the_wall_parts(tmp_path):
    starter, _ = rewrite_for_openradioss(_block(tmp_path, "hollow"), tmp_path / "o" / "deck.k")
    text = starter.read_text()
    c = _inter(text, 2)
    assert c["title"] == "hollow self-contact" and c["s2"] == 0
    assert _cards(text, f"/SURF/PART/{int(c['s1'])}")[2].split() == ["11", "12", "13"]
    t = _inter(text, 1)  # tissue-impactor: the part set of the walls against the impactor
    assert _cards(text, f"/SURF/PART/{int(t['s1'])}")[2].split() == ["11", "12", "13"]


def test_friction_decay_thickness_and_slsfac_are_carried(tmp_path):
    path = _block(tmp_path, "solid")
    deck = read_deck(path)
    c = deck.of_type(Contact)[0]
    c.fs, c.fd, c.dc, c.fsf = 0.5, 0.3, 2.0, 2.0
    c.sst, c.mst, c.sfst, c.sfmt, c.sfs, c.sfm = 1.5, 3.0, 1.2, 0.8, 2.0, 3.0
    c.soft, c.vdc = 0, 20.0
    deck.add(ControlContact(slsfac=0.05))
    write_deck(deck, tmp_path / "x.k")
    text = rewrite_for_openradioss(tmp_path / "x.k", tmp_path / "o" / "x.k")[0].read_text()
    r = _inter(text, 1)
    # mu = FD + (FS - FD) exp(-DC v), both scaled by FSF: law 2 with Fric, C5, C6
    assert (r["ifric"], r["fric"]) == (2, pytest.approx(0.6, rel=1e-9))
    c15 = [float(x) for x in _fields(r["extra"][0], [20] * 5)]
    assert c15 == [0.0, 0.0, 0.0, 0.0, pytest.approx(0.4, rel=1e-9)]
    assert float(r["extra"][1]) == pytest.approx(-2.0, rel=1e-9)
    # given thicknesses: Igap 5 and the thickness card; gap scale the mean of SFST, SFMT
    assert r["igap"] == 5 and r["gap_scale"] == pytest.approx(1.0, rel=1e-9)
    assert [float(x) for x in _fields(r["extra"][2], [20] * 4)] == pytest.approx(
        [1.5, 1.2, 3.0, 0.8], rel=1e-9)
    # SLSFAC 0.05 x min(SFS, SFM) = 0.1; SOFT 0: no mass stiffness; VDC 20 % -> 0.2
    assert r["stfac"] == pytest.approx(0.1, rel=1e-9)
    assert (r["ipstif"], r["stfac_mdt"], r["viss"]) == (0, 0.0, pytest.approx(0.2, rel=1e-9))


def test_contacts_not_written_are_refused_naming_file_line_and_keyword(tmp_path):
    path = _block(tmp_path, "solid")
    text = path.read_text().replace("*END", "*CONTACT_TIED_NODES_TO_SURFACE\n"
                                           "         1         2         4         3\n\n\n*END")
    path.write_text(text)
    line = text.splitlines().index("*CONTACT_TIED_NODES_TO_SURFACE") + 1
    with pytest.raises(DeckError) as err:
        rewrite_for_openradioss(path, tmp_path / "o" / "deck.k")
    assert err.value.file == str(path) and err.value.line in (line, line + 1)
    assert err.value.keyword.startswith("CONTACT_TIED_NODES_TO_SURFACE")
    assert "not written for OpenRadioss" in str(err.value)
    # a part set that does not exist
    deck = read_deck(_block(tmp_path / "b", "solid"))
    c = deck.of_type(Contact)[0]
    c.ssid, c.sstyp = 77, 2
    write_deck(deck, tmp_path / "y.k")
    with pytest.raises(DeckError, match="part set 77 is not defined"):
        rewrite_for_openradioss(tmp_path / "y.k", tmp_path / "o2" / "y.k")


def test_history_nodes_of_node_sets_are_expanded(tmp_path):
    from hollowbody.io.keyword import DatabaseHistoryNodeSet, SetNodeList

    deck = build_block_deck(BlockConfig(mesh=15.0, end_time=1.0))
    deck.add(SetNodeList(sid=55, nodes=[3, 1_000_001, 4]))
    deck.add(DatabaseHistoryNodeSet(ids=[55]))
    assert history_nodes(deck) == [1_000_001, 3, 4]


TH_HEADER = ['"time"', '"INTERNAL ENERGY"', '"KINETIC ENERGY"']


def _th_file(path: Path, rows: np.ndarray, columns: list[str]) -> None:
    """A file in th_to_csv's layout (last value of the last row left out, as it does)."""
    flat = [f"{v:e}" for v in rows.reshape(-1)][:-1]
    n = rows.shape[1]
    body = "\n".join(",".join(flat[k:k + n]) for k in range(0, len(flat), n))
    path.write_text(",".join(TH_HEADER + [f'"{c}"' for c in columns]) + "\n" + body)


def test_time_history_becomes_rcforc_and_nodout_rows(tmp_path):
    cols = [f"{TH_INTER_TITLE} 1 tissue-impactor {v} " for v in
            ("FNX", "FNY", "FNZ", "FTX", "FTY", "FTZ")]
    cols += [f"{TH_NODE_TITLE} 1000001 {'':20s} {v} " for v in
             ("DX", "DY", "DZ", "VX", "VY", "VZ")]
    t = np.array([0.0, 0.02, 0.04])
    vals = []
    for k, tk in enumerate(t):
        fn = [0.1 * k, 0.0, 2.0 * k]
        ft = [0.01 * k, -0.02 * k, 0.0]
        node = [0.0, 0.0, -11.1 * tk, 0.0, 0.0, -11.1]
        vals.append([tk, 5.0, 10.0, *fn, *ft, *node])
    path = tmp_path / "deckT01.csv"
    _th_file(path, np.array(vals), cols)
    names, data = read_th_csv(path)
    assert data.shape == (2, 15)  # the short last row is dropped
    h = histories(path)
    rc = np.array(h["rcforc"])
    # master force = FN + FT (x sign); the slave side gets the opposite force
    assert rc[1, :2].tolist() == [0.02, 1.0]
    master = MASTER_SIGN * np.array([0.1 + 0.01, -0.02, 2.0])
    assert rc[1, 5:8] == pytest.approx(master, rel=1e-6)
    assert rc[1, 2:5] == pytest.approx(-master, rel=1e-6)
    nd = np.array(h["nodout"])
    assert nd[1, :2].tolist() == [0.02, 1_000_001]
    assert nd[1, 4] == pytest.approx(-0.222, rel=1e-6) and nd[1, 7] == pytest.approx(-11.1)
    # groups that are absent leave their history out
    _th_file(tmp_path / "e.csv", np.array([[0.0, 1.0, 2.0], [1.0, 1.0, 2.0], [2.0, 0, 0]]), [])
    assert histories(tmp_path / "e.csv") == {}


def test_hourglass_and_contact_energies_interpolated_at_the_listing_times(tmp_path):
    from hollowbody.engines.radioss_th import energies_at

    t = np.array([0.0, 0.1, 0.2, 0.3])
    rows = np.column_stack([t, 1 + t, 2 + t, 10 * t, 20 * t])
    path = tmp_path / "g.csv"
    flat = [f"{v:e}" for v in rows.reshape(-1)][:-1]
    path.write_text('"time","INTERNAL ENERGY","KINETIC ENERGY","CONTACT ENERGY",'
                    '"HOURGLASS ENERGY"\n' + "\n".join(
                        ",".join(flat[k:k + 5]) for k in range(0, len(flat), 5)))
    e = energies_at(path, np.array([0.05, 0.15, 0.5]))
    # linear in time: exact at the midpoints; beyond the history (last row dropped): NaN
    assert e["contact [J]"][:2] == pytest.approx([0.5, 1.5], rel=1e-6)
    assert e["hourglass [J]"][:2] == pytest.approx([1.0, 3.0], rel=1e-6)
    assert np.isnan(e["contact [J]"][2])
