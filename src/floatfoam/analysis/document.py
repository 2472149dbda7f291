"""A tiny document model rendered both as Markdown and as self-contained HTML.

The report is built once as a list of blocks (headings, paragraphs, lists, tables, images) and
written twice, so ``index.md`` and ``index.html`` always say the same thing. The HTML has its
style inline and no scripts; images are PNG files next to it, referenced by relative paths.
"""

from __future__ import annotations

import html

_STYLE = """
body { font-family: system-ui, sans-serif; max-width: 1200px; margin: 2em auto; padding: 0 1em;
       color: #222; line-height: 1.4; }
table { border-collapse: collapse; margin: 0.8em 0; font-size: 0.9em; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.6em; text-align: left;
         vertical-align: top; }
th { background: #f0f0f0; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
img { max-width: 100%; border: 1px solid #ddd; margin: 0.5em 0; }
h2 { border-bottom: 2px solid #ddd; padding-bottom: 0.2em; margin-top: 2em; }
.note { color: #555; font-size: 0.9em; }
"""


def _is_number(text: str) -> bool:
    try:
        float(text.replace(" %", "").replace("+", ""))
    except ValueError:
        return False
    return True


class Document:
    """Blocks of a report; :meth:`markdown` and :meth:`html` render them."""

    def __init__(self, title: str):
        self.title = title
        self.blocks: list[tuple] = []

    def heading(self, text: str, level: int = 2) -> None:
        self.blocks.append(("heading", level, text))

    def paragraph(self, text: str, note: bool = False) -> None:
        self.blocks.append(("paragraph", text, note))

    def bullets(self, items: list[str]) -> None:
        if items:
            self.blocks.append(("bullets", list(items)))

    def table(self, header, rows) -> None:
        self.blocks.append(("table", [str(h) for h in header],
                            [[str(cell) for cell in row] for row in rows]))

    def image(self, src: str, alt: str) -> None:
        self.blocks.append(("image", src, alt))

    def markdown(self) -> str:
        """The document as GitHub-flavoured Markdown."""
        out = [f"# {self.title}", ""]
        for kind, *args in self.blocks:
            if kind == "heading":
                out += ["#" * args[0] + " " + args[1], ""]
            elif kind == "paragraph":
                out += [f"*{args[0]}*" if args[1] else args[0], ""]
            elif kind == "bullets":
                out += [f"- {item}" for item in args[0]] + [""]
            elif kind == "table":
                header, rows = args
                out.append("| " + " | ".join(header) + " |")
                out.append("|" + "---|" * len(header))
                out += ["| " + " | ".join(c.replace("|", "\\|") for c in row) + " |"
                        for row in rows]
                out.append("")
            elif kind == "image":
                out += [f"![{args[1]}]({args[0]})", ""]
        return "\n".join(out)

    def html(self) -> str:
        """The document as one HTML page with inline style."""
        esc = html.escape
        out = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
               f"<title>{esc(self.title)}</title><style>{_STYLE}</style></head><body>",
               f"<h1>{esc(self.title)}</h1>"]
        for kind, *args in self.blocks:
            if kind == "heading":
                level = min(args[0], 6)
                anchor = esc(args[1].split(":")[0].strip().replace(" ", "-"))
                out.append(f'<h{level} id="{anchor}">{esc(args[1])}</h{level}>')
            elif kind == "paragraph":
                cls = ' class="note"' if args[1] else ""
                out.append(f"<p{cls}>{esc(args[0])}</p>")
            elif kind == "bullets":
                out.append("<ul>" + "".join(f"<li>{esc(i)}</li>" for i in args[0]) + "</ul>")
            elif kind == "table":
                header, rows = args
                out.append("<table><thead><tr>" + "".join(f"<th>{esc(h)}</th>" for h in header)
                           + "</tr></thead><tbody>")
                for row in rows:
                    cells = "".join(
                        f'<td class="num">{esc(c)}</td>' if _is_number(c) else f"<td>{esc(c)}</td>"
                        for c in row)
                    out.append(f"<tr>{cells}</tr>")
                out.append("</tbody></table>")
            elif kind == "image":
                out.append(f'<p><img src="{esc(args[0])}" alt="{esc(args[1])}"></p>')
        out.append("</body></html>")
        return "\n".join(out) + "\n"
