"""The converted deck: re-reads, passes check, keeps everything else, respects includes."""

from __future__ import annotations

import hashlib
import warnings

import numpy as np
import pytest

import hollowbody.cli.main as cli_main
from hollowbody.build import build_model
from hollowbody.hollow.convert import HollowOptions, Selection, hollowize
from hollowbody.hollow.output import write_converted
from hollowbody.io.keyword import (
    Contact,
    MassElements,
    Material,
    Nodes,
    Part,
    RawKeyword,
    SectionShell,
    SectionSolid,
    ShellElements,
    SolidElements,
    TiedContact,
    read_deck,
)
from hollowbody.model.mass import lumped_node_mass
from hollowbody.testing.decks import write_multipart_deck


def _read(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return read_deck(path)


def _digest(folder):
    return {p.relative_to(folder): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*.k"))}


@pytest.fixture(scope="module")
def converted(tmp_path_factory):
    root = tmp_path_factory.mktemp("multipart")
    main = write_multipart_deck(root / "in")
    before = _digest(root / "in")
    deck = _read(main)
    new, report = hollowize(deck, Selection(parts=[1]), HollowOptions())
    files = write_converted(new, root / "out" / "new.k", report.changed_decks)
    return {"root": root, "main": main, "deck": deck, "new": new, "report": report,
            "files": files, "before": before}


def test_only_the_converted_parts_include_is_rewritten(converted):
    root = converted["root"]
    names = sorted(p.name for p in converted["files"])
    assert names == ["muscle_hollow.k", "new.k"]
    assert _digest(root / "in") == converted["before"]  # input files untouched
    text = (root / "out" / "new.k").read_text()
    for inc in ("muscle_hollow.k", "../in/mesh/organ.k", "../in/mesh/skin.k", "../in/props.k"):
        assert f"\n{inc}\n" in text
    assert "mesh/muscle.k" not in text


def test_converted_deck_rereads_and_checks(converted, capsys, monkeypatch):
    out = converted["root"] / "out" / "new.k"
    deck = _read(out)
    model = build_model(deck)
    assert 1 not in {g.pid for g in model.solid_groups}
    assert 1 in {g.pid for g in model.shell_groups}
    if "hollowize" not in cli_main.SUBCOMMANDS:
        monkeypatch.setattr(cli_main, "SUBCOMMANDS", cli_main.SUBCOMMANDS + ("hollowize",))
    assert cli_main.main(["check", str(out)]) == 0
    # total mass of the model kept
    m0 = build_model(converted["deck"])
    assert lumped_node_mass(model)[0].sum() == pytest.approx(lumped_node_mass(m0)[0].sum(),
                                                            rel=1e-5)
    # the new keywords are there: tied contact, self-contact, section, material
    assert not [r.keyword for r in deck.of_type(RawKeyword) if r.unsupported]
    tie = deck.of_type(TiedContact)
    assert [(t.type, t.sstyp, t.mstyp) for t in tie] == [("TIED_SHELL_EDGE_TO_SURFACE", 4, 0)]
    assert model.tied_contacts[0].kind == "shell_edge_to_surface"
    assert any(c.type == "AUTOMATIC_SINGLE_SURFACE" and c.ssid == 1 for c in
               deck.of_type(Contact))


def test_untouched_parts_are_identical(converted):
    m0 = build_model(converted["deck"])
    m1 = build_model(_read(converted["root"] / "out" / "new.k"))
    for pid in (2, 3):
        g0 = next(g for g in m0.solid_groups + m0.shell_groups if g.pid == pid)
        g1 = next(g for g in m1.solid_groups + m1.shell_groups if g.pid == pid)
        assert np.array_equal(g0.elem_ids, g1.elem_ids)
        assert np.array_equal(m0.node_ids[g0.conn], m1.node_ids[g1.conn])
        assert np.array_equal(m0.node_x0[g0.conn], m1.node_x0[g1.conn])
        assert m0.materials[m0.parts[pid].mid].params == m1.materials[m1.parts[pid].mid].params
        assert m0.parts[pid].secid == m1.parts[pid].secid
    assert m0.node_sets[1].size == m1.node_sets[1].size
    assert np.array_equal(m0.node_ids[m0.node_sets[1]], m1.node_ids[m1.node_sets[1]])


def test_new_ids_above_the_maxima_and_input_deck_unchanged(converted):
    deck, new = converted["deck"], converted["new"]
    old_items = list(deck.iter_items())
    new_items = list(new.iter_items())
    max_node = max(int(n.ids.max()) for n in deck.of_type(Nodes))
    max_elem = max(int(e.ids.max()) for e in deck.of_type(SolidElements)
                   + deck.of_type(ShellElements))
    old_nodes = np.concatenate([n.ids for n in deck.of_type(Nodes)])
    new_nodes = np.setdiff1d(np.concatenate([n.ids for n in new.of_type(Nodes)]), old_nodes)
    assert new_nodes.size and new_nodes.min() > max_node
    old_elems = np.concatenate([e.ids for e in deck.of_type(SolidElements)
                                + deck.of_type(ShellElements)])
    added = [it for it in new_items if not any(it is o for o in old_items)]
    for it in added:
        if isinstance(it, (ShellElements, MassElements)):
            assert not np.isin(it.ids, old_elems).any() and it.ids.min() > max_elem
        elif isinstance(it, SectionShell):
            assert it.secid > max(s.secid for s in deck.of_type(SectionSolid)
                                  + deck.of_type(SectionShell))
        elif isinstance(it, Material):
            assert it.mid > max(m.mid for m in deck.of_type(Material))
    part = next(p for p in new.of_type(Part) if p.pid == 1)
    assert part.secid != 1 and part.mid != 1
    assert next(p for p in deck.of_type(Part) if p.pid == 1).secid == 1  # input untouched
    assert deck == _read(converted["main"])


def test_two_parts_converted_share_their_interface(tmp_path):
    main = write_multipart_deck(tmp_path / "in")
    deck = _read(main)
    new, report = hollowize(deck, Selection(parts=[1, 2]), HollowOptions(cell=20.0))
    assert [p.pid for p in report.parts] == [1, 2]
    assert all(p.ok for p in report.parts)
    files = write_converted(new, tmp_path / "out" / "two.k", report.changed_decks)
    # part 2's *PART card lives in props.k: that file changes too
    assert sorted(p.name for p in files) == ["muscle_hollow.k", "organ_hollow.k", "props_hollow.k",
                                            "two.k"]
    m0 = build_model(deck)
    m = build_model(_read(tmp_path / "out" / "two.k"))
    assert not m.solid_groups
    s1, s2 = (set(m.node_ids[np.unique(g.conn)]) for g in m.shell_groups if g.pid in (1, 2))
    interface = m0.node_ids[np.abs(m0.node_x0[:, 2] - 30.0) < 1e-9]
    assert interface.size == 49 and set(interface) <= s1 & s2


def test_writer_refuses_to_overwrite_an_input(converted):
    from hollowbody.errors import UserInputError

    with pytest.raises(UserInputError, match="input"):
        write_converted(converted["new"], converted["main"], converted["report"].changed_decks)


def test_include_path_folders_follow_the_new_location(tmp_path):
    from hollowbody.io.keyword import Deck, write_deck
    from hollowbody.testing.decks import box_deck

    (tmp_path / "in" / "lib").mkdir(parents=True)
    write_deck(box_deck((60.0, 60.0, 60.0), 10.0), tmp_path / "in" / "lib" / "box.k")
    organ = Deck()
    write_deck(organ, tmp_path / "in" / "lib" / "other.k")
    (tmp_path / "in" / "main.k").write_text("*KEYWORD\n*INCLUDE_PATH\nlib\n*INCLUDE\nbox.k\n"
                                            "*INCLUDE\nother.k\n*END\n")
    deck = _read(tmp_path / "in" / "main.k")
    new, report = hollowize(deck, Selection(parts=[1]), HollowOptions())
    files = write_converted(new, tmp_path / "out" / "n.k", report.changed_decks)
    assert sorted(p.name for p in files) == ["box_hollow.k", "n.k"]
    text = (tmp_path / "out" / "n.k").read_text()
    assert "*INCLUDE_PATH\n../in/lib\n" in text and "\n../in/lib/other.k\n" in text
    assert build_model(_read(tmp_path / "out" / "n.k")).shell_groups


def test_wall_hourglass_option_gives_the_walls_their_own_control(tmp_path):
    """--wall-hourglass 4: the converted parts point to a new *HOURGLASS (IHQ 4, QM 0.1,
    an id above the deck's), written and read back; by default they carry none (HGID 0).
    A bad IHQ is refused with the option's name."""
    from hollowbody.errors import UserInputError

    main = write_multipart_deck(tmp_path / "in")
    deck = _read(main)
    new, report = hollowize(deck, Selection(parts=[1, 2]),
                            HollowOptions(cell=20.0, wall_hourglass_ihq=4))
    write_converted(new, tmp_path / "out" / "hg.k", report.changed_decks)
    m = build_model(_read(tmp_path / "out" / "hg.k"))
    hgids = {m.parts[p].hgid for p in (1, 2)}
    assert all(h > 1000 for h in hgids) and len(hgids) == 2
    for p in (1, 2):
        hg = m.hourglass_of(p)
        assert hg.ihq == 4 and hg.qm == pytest.approx(0.1)
    plain, plain_report = hollowize(deck, Selection(parts=[1]), HollowOptions(cell=20.0))
    write_converted(plain, tmp_path / "out" / "plain.k", plain_report.changed_decks)
    assert build_model(_read(tmp_path / "out" / "plain.k")).parts[1].hgid == 0
    with pytest.raises(UserInputError, match="--wall-hourglass"):
        HollowOptions(wall_hourglass_ihq=9).validate()
