"""The report as one self-contained HTML document.

Everything is inline: the style sheet, the scripts (the joint table's, the 3D viewer's
and, for 3D scenes, three.js itself, see ``vendor/README.md``), the data as JSON and the
2D pictures as SVG whose text stays text. The document makes no network request, so
it opens offline from a file, an e-mail attachment or a notebook.

A page-side hook records JavaScript errors: it writes them into ``#rb-errors`` and
counts them in ``<html data-js-errors>``; a working 3D view sets
``<html data-viewer-ready="1">`` and its timings (see :mod:`rigidblocks.reporting.browser`).
"""

from __future__ import annotations

import datetime as _dt
import html
import io
import json
import re
from importlib import resources
from typing import Any

from ..scene.model import Scene
from . import content

ERROR_HOOK = """window.rbErrors = [];
function rbErr(msg) {
  window.rbErrors.push(String(msg));
  document.documentElement.setAttribute("data-js-errors", String(window.rbErrors.length));
  var box = document.getElementById("rb-errors");
  if (box) { box.hidden = false; box.textContent += String(msg) + "\\n"; }
}
window.addEventListener("error", function (e) {
  var t = e.target;
  if (t && t !== window && (t.src || t.href)) {  // a resource that failed to load
    rbErr("resource failed to load: " + (t.src || t.href));
  } else {
    rbErr("error: " + e.message + " (" + (e.filename || "inline") + ":" + (e.lineno || 0) + ")");
  }
}, true);
window.addEventListener("unhandledrejection", function (e) {
  rbErr("unhandled rejection: " + (e.reason && e.reason.stack || e.reason));
});"""

LAUNCH_3D = """try {
  const data = JSON.parse(document.getElementById("rb-view-data").textContent);
  const table = JSON.parse(document.getElementById("rb-table-data").textContent);
  window.rbViewer(window.THREE, data, document.getElementById("rb-view"), table);
} catch (e) {
  document.getElementById("rb-view-msg").hidden = false;
  rbErr("3D view: " + (e && e.stack || e));
}"""


def asset(name: str) -> str:
    """The text of a file shipped in ``assets/`` or ``vendor/``."""
    return resources.files(__package__).joinpath(name).read_text(encoding="utf-8")


def three_script() -> str:
    """three.js as a classic script that defines ``window.THREE``.

    The vendored file is an ES module whose only module syntax is its final
    ``export{a as Name, ...}`` statement (no imports, no ``import.meta``): wrapped in a
    function, with that statement turned into ``window.THREE = {Name: a, ...}``, it runs
    as an ordinary inline script, synchronously, before the page's load event (so that
    a headless browser's screenshot sees the drawn view) and in notebooks that do not
    run module scripts.
    """
    src = asset("vendor/three.module.min.js")
    i = src.rindex("export{")
    j = src.index("}", i)
    if "import.meta" in src or re.search(r"(^|[;}])import[\s{(]", src):
        raise RuntimeError("the vendored three.js imports modules: cannot inline it")
    names = []
    for item in src[i + len("export{"):j].split(","):
        local, _, exported = item.strip().partition(" as ")
        names.append(f"{exported or local}:{local}")
    rest = src[j + 1:].lstrip().removeprefix(";")
    body = src[:i] + rest
    if "</script" in body.lower():
        raise RuntimeError("three.js source cannot be inlined")
    return ('(function () {"use strict";\n' + body + "\nwindow.THREE = Object.freeze({"
            + ",".join(names) + "});\n})();")


def _json(obj: Any) -> str:
    """JSON safe inside a <script> element (no "<" at all)."""
    return json.dumps(obj, separators=(",", ":"), allow_nan=False).replace("<", "\\u003c")


def _e(s: Any) -> str:
    return html.escape(str(s), quote=True)


def _words(s: Any) -> str:
    """Escaped text whose `quoted` commands (the terminal's backticks) are code."""
    return re.sub(r"`([^`]+)`", r"<code>\1</code>", _e(s))


