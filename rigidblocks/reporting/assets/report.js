/* rigidblocks report: the sortable, filterable per-joint table (rendered from the JSON
 * in #rb-table-data, a page at a time, so that tens of thousands of joints stay fast). */
(function () {
  "use strict";
  const el = document.getElementById("rb-table-data");
  const host = document.getElementById("rb-table");
  if (!el || !host) return;
  const T = JSON.parse(el.textContent);
  if (!T.n) return;
  const units = T.units || {};
  const fu = units.force ? " [" + units.force + "]" : "";
  const lu = units.length ? " [" + units.length + "]" : "";
  const cols = [{ key: "joint", label: "joint", num: false }];
  if (T.has_forces) {
    cols.push({ key: "N", label: "N" + fu, num: true,
      title: "normal force resultant (compression positive)" });
    cols.push({ key: "T", label: (T.dimension === 3 ? "|T|" : "T") + fu, num: true,
      title: T.dimension === 3 ? "shear resultant's magnitude" : "shear along the joint's tangent" });
    cols.push({ key: "e", label: "e" + lu, num: true,
      title: T.dimension === 3 ? "distance of the centre of pressure from the joint's centroid"
        : "eccentricity: the resultant's position from the joint's midpoint" });
    cols.push({ key: "demand", label: "|T|/N", num: true, title: "friction demand" });
    // the joints' own laws, where they differ
    const su = units.force && units.length ? " [" + units.force + "/" + units.length + "\u00b2]" : "";
    if (T.friction) cols.push({ key: "friction", label: "f", num: true,
      title: "the joint's friction coefficient in this analysis" });
    if (T.cohesion) cols.push({ key: "cohesion", label: "c" + su, num: true,
      title: "the joint's cohesion (stress)" });
    if (T.tensile_strength) cols.push({ key: "tensile_strength", label: "ft" + su, num: true,
      title: "the joint's tensile strength (stress)" });
  }
  cols.push({ key: "state", label: T.state_label || "state", num: false,
    title: "open, in tension, hinging, at friction limit or closed; after a collapse, " +
      "the mechanism's mode (hinge, slide, open)" });
  const order = [];
  for (let k = 0; k < T.n; k++) order.push(k);
  let sortKey = null, dir = 1, page = 0, filter = "";
  const pageSize = 100;
  let rows = order.slice();

  function fmt(x) {
    if (x === null || x === undefined) return "-";
    if (x === "inf") return "\u221e";
    const a = Math.abs(x);
    if (a !== 0 && (a < 1e-3 || a >= 1e5)) return x.toExponential(3);
    return String(Number(x.toPrecision(4)));
  }
  function esc(s) {
    return String(s).replace(/&/g, "&amp;").replace(/</g, "&lt;").replace(/>/g, "&gt;")
      .replace(/'/g, "&#39;");
  }
  function val(k, key) {
    const v = T[key][k];
    if (v === "inf") return Infinity;
    return v;
  }
  function apply() {
    const f = filter.toLowerCase();
    rows = order.filter(function (k) {
      return !f || T.joint[k].toLowerCase().indexOf(f) >= 0 || T.state[k].indexOf(f) >= 0;
    });
    if (sortKey) {
      const c = cols.find(function (c) { return c.key === sortKey; });
      rows.sort(function (a, b) {
        let x = val(a, sortKey), y = val(b, sortKey);
        if (x === null || x === undefined) return 1;
        if (y === null || y === undefined) return -1;
        if (!c.num) { x = String(x); y = String(y); return dir * x.localeCompare(y); }
        return dir * (x - y);
      });
    }
    draw();
  }
  function draw() {
    const pages = Math.max(1, Math.ceil(rows.length / pageSize));
    page = Math.min(page, pages - 1);
    let h = "<div class='rb-tablebar'><input type='search' class='rb-filter' " +
      "placeholder='filter: block id or state' value='" + esc(filter) + "'> " +
      "<span>" + rows.length + " of " + T.n + " joints</span> " +
      "<button class='rb-prev'" + (page === 0 ? " disabled" : "") + ">\u2039 prev</button>" +
      " page " + (page + 1) + " / " + pages + " " +
      "<button class='rb-next'" + (page >= pages - 1 ? " disabled" : "") + ">next \u203a</button>" +
      "</div><table class='rb-joints'><thead><tr>";
    for (const c of cols) {
      const arrow = sortKey === c.key ? (dir > 0 ? " \u25b2" : " \u25bc") : "";
      h += "<th data-key='" + c.key + "'" + (c.title ? " title='" + esc(c.title) + "'" : "") +
        " aria-sort='" + (sortKey === c.key ? (dir > 0 ? "ascending" : "descending") : "none") +
        "'>" + c.label + arrow + "</th>";
    }
    h += "</tr></thead><tbody>";
    for (const k of rows.slice(page * pageSize, (page + 1) * pageSize)) {
      h += "<tr data-joint='" + k + "'" + (T.governing[k] ? " class='gov'" : "") + ">";
      for (const c of cols) {
        const v = T[c.key][k];
        h += c.num ? "<td class='num'>" + fmt(v) + "</td>" : "<td>" + esc(v) + "</td>";
      }
      h += "</tr>";
    }
    h += "</tbody></table>";
    host.innerHTML = h;
    host.querySelectorAll("th").forEach(function (th) {
      th.addEventListener("click", function () {
        const key = th.getAttribute("data-key");
        if (sortKey === key) dir = -dir; else { sortKey = key; dir = key === "demand" ? -1 : 1; }
        apply();
      });
    });
    const inp = host.querySelector(".rb-filter");
    inp.addEventListener("change", function () { filter = inp.value; page = 0; apply(); });
    host.querySelector(".rb-prev").addEventListener("click", function () { page--; draw(); });
    host.querySelector(".rb-next").addEventListener("click", function () { page++; draw(); });
    host.querySelectorAll("tbody tr").forEach(function (tr) {
      tr.addEventListener("click", function () {
        if (window.rbHighlightJoint) window.rbHighlightJoint(Number(tr.getAttribute("data-joint")));
      });
    });
  }
  // the joints that decide first: highest friction demand
  if (T.has_forces) { sortKey = "demand"; dir = -1; }
  apply();
  document.documentElement.dataset.tableRows = String(host.querySelectorAll("tbody tr").length);
})();
