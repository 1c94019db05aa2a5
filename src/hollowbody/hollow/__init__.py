"""Hollow structures: the paper's hollow block (:mod:`.grid`) and the conversion of the
solid soft tissue of any keyword deck into hollow shell structures (:mod:`.convert`;
``hollowbody hollowize``; docs/hollowize.md)."""
