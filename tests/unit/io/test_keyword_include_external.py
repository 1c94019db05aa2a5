"""An external *INCLUDE (someone else's file) is referred to, never rewritten; long include
names are continued with `` +`` and read back whole."""

from __future__ import annotations

import numpy as np

from hollowbody.io.keyword import Deck, Include, Nodes, read_deck, write_deck


def _user_file(folder) -> tuple:  # noqa: ANN001
    folder.mkdir(parents=True)
    path = folder / "model.k"
    # hand-written, so that any rewrite (spacing, header) would change the bytes
    path.write_text("*KEYWORD\n*NODE\n1,0.0,0.0,0.0\n2,1.0,0.0,0.0\n*END\n")
    return path, path.read_bytes()


def test_external_include_is_not_written(tmp_path) -> None:
    user, before = _user_file(tmp_path / "user")
    main = Deck()
    main.add(Include(filename=str(user), deck=read_deck(user), external=True))
    main.add_include("extra.k", Deck()).deck.add_nodes(np.array([3]), np.array([[2.0, 0, 0]]))
    written = write_deck(main, tmp_path / "run" / "main.k", flatten=False)
    assert [p.name for p in written] == ["main.k", "extra.k"]
    assert user.read_bytes() == before
    back = read_deck(tmp_path / "run" / "main.k")
    ids = np.concatenate([n.ids for n in back.of_type(Nodes)])
    assert ids.tolist() == [1, 2, 3]


def test_long_include_name_is_continued_and_read_back(tmp_path) -> None:
    folder = tmp_path
    for k in range(6):  # a folder name longer than one 80-column line
        folder = folder / f"a_rather_long_folder_name_number_{k}"
    user, before = _user_file(folder)
    assert len(str(user)) > 160
    main = Deck()
    main.add(Include(filename=str(user), deck=read_deck(user), external=True))
    lines = main.items[0].to_lines()
    assert all(len(t) <= 80 for t in lines) and len(lines) >= 4
    assert all(t.endswith(" +") for t in lines[1:-1])
    write_deck(main, tmp_path / "main.k", flatten=False)
    back = read_deck(tmp_path / "main.k")
    assert back.items[0].filename == str(user)
    assert np.concatenate([n.ids for n in back.of_type(Nodes)]).tolist() == [1, 2]
    assert user.read_bytes() == before
