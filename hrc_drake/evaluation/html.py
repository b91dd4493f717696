"""The plain HTML pages of the reports (a run's report.html, a sweep's, a search's
falsify.html): one style, tables of numbers."""

from html import escape

FLAG = ' class="flagged"'
FINE = ' class="fine"'


def html_table(header: list[str], rows: list[list], flagged=()) -> str:
    """`flagged`: indices of rows to mark (beyond a limit)."""
    head = "".join(f"<th>{escape(str(h))}</th>" for h in header)
    body = "".join(
        f"<tr{FLAG if k in flagged else ''}>"
        + "".join(f"<td>{escape(_cell(c))}</td>" for c in row)
        + "</tr>"
        for k, row in enumerate(rows)
    )
    return f"<table><tr>{head}</tr>{body}</table>"


def verdict(text: str, flagged: bool, element_id: str) -> str:
    """A line a reader sees before anything else on the page: marked when it is bad news."""
    return f'<p id="{element_id}"{FLAG if flagged else FINE}>{escape(text)}</p>'


def page(title: str, body: str) -> str:
    style = (
        "body{font-family:sans-serif;margin:2em}table{border-collapse:collapse;margin:1em 0}"
        "td,th{border:1px solid #ccc;padding:2px 8px;font-size:13px;text-align:right}"
        "td:first-child,th:first-child{text-align:left}"
        ".flagged{background:#f8d7d3}p.flagged,p.fine{padding:6px 10px;font-weight:bold}"
        "p.flagged{border-left:6px solid #c0392b}p.fine{background:#e3f1e3;"
        "border-left:6px solid #3c8d3c}"
    )
    return (
        f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>{escape(title)}</title>"
        f"<style>{style}</style></head><body>{body}</body></html>\n"
    )


def _cell(value) -> str:
    return f"{value:.6g}" if isinstance(value, float) else str(value)
