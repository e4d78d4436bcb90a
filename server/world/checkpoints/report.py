"""The report a student hands in: every checkpoint with its state, time, evidence and picture, and
the answers; as JSON, and as one printable HTML page that embeds the same JSON. Signed by
signing.py's ReportSigner."""

from __future__ import annotations

import base64
import json
from html import escape
from typing import Any

from server.world.checkpoints.plot import svg_data_url, track_svg
from server.world.checkpoints.progress import Progress, iso
from server.world.checkpoints.signing import KIND, META_EMPTY, ReportSigner
from server.world.checkpoints.view import Lines, questions, state

FORMAT = 1


def picture(progress: Progress, name: str, evidence: dict[str, Any] | None) -> str | None:
    """The page's capture of its 3D view, else a plot of the evidence's track, else None."""
    png = progress.captures.get(name)
    if png is not None:
        return "data:image/png;base64," + base64.b64encode(png).decode()
    if evidence is None or not evidence.get("track"):
        return None
    target = evidence.get("target")
    return svg_data_url(track_svg(evidence["track"], target, f"{name}: the drone's track"))


def build(progress: Progress, lines: Lines, world: str | None) -> dict[str, Any]:
    checkpoints = []
    for c in progress.checkpoints:
        record = progress.records.get(c.name)
        evidence = record.evidence if record is not None else None
        checkpoints.append(
            {
                "name": c.name,
                "title": c.title,
                "state": state(progress, lines, c.name),
                "done_at": iso(record.done_at_s) if record is not None else None,
                "times_done": record.times if record is not None else 0,
                "evidence": evidence,
                "picture": picture(progress, c.name, evidence),
            }
        )
    return {
        "kind": KIND,
        "format": FORMAT,
        "student": progress.student,
        "world": world,
        "generated_at": iso(progress.wall()),
        "checkpoints": checkpoints,
        "questions": questions(progress),
    }


def _evidence_html(evidence: dict[str, Any]) -> str:
    parts = []
    facts = {k: v for k, v in evidence.items() if not isinstance(v, (list, dict)) and k != "launch_text"}
    if facts:
        rows = "".join(f"<tr><th>{escape(k)}</th><td>{escape(str(v))}</td></tr>" for k, v in facts.items())
        parts.append(f"<table class='facts'>{rows}</table>")
    if evidence.get("launch_text"):
        parts.append(f"<h4>Launch file</h4><pre>{escape(str(evidence['launch_text']))}</pre>")
    graph = evidence.get("graph")
    if isinstance(graph, dict):
        student = {evidence.get("student_node")} | {
            e.get("by") for e in evidence.get("timeline", []) if isinstance(e, dict) and e.get("student")
        }
        nodes = ", ".join(
            f"<b>{escape(n['name'])} (yours)</b>" if n["name"] in student else escape(n["name"])
            for n in graph.get("nodes", [])
        )
        edges = "".join(
            f"<li>{escape(e['source'])} → {escape(e['target'])}</li>" for e in graph.get("edges", [])
        )
        parts.append(f"<h4>Graph</h4><p>{nodes}</p><ul class='edges'>{edges}</ul>")
    timeline = evidence.get("timeline") or evidence.get("setpoints") or []
    if timeline:
        rows = "".join(
            f"<tr><td>{e['t_s']:.2f}</td><td>{escape(str(e['what']))}</td><td>{escape(str(e['value']))}</td>"
            f"<td>{escape(str(e.get('by', '')))}</td></tr>"
            for e in timeline[-40:]
        )
        parts.append(
            f"<h4>Timeline (s on the lab's clock)</h4><table><tr><th>t</th><th>what</th><th>value</th>"
            f"<th>by</th></tr>{rows}</table>"
        )
    return "".join(parts)


STYLE = """body{font-family:sans-serif;max-width:52rem;margin:2rem auto;color:#222}
h2{border-bottom:1px solid #ccc}table{border-collapse:collapse;font-size:.85rem}td,th{padding:2px 8px;
text-align:left;border-bottom:1px solid #eee}pre{background:#f5f5f5;padding:.5rem;white-space:pre-wrap}
.done{color:#2e7d32}.in_progress{color:#ef6c00}.not_started{color:#777}img{max-width:100%}
section{page-break-inside:avoid}"""


def html_page(report: dict[str, Any]) -> bytes:
    who = report.get("student") or "the lab's student"
    sections = []
    for c in report["checkpoints"]:
        when = f" at {escape(c['done_at'])}" if c["done_at"] else ""
        body = _evidence_html(c["evidence"]) if c["evidence"] else ""
        pic = f"<img alt='{escape(c['name'])}' src='{escape(c['picture'])}'>" if c["picture"] else ""
        sections.append(
            f"<section><h2>{escape(c['title'])}</h2><p class='{escape(c['state'])}'>"
            f"{escape(c['state'].replace('_', ' '))}{when}</p>{pic}{body}</section>"
        )
    answers = "".join(
        f"<section><h3>{escape(q['text'])}</h3><pre>{escape(q['answer']) or '(no answer)'}</pre></section>"
        for q in report["questions"]
    )
    embedded = json.dumps(report, sort_keys=True).replace("<", "\\u003c")
    page = (
        "<!doctype html><html><head><meta charset='utf-8'>"
        f"<title>Checkpoints: {escape(who)}</title>{META_EMPTY.decode()}<style>{STYLE}</style></head><body>"
        f"<h1>Checkpoints of {escape(who)}</h1><p>Made {escape(str(report['generated_at']))} by the lab's "
        "server, which signed it: <code>ros2lab report verify FILE</code> tells whether it was changed.</p>"
        + "".join(sections)
        + "<h2>Answers</h2>"
        + answers
        + f'<script type="application/json" id="report">{embedded}</script></body></html>'
    )
    return page.encode()


def signed_files(signer: ReportSigner, report: dict[str, Any]) -> tuple[bytes, bytes]:
    """The report's JSON file and its HTML page, both signed."""
    signed = signer.sign(report)
    return signer.json_file(report), signer.sign_html(html_page(signed))