def svg_picture(scene: Scene, result: Any = None, **kwargs: Any) -> str:
    """The 2D picture (:func:`rigidblocks.plotting.plot`) as an inline <svg> element,
    text kept as text."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    from ..plotting import plot

    ax = plot(scene, result, **kwargs)
    buf = io.StringIO()
    try:
        with matplotlib.rc_context({"svg.fonttype": "none", "svg.hashsalt": "rb"}):
            ax.figure.savefig(buf, format="svg", bbox_inches="tight")
    finally:
        plt.close(ax.figure)
    text = buf.getvalue()
    start = text.index("<svg")
    svg = text[start:]
    head_end = svg.index(">")
    head = svg[:head_end]
    # no size (the page sizes it), no namespace attributes (inline SVG in HTML needs
    # none) and no RDF metadata: the report names no address at all
    head = re.sub(r'\s(width|height|xmlns(:\w+)?)="[^"]*"', "", head)
    svg = re.sub(r"<metadata>.*?</metadata>", "", svg, flags=re.S)
    head_end = svg.index(">")
    return head + ' role="img" aria-label="picture of the structure and the result"' + \
        svg[head_end:]


def _answer_html(ans: content.Answer) -> str:
    badge = ans.status if ans.verdict else "no verdict"
    items = "".join(f"<li>{_words(d)}</li>" for d in ans.details)
    return (f'<div class="answer {ans.tone}" id="rb-answer" data-status="{_e(ans.status)}" '
            f'data-verdict="{"yes" if ans.verdict else "no"}">'
            f'<span class="badge">{_e(badge)}</span>'
            f'<span class="headline">{_words(ans.headline)}</span>'
            + (f"<ul>{items}</ul>" if items else "") + "</div>")


def _view3d_html(mechanism: bool, moving: list[tuple[str, str]] | None = None,
                 forces: bool = True, breached: bool = False) -> str:
    """The 3D view's canvas, legend and layer switches; ``moving``: the legend's rows of
    the moving blocks' colours (:func:`rigidblocks.plotting.marks.mechanism_colours`).
    Without a mechanism (a check) its legend rows, layer, slider and play button are left
    out: a check's report showed "moving block (mechanism)" and a mechanism to play.
    ``forces``: the view draws joint resultants; ``breached``: it marks the joints a
    NOT ADMISSIBLE check breaches (its legend read "joint resultant" over none)."""
    rows = (moving or [("#e39a5b", "moving block (mechanism)")]) if mechanism else []
    legend = (
        '<div class="rb-legend">'
        '<div><span class="sw" style="background:#d9c7a7"></span>block</div>'
        '<div><span class="sw" style="background:#8a8a8a"></span>support</div>'
        + "".join(f'<div><span class="sw" style="background:{_e(c)}"></span>{_e(t)}</div>'
                  for c, t in rows) +
        ('<div><span class="ln" style="border-color:#d62728"></span>hinge line (dots at '
         'its ends)</div>'
         '<div><span class="ln" style="border-color:#1f77b4"></span>sliding joint / joint '
         'resultant</div>'
         '<div><span class="ln" style="border-color:#ff8c00"></span>opening joint</div>'
         if mechanism else
         '<div><span class="ln" style="border-color:#1f77b4"></span>joint resultant</div>'
         if forces else "")
        + ('<div><span class="sw" style="background:#d62728;border-radius:50%"></span>'
           'breached joint (its breach in the table)</div>' if breached else "")
        + '<div><span class="ln" style="border-color:#333"></span>dead load</div>'
        '<div><span class="ln" style="border-color:#c2185b"></span>live load '
        '(\N{MULTIPLICATION SIGN} \N{GREEK SMALL LETTER LAMDA})</div></div>')
    layers = "".join(
        f'<label><input type="checkbox" data-layer="{k}"{" checked" if on else ""}> {lab}'
        "</label>"
        for k, lab, on in (("blocks", "blocks", True),
                           # with a mechanism the forces are one layer too many at first
                           ("forces", "forces", not mechanism),
                           ("mechanism", "mechanism", True), ("loads", "loads", True),
                           ("joints", "joint dots", True))
        if mechanism or k != "mechanism")
    play = ('<label>mechanism <input type="range" class="rb-amp" min="0" max="1000" '
            'value="1000"></label><button class="rb-play" type="button">play</button>'
            if mechanism else "")
    return (
        '<div class="rb-view" id="rb-view"><canvas aria-label="interactive 3D view">'
        "</canvas>" + legend + '<div class="rb-labels"></div><div class="rb-tip" hidden>'
        '</div><div class="rb-panel">' + layers + play +
        '<button class="rb-reset" type="button">reset view</button></div></div>'
        '<p class="rb-help">Drag to turn, wheel to zoom, right-drag or shift-drag to pan; '
        "hover a joint (its dot) for its forces, click a row of the table to find it."
        + (" The mechanism's displacements are to an arbitrary scale (the slider)."
           if mechanism else "") + "</p>"
        '<p id="rb-view-msg" hidden>The 3D view could not start (it needs WebGL); the '
        "tables below are complete.</p>")


def render(scene: Scene, result: Any = None, *, title: str | None = None) -> str:
    """The report of a scene and (optionally) an analysis result, as an HTML document."""
    from .._version import __version__

    summ = content.summary(scene, result)
    ans = content.answer(scene, result) if result is not None else None
    table = content.joint_table(result) if result is not None else {"n": 0}
    table.update({"units": {"length": scene.length_unit, "force": scene.force_unit},
                  "dimension": scene.dimension})
    heading = title or summ.title
    now = _dt.datetime.now(_dt.UTC).strftime("%Y-%m-%d %H:%M UTC")
    parts = [
        "<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
        '<meta name="viewport" content="width=device-width, initial-scale=1">',
        f"<title>{_e(heading)} \N{EM DASH} rigidblocks report</title>",
        f"<script>{ERROR_HOOK}</script>", f"<style>{asset('assets/report.css')}</style>",
        "</head><body><main>", '<pre id="rb-errors" hidden></pre>',
        f'<header><h1>{_e(heading)}</h1><div class="sub">rigidblocks {__version__} report, '
        f"{now}" + (f", scene file {_e(scene.source)}"
                     if scene.source and scene.source != scene.name else "") +
        "</div></header>",
        "<noscript><p>The 3D view and the joint table need JavaScript; the rest of this "
        "report reads without it.</p></noscript>",
    ]
    if result is not None:
        parts += ["<section><h2>Question and answer</h2>",
                  f'<p class="question">{_e(content.question(scene, result))}</p>',
                  _answer_html(ans)]
        if ans.notes:  # the solver's and the accuracy's (the CLI's --verbose)
            parts.append('<details class="notes"><summary>Solver and accuracy notes'
                         '</summary><ul class="notes">'
                         + "".join(f"<li>{_words(n)}</li>" for n in ans.notes)
                         + "</ul></details>")
        shown = content.forces_shown(result)
        if shown is not None:
            parts.append(f'<p class="rb-help">{_e(shown)}</p>')
        parts.append("</section>")
    parts.append("<section><h2>Picture</h2>")
    scripts = [f'<script type="application/json" id="rb-table-data">{_json(table)}</script>']
    if scene.dimension == 2:
        parts.append(f'<div class="picture" id="rb-picture">{svg_picture(scene, result)}</div>')
    else:
        from .view3d import view_data

        data = view_data(scene, result)
        joints = data.get("joints", {})
        parts.append(_view3d_html(getattr(result, "mechanism", None) is not None,
                                  data.get("mechanism", {}).get("legend"),
                                  forces="forces" in joints, breached="breached" in joints))
        scripts += [
            f'<script type="application/json" id="rb-view-data">{_json(data)}</script>',
            f"<script>{three_script()}</script>",
            f"<script>{asset('assets/viewer.js')}</script>",
            f"<script>{LAUNCH_3D}</script>",
        ]
    parts.append("</section>")
    parts.append('<section><h2>Scene</h2><table class="kv">' + "".join(
        f"<tr><th>{_e(k)}</th><td>{_e(v)}</td></tr>" for k, v in summ.rows) + "</table>")
    if summ.loads:
        parts.append("<p><b>Point loads</b></p><ul>" + "".join(
            f"<li>{_e(x)}</li>" for x in summ.loads) + "</ul>")
    parts.append("</section>")
    if table.get("n") and not table.get("has_forces") \
            and all(x == "-" for x in table.get("state", ())):
        # (a result made with state=False: a row per joint, each "joint -", nothing else)
        parts.append("<section><h2>Joints</h2><p class=\"rb-help\">No joint forces: the "
                     "result was made without its force state (state=False); analyse "
                     "with state=True for the joint table.</p></section>")
    elif table.get("n"):
        parts.append("<section><h2>Joints</h2><p class=\"rb-help\">Click a column to sort "
                     "(highest friction demand first); governing joints are highlighted."
                     "</p><div id=\"rb-table\"></div></section>")
    parts.append("<footer>Self-contained: this file needs no network and no other file. "
                 "three.js (MIT licence) is included in 3D reports.</footer></main>")
    # the table first: the 3D view's hover reads the table's data
    parts.append(scripts[0])
    parts.append(f"<script>{asset('assets/report.js')}</script>")
    parts += scripts[1:]
    parts.append("</body></html>")
    return "\n".join(parts)


__all__ = ["asset", "render", "svg_picture"]
