"""A folder's index page: Markdown, and the same page as self-contained HTML.

:func:`markdown_to_html` understands the small Markdown subset the reports
write: ``#`` headings, pipe tables, images ``![alt](src)``, links
``[text](href)``, inline code, ``- `` lists and paragraphs.
"""

from __future__ import annotations

import html
import re
from pathlib import Path

_IMG = re.compile(r"!\[([^\]]*)\]\(([^)]+)\)")
_LINK = re.compile(r"\[([^\]]+)\]\(([^)]+)\)")
_CODE = re.compile(r"`([^`]+)`")
_BOLD = re.compile(r"\*\*([^*]+)\*\*")

STYLE = ("body{font-family:sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;"
         "line-height:1.4}table{border-collapse:collapse;margin:1em 0;font-size:0.9em}"
         "td,th{border:1px solid #bbb;padding:3px 7px;text-align:left}"
         "th{background:#eee}img{max-width:100%;border:1px solid #ddd;margin:0.5em 0}"
         "code{background:#f4f4f4;padding:0 3px}")


def _inline(text: str) -> str:
    out = html.escape(text, quote=False)
    out = _IMG.sub(lambda m: f'<img alt="{m.group(1)}" src="{m.group(2)}">', out)
    out = _LINK.sub(lambda m: f'<a href="{m.group(2)}">{m.group(1)}</a>', out)
    out = _CODE.sub(lambda m: f"<code>{m.group(1)}</code>", out)
    out = _BOLD.sub(lambda m: f"<b>{m.group(1)}</b>", out)
    return out.replace("\\*", "*")


def _cells(line: str) -> list[str]:
    return [c.strip() for c in line.strip().strip("|").split("|")]


def markdown_to_html(text: str, title: str = "") -> str:
    """A complete HTML page of ``text`` (the subset in the module docstring)."""
    body: list[str] = []
    lines = text.splitlines()
    i = 0
    para: list[str] = []

    def flush() -> None:
        if para:
            body.append("<p>" + " ".join(_inline(p) for p in para) + "</p>")
            para.clear()

    while i < len(lines):
        line = lines[i]
        s = line.strip()
        if not s:
            flush()
        elif s.startswith("#"):
            flush()
            level = min(len(s) - len(s.lstrip("#")), 6)
            body.append(f"<h{level}>{_inline(s[level:].strip())}</h{level}>")
        elif s.startswith("|"):
            flush()
            rows = []
            while i < len(lines) and lines[i].strip().startswith("|"):
                rows.append(_cells(lines[i]))
                i += 1
            head, rest = rows[0], [r for r in rows[1:] if not all(set(c) <= set("-: ")
                                                                  for c in r)]
            body.append("<table><tr>" + "".join(f"<th>{_inline(c)}</th>" for c in head)
                        + "</tr>" + "".join("<tr>" + "".join(f"<td>{_inline(c)}</td>"
                                                              for c in r) + "</tr>"
                                             for r in rest) + "</table>")
            continue
        elif s.startswith("- "):
            flush()
            items = []
            while i < len(lines) and lines[i].strip().startswith("- "):
                items.append(f"<li>{_inline(lines[i].strip()[2:])}</li>")
                i += 1
            body.append("<ul>" + "".join(items) + "</ul>")
            continue
        else:
            para.append(s)
        i += 1
    flush()
    return (f"<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>"
            f"{html.escape(title)}</title><style>{STYLE}</style></head><body>\n"
            + "\n".join(body) + "\n</body></html>\n")


def write_index(markdown: str, out_dir: str | Path, title: str) -> tuple[Path, Path]:
    """Write ``index.md`` and ``index.html`` into ``out_dir``."""
    out = Path(out_dir)
    md, page = out / "index.md", out / "index.html"
    md.write_text(markdown)
    page.write_text(markdown_to_html(markdown, title))
    return md, page
