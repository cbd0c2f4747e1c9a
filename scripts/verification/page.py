"""HTML pieces of the verification report: embedded PNGs, tables, markdown tables, verdicts."""
import base64
import html
import re
from dataclasses import dataclass
from pathlib import Path

STYLE = ("body{font-family:sans-serif;max-width:1150px;margin:auto}img{max-width:100%}"
         "table{border-collapse:collapse;margin:0.5em 0}td,th{border:1px solid #bbb;padding:2px 8px}"
         "pre{color:#a00}pre.log{color:#333;font-size:85%;white-space:pre-wrap}"
         ".pass{color:#070;font-weight:bold}.fail{color:#b00;font-weight:bold}"
         ".info{color:#555;font-weight:bold}")


@dataclass
class Section:
    """One section: `passed` is True or False against the suite's tolerances, None where the
    suite asserts nothing (a measurement shown for information)."""
    body: str
    passed: object = None
    against: str = "the suite's tolerances"


def image(path):
    data = base64.b64encode(Path(path).read_bytes()).decode()
    return f'<img src="data:image/png;base64,{data}" alt="{html.escape(Path(path).name)}">'


def table(header, rows):
    head = "".join(f"<th>{html.escape(str(h))}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in r) + "</tr>"
                   for r in rows)
    return f"<table><tr>{head}</tr>{body}</table>"


def markdown(text):
    """A study's markdown (headings, paragraphs, pipe tables) as HTML."""
    out, rows = [], []

    def flush():
        if rows:
            out.append(table(rows[0], rows[1:]))
            rows.clear()

    for line in text.splitlines():
        if line.startswith("|"):
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if not all(re.fullmatch(r":?-+:?", c) for c in cells):
                rows.append(cells)
            continue
        flush()
        if line.startswith("#"):
            out.append(f"<h3>{html.escape(line.lstrip('#').strip())}</h3>")
        elif line.strip():
            out.append(f"<p>{html.escape(line)}</p>")
    flush()
    return "".join(out)


def verdict(section):
    if section.passed is None:
        return '<span class="info">measured (the suite asserts no bound)</span>'
    return ('<span class="pass">PASSED</span>' if section.passed
            else '<span class="fail">FAILED</span>') + f" against {html.escape(section.against)}"


def render(sections, mode, seconds):
    """sections: [(title, Section or None, error text or None)]."""
    summary, parts = [], []
    for k, (title, section, error) in enumerate(sections):
        anchor = f"s{k}"
        state = verdict(section) if section else '<span class="fail">NOT MADE</span>'
        summary.append(f'<tr><td><a href="#{anchor}">{html.escape(title)}</a></td><td>{state}</td></tr>')
        body = section.body if section else f"<pre>{html.escape(error)}</pre>"
        parts.append(f'<h2 id="{anchor}">{html.escape(title)}</h2><p>{state}</p>{body}')
    return ("<!DOCTYPE html><html><head><meta charset='utf-8'><title>meshfree verification"
            f"</title><style>{STYLE}</style></head><body>"
            f"<h1>meshfree verification report</h1><p>{html.escape(mode)}; made in {seconds:.0f} s."
            "</p><table><tr><th>section</th><th>result</th></tr>" + "".join(summary) + "</table>"
            + "".join(parts) + "</body></html>")
