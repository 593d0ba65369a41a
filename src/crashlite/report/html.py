"""HTML pieces of the report: escaping, number formatting, tables and
embedded images. The page carries its CSS and images inline, so the one
file can be sent on."""

from __future__ import annotations

import base64
import html
import math

CSS = """
body { font-family: system-ui, sans-serif; margin: 1.5em 2.5em; color: #222; max-width: 1400px; }
h1 { font-size: 1.5em; } h2 { font-size: 1.2em; border-bottom: 1px solid #bbb; margin-top: 1.8em; }
h3 { font-size: 1.0em; }
table { border-collapse: collapse; margin: 0.5em 0 1em; font-size: 0.85em; }
th, td { border: 1px solid #ccc; padding: 2px 7px; text-align: right; }
th { background: #eef1f6; } td.l, th.l { text-align: left; }
.grid { display: flex; flex-wrap: wrap; gap: 8px; } .grid img { border: 1px solid #ddd; }
.excellent { background: #d8f0d8; } .good { background: #eef6d0; } .fair { background: #fbeccc; }
.poor { background: #f6d4d4; } .note { color: #555; font-size: 0.85em; }
code { background: #f3f3f3; padding: 0 3px; }
"""


def esc(text) -> str:
    return html.escape(str(text))


def num(value, digits: int = 4) -> str:
    """A figure for a table: '–' for None, integers as they are."""
    if value is None:
        return "–"
    if isinstance(value, bool):
        return str(value)
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            return "–"
        return f"{value:.{digits}g}"
    return esc(value)


def pct(value) -> str:
    return "–" if value is None else f"{value:+.2f} %"


def table(header: list[str], rows: list[list], left: int = 1, classes: list[str] | None = None) -> str:
    """An HTML table; the first ``left`` columns left-aligned; cells are
    escaped text unless they are already HTML (wrapped in ``Raw``)."""

    def cell(tag, v, k):
        cls = ' class="l"' if k < left else ""
        return f"<{tag}{cls}>{v if isinstance(v, Raw) else esc(v)}</{tag}>"

    out = ["<table>", "<tr>" + "".join(cell("th", h, k) for k, h in enumerate(header)) + "</tr>"]
    for i, row in enumerate(rows):
        cls = f' class="{classes[i]}"' if classes and classes[i] else ""
        out.append(f"<tr{cls}>" + "".join(cell("td", v, k) for k, v in enumerate(row)) + "</tr>")
    out.append("</table>")
    return "\n".join(out)


class Raw(str):
    """HTML that a table cell takes as it is."""


def image(png: bytes, alt: str) -> str:
    return f'<img alt="{esc(alt)}" src="data:image/png;base64,{base64.b64encode(png).decode("ascii")}"/>'


def page(title: str, body: list[str]) -> str:
    return (
        '<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8"/>'
        f"<title>{esc(title)}</title><style>{CSS}</style></head>\n<body>\n<h1>{esc(title)}</h1>\n"
        + "\n".join(body)
        + "\n</body></html>\n"
    )
