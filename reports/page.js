// report.html's script (reports/page.py inlines it): the answer's chooser and tables, the
// work-precision diagrams and the spectra, drawn as SVG from the page's own data. No
// library and no network: the page works from a file.
"use strict";

const DATA = JSON.parse(document.getElementById("report-data").textContent);
if (DATA.answer) {  // each summary row as an object: its family's and setting's names, its numbers
  const A = DATA.answer;
  A.rows = A.rows.map((values) => {
    const r = Object.fromEntries(A.fields.map((f, i) => [f, values[i]]));
    const s = A.settings[r.setting];
    return Object.assign(r, { family: A.families[r.family], label: s.label, time_stepper: s.time_stepper,
                              line: s.line, fineness: s.fineness });
  });
  A.robust = {};  // error measure -> robustErrors(A.rows, measure), computed on first use
}
const SVG = "http://www.w3.org/2000/svg";
const FLOOR = 1e-13;  // errors below are round-off: drawn at it (reports/wp.py's ERROR_FLOOR)
const PALETTE = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#bcbd22",
                 "#17becf"];  // reports/styles.py's
const DASHES = ["", "8 3", "2 2.5", "8 2.5 2 2.5", "4 2.5", "12 3 2 2.5 2 2.5", "1.6 5.6"];

// A missing value (null in the JSON: a NaN, which JSON cannot hold) as NaN again, so that
// every comparison with it is false, as in the Python that wrote the markdown.
function val(x) { return x === null || x === undefined ? NaN : x; }

// Python's format(x, ".{p}g"): the same text as the markdown's numbers.
function fmtG(x, p) {
  if (!isFinite(x)) return isNaN(x) ? "nan" : (x > 0 ? "inf" : "-inf");
  if (x === 0) return "0";
  const [mantissa, exponent] = x.toExponential(p - 1).split("e");
  const e = parseInt(exponent, 10);
  const strip = (s) => (s.includes(".") ? s.replace(/0+$/, "").replace(/\.$/, "") : s);
  if (e < -4 || e >= p) return strip(mantissa) + "e" + (e < 0 ? "-" : "+") + String(Math.abs(e)).padStart(2, "0");
  return strip(x.toFixed(Math.max(p - 1 - e, 0)));
}

function el(tag, attrs, parent) {
  const node = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs || {})) node.setAttribute(k, v);
  if (parent) parent.appendChild(node);
  return node;
}

function option(select, value, text) {
  const o = document.createElement("option");
  o.value = value;
  o.textContent = text;
  select.appendChild(o);
}

// ---------------------------------------------------------------- the answer (answer.py)

// The rows of each setting over the given families, for the settings that ran on all of
// them (answer.settings_over): Maps family -> row, in order of first appearance.
function settingsOver(rows, families, timeSteppersOnly) {
  const by = new Map();
  for (const r of rows) {
    if (!families.includes(r.family) || (timeSteppersOnly && !r.time_stepper)) continue;
    if (!by.has(r.setting)) by.set(r.setting, new Map());
    by.get(r.setting).set(r.family, r);
  }
  return [...by.values()].filter((m) => m.size === new Set(families).size && families.every((f) => m.has(f)));
}

// robust.robust_errors, the one rule: each row's largest error `key` over it and every finer
// step of its line (its solver and variant, its settings apart from the step) on its family;
// NaN where one of them failed or is unresolved. A setting without a step (fineness null) is
// judged alone. A Map from row to its robust error.
function robustErrors(rows, key) {
  const out = new Map();
  const lines = new Map();  // family -> line -> [[row, error]]
  for (const r of rows) {
    const e = r.failed > 0 || r.unresolved > 0 ? NaN : val(r[key]);
    if (r.fineness === null) { out.set(r, e); continue; }
    if (!lines.has(r.family)) lines.set(r.family, new Map());
    const byLine = lines.get(r.family);
    if (!byLine.has(r.line)) byLine.set(r.line, []);
    byLine.get(r.line).push([r, e]);
  }
  for (const byLine of lines.values()) {
    for (const members of byLine.values()) {
      // finest first, so that one running maximum carries every finer step's error
      members.sort((a, b) => b[0].fineness - a[0].fineness);
      let running = -Infinity;
      for (const [r, e] of members) {
        running = isNaN(e) || isNaN(running) ? NaN : Math.max(running, e);
        out.set(r, running);
      }
    }
  }
  return out;
}

// answer.cheapest: among settings whose robust error `key` (robustErrors) is <= target on
// every family, the cheapest by its median CPU time on its most expensive family; that row.
function cheapest(settings, key, target, robust) {
  let best = null;
  for (const perFamily of settings) {
    const rows = [...perFamily.values()];
    if (rows.some((r) => !(robust.get(r) <= target))) continue;
    let costliest = rows[0];
    for (const r of rows) if (val(r.cpu) > val(costliest.cpu)) costliest = r;
    if (best === null || val(costliest.cpu) < val(best.cpu)) best = costliest;
  }
  return best;
}

function choose(scope, key, target) {
  const A = DATA.answer;
  const settings = settingsOver(A.rows, scope.families, scope.time_steppers_only);
  if (!(key in A.robust)) A.robust[key] = robustErrors(A.rows, key);
  const best = cheapest(settings, key, target, A.robust[key]);
  if (best === null) return null;
  const mine = settings.find((m) => [...m.values()].includes(best));
  const worst = (k) => {
    const v = [...mine.values()].map((r) => val(r[k])).filter((x) => !isNaN(x));
    return v.length ? fmtG(Math.max(...v), 2) : "–";
  };
  const imp = key === "err_median" ? "imp_median" : "imp_p95";
  return { setting: best.label, cost: best.cost, family: best.family,
           error: worst(key) + (A.impacting ? " / " + worst(imp) : "") };
}

function answerTables() {
  const A = DATA.answer;
  const box = document.getElementById("answer-tables");
  for (const [key, measure] of A.measures) {
    const h = document.createElement("p");
    h.textContent = "By the " + measure + " of the error:";
    box.appendChild(h);
    const table = document.createElement("table");
    table.className = "answer-table";
    table.dataset.measure = key;
    const head = ["scene", "target", "cheapest setting", "CPU per run (us)", "cost set by",
                  "error, worst family: " + (A.impacting ? "every point / impacting points" : "every point")];
    table.innerHTML = "<thead><tr>" + head.map((t) => "<th>" + t + "</th>").join("") + "</tr></thead>";
    const body = document.createElement("tbody");
    for (const scope of A.scopes.slice(0, A.table_scopes)) {
      for (const target of A.targets) {
        const c = choose(scope, key, target);
        const tr = document.createElement("tr");
        const cells = c ? [scope.name, fmtG(target, 6), c.setting, c.cost, c.family, c.error]
                        : [scope.name, fmtG(target, 6), "none", "", "", ""];
        cells.forEach((t, i) => {
          const td = document.createElement("td");
          td.textContent = t;
          if (i === 1 || i === 3 || i === 5) td.className = "num";
          if (i === 0 && A.all.includes(t)) td.style.fontWeight = "600";
          tr.appendChild(td);
        });
        body.appendChild(tr);
      }
    }
    table.appendChild(body);
    box.appendChild(table);
  }
}

function chooser() {
  const A = DATA.answer;
  const scope = document.getElementById("chooser-scope");
  const target = document.getElementById("chooser-target");
  const measure = document.getElementById("chooser-measure");
  A.scopes.forEach((s, i) => option(scope, i, s.name));
  A.targets.forEach((t) => option(target, t, fmtG(t, 6)));
  A.measures.forEach(([key, name]) => option(measure, key, name));
  const show = () => {
    const c = choose(A.scopes[+scope.value], measure.value, +target.value);
    document.getElementById("chooser-setting").textContent = c ? c.setting : "none";
    document.getElementById("chooser-cost").textContent = c ? c.cost : "–";
    document.getElementById("chooser-family").textContent = c ? c.family : "–";
    document.getElementById("chooser-error").textContent = c ? c.error : "–";
  };
  for (const s of [scope, target, measure]) s.addEventListener("change", show);
  show();
}

// ---------------------------------------------------------------- charts

const tooltip = document.getElementById("tooltip");
function showTip(event, lines) {
  tooltip.replaceChildren(...lines.flatMap((t, i) => (i ? [document.createElement("br"), t] : [t])));
  tooltip.classList.add("on");
  moveTip(event);
}
function moveTip(event) {
  tooltip.style.left = (event.pageX + 14) + "px";
  tooltip.style.top = (event.pageY + 12) + "px";
}
function hideTip() { tooltip.classList.remove("on"); }

function scale(lo, hi, a, b, log) {
  const f = log ? Math.log10 : (x) => x;
  const [l, h] = [f(lo), f(hi)];
  return (x) => a + (f(x) - l) / (h - l || 1) * (b - a);
}

// Axis ends and ticks: whole decades on a log axis, round steps on a linear one.
function ticks(lo, hi, log) {
  if (log) {
    const a = Math.floor(Math.log10(lo)), b = Math.ceil(Math.log10(hi));
    const step = Math.max(1, Math.ceil((b - a) / 8));
    const t = [];
    for (let e = a; e <= b; e += step) t.push(Math.pow(10, e));
    return { lo: Math.pow(10, a), hi: Math.pow(10, b), ticks: t };
  }
  const span = hi - lo || Math.abs(hi) || 1;
  const raw = span / 6, mag = Math.pow(10, Math.floor(Math.log10(raw)));
  const step = [1, 2, 5, 10].map((m) => m * mag).find((s) => s >= raw);
  const a = Math.floor(lo / step) * step, b = Math.ceil(hi / step) * step;
  const t = [];
  for (let x = a; x <= b + step / 2; x += step) t.push(Math.abs(x) < step / 1e6 ? 0 : x);
  return { lo: a, hi: b, ticks: t };
}

function tickText(x, log) {
  if (log) {
    const e = Math.round(Math.log10(x));
    return e >= -2 && e <= 3 ? String(x >= 1 ? Math.round(x) : +x.toFixed(-e)) : "1e" + e;
  }
  return fmtG(x, 4);
}

// One chart: series of points {x, y, hollow, info} as lines and markers. opts: width,
// height, title, xlabel, ylabel, xlog, ylog, floor (a y under which points are round-off),
// series [{name, color, dash, width, markers, points}], and `behind`: series drawn under the
// rest with no markers (a Pareto front).
function chart(opts) {
  const W = opts.width, H = opts.height, m = { l: 64, r: 14, t: opts.title ? 26 : 10, b: 46 };
  const svg = el("svg", { width: W, height: H, viewBox: `0 0 ${W} ${H}`, role: "img" });
  const all = opts.series.concat(opts.behind || []).flatMap((s) => s.points);
  const xs = all.map((p) => p.x).filter((x) => isFinite(x) && (!opts.xlog || x > 0));
  const ys = all.map((p) => p.y).filter((y) => isFinite(y) && (!opts.ylog || y > 0));
  if (!xs.length || !ys.length) {
    el("text", { x: 10, y: 30 }, svg).textContent = "nothing to draw";
    return svg;
  }
  const X = ticks(Math.min(...xs), Math.max(...xs), opts.xlog), Y = ticks(Math.min(...ys), Math.max(...ys), opts.ylog);
  const sx = scale(X.lo, X.hi, m.l, W - m.r, opts.xlog), sy = scale(Y.lo, Y.hi, H - m.b, m.t, opts.ylog);
  if (opts.floor && Y.lo < opts.floor) el("rect", { class: "floor", x: m.l, y: sy(opts.floor), width: W - m.l - m.r,
                                                    height: H - m.b - sy(opts.floor) }, svg);
  for (const t of X.ticks) {
    el("line", { class: "grid", x1: sx(t), x2: sx(t), y1: m.t, y2: H - m.b }, svg);
    el("text", { x: sx(t), y: H - m.b + 16, "text-anchor": "middle" }, svg).textContent = tickText(t, opts.xlog);
  }
  for (const t of Y.ticks) {
    el("line", { class: "grid", x1: m.l, x2: W - m.r, y1: sy(t), y2: sy(t) }, svg);
    el("text", { x: m.l - 6, y: sy(t) + 4, "text-anchor": "end" }, svg).textContent = tickText(t, opts.ylog);
  }
  el("rect", { class: "axis", x: m.l, y: m.t, width: W - m.l - m.r, height: H - m.t - m.b }, svg);
  el("text", { x: (m.l + W - m.r) / 2, y: H - 8, "text-anchor": "middle" }, svg).textContent = opts.xlabel;
  el("text", { x: 14, y: (m.t + H - m.b) / 2, "text-anchor": "middle",
               transform: `rotate(-90 14 ${(m.t + H - m.b) / 2})` }, svg).textContent = opts.ylabel;
  if (opts.title) el("text", { x: (m.l + W - m.r) / 2, y: 17, "text-anchor": "middle" }, svg).textContent = opts.title;
  const path = (pts) => pts.map((p, i) => (i ? "L" : "M") + sx(p.x).toFixed(1) + " " + sy(p.y).toFixed(1)).join("");
  for (const s of opts.behind || [])
    el("path", { d: path(s.points), fill: "none", stroke: s.color, "stroke-width": s.width, "stroke-linecap": "round",
                 "stroke-linejoin": "round", opacity: s.opacity }, svg);
  opts.series.forEach((s, index) => {
    const pts = s.points.filter((p) => isFinite(p.x) && isFinite(p.y) && (!opts.xlog || p.x > 0) && (!opts.ylog || p.y > 0));
    el("path", { d: path(pts), fill: "none", stroke: s.color, "stroke-width": s.width || 1.6,
                 "stroke-dasharray": s.dash || "" }, svg);
    if (!s.markers) return;
    pts.forEach((p, i) => {
      const c = el("circle", { class: "pt", cx: sx(p.x).toFixed(1), cy: sy(p.y).toFixed(1), r: 4.5, stroke: s.color,
                               "stroke-width": 1.5, fill: p.hollow ? "#fff" : s.color,
                               "data-series": index, "data-point": i }, svg);
      c.addEventListener("mouseenter", (e) => showTip(e, p.info));
      c.addEventListener("mousemove", moveTip);
      c.addEventListener("mouseleave", hideTip);
    });
  });
  return svg;
}

// A legend whose entries toggle their series (hidden: a Set of names) and whose group
// names show that group alone; `redraw` draws the charts again.
function legend(box, entries, hidden, redraw) {
  box.replaceChildren();
  let group = null;
  for (const e of entries) {
    if (e.group && e.group !== group) {
      group = e.group;
      const g = document.createElement("div");
      g.className = "group";
      g.textContent = group;
      g.title = "show this group alone";
      const members = entries.filter((x) => x.group === group).map((x) => x.name);
      g.addEventListener("click", () => {
        for (const x of entries) (members.includes(x.name) ? hidden.delete(x.name) : hidden.add(x.name));
        redraw();
      });
      box.appendChild(g);
    }
    const item = document.createElement("span");
    item.className = "item" + (hidden.has(e.name) ? " off" : "");
    item.dataset.series = e.name;
    const swatch = el("svg", { class: "swatch", width: 30, height: 10 });  // the line as the chart draws it
    el("line", { x1: 1, x2: 29, y1: 5, y2: 5, stroke: e.color, "stroke-width": 2, "stroke-dasharray": e.dash || "" },
       swatch);
    item.append(swatch, e.name);
    item.addEventListener("click", () => { (hidden.has(e.name) ? hidden.delete(e.name) : hidden.add(e.name)); redraw(); });
    box.appendChild(item);
  }
}

// A colour and a dash per series name: a solver setting's are the figures' (DATA.styles,
// reports/styles.py), the same in every family; any other series' by its place in the
// legend, colour and dash cycling at different lengths, so that no two of a chart share both.
function styles(entries) {
  const given = DATA.styles || {};
  return entries.map((e, k) => Object.assign({}, e, given[e.name] ||
    { color: PALETTE[k % PALETTE.length], dash: DASHES[k % DASHES.length] }));
}

function chartWidth(columns) {
  const room = Math.min(document.body.clientWidth || 1000, 1100) - 8;
  return Math.max(320, Math.floor(room / columns) - 8);
}

// ---------------------------------------------------------------- work-precision diagrams

function diagrams() {
  const D = DATA.diagrams;
  const family = document.getElementById("wp-family"), measure = document.getElementById("wp-measure");
  Object.keys(D).forEach((f) => option(family, f, f));
  DATA.answer.measures.forEach(([key, name]) => option(measure, key, name + " over the points"));
  const hidden = new Set();
  const draw = () => {
    const key = measure.value, name = measure.options[measure.selectedIndex].text;
    const entries = styles(D[family.value].map((s) => ({ name: s.name, group: s.group, points: s.points })));
    // The lines greyed out stay behind the others, thin and without markers, for context.
    const context = entries.filter((e) => hidden.has(e.name)).map((e) => ({
      points: e.points.filter((p) => !isNaN(val(p[key]))).map((p) => ({ x: 1e6 * val(p.cpu), y: Math.max(val(p[key]), FLOOR) })),
      color: "#bbb", width: 1, opacity: 0.8 }));
    const series = entries.filter((e) => !hidden.has(e.name)).map((e) => ({
      name: e.name, color: e.color, dash: e.dash, markers: true,
      points: e.points.filter((p) => !isNaN(val(p[key]))).map((p) => ({
        x: 1e6 * val(p.cpu), y: Math.max(val(p[key]), FLOOR), hollow: p.failed > 0,
        info: [p.setting, "N = " + (p.n === null ? "– (no step)" : p.n), name.split(" ")[0] === "median"
          ? "median error: " + fmtG(val(p[key]), 3) : "95th percentile error: " + fmtG(val(p[key]), 3),
               "CPU per run: " + p.cost + " us"].concat(p.failed ? [p.failed + " of " + p.runs + " runs failed"] : []),
      })),
    }));
    // The Pareto front over every configuration shown: cheapest first, each one more accurate.
    const candidates = series.flatMap((s) => s.points.filter((p) => !p.hollow)).sort((a, b) => a.x - b.x);
    const front = [];
    for (const p of candidates) if (!front.length || p.y < front[front.length - 1].y) front.push(p);
    const box = document.getElementById("wp-chart");
    box.replaceChildren(chart({ width: chartWidth(1), height: 440, xlog: true, ylog: true, floor: FLOOR,
                                title: family.value + ": " + name, xlabel: "CPU time per run (us)",
                                ylabel: "relative Pi1 error", series,
                                behind: context.concat([{ points: front, color: "#000", width: 9, opacity: 0.15 }]) }));
    legend(document.getElementById("wp-legend"), entries, hidden, draw);
  };
  family.addEventListener("change", () => { hidden.clear(); draw(); });
  measure.addEventListener("change", draw);
  document.getElementById("wp-all").addEventListener("click", () => { hidden.clear(); draw(); });
  draw();
}

// ---------------------------------------------------------------- spectra

function spectra() {
  const S = DATA.spectra;
  const family = document.getElementById("spectra-family");
  Object.keys(S.families).forEach((f) => option(family, f, f));
  const hidden = new Set();
  const draw = () => {
    const panels = S.families[family.value];
    const names = new Map();
    for (const p of panels) for (const l of p.lines) if (l.kind === "series" && !names.has(l.name)) names.set(l.name, l.group);
    const entries = styles([...names].map(([name, group]) => ({ name, group })));
    const style = new Map(entries.map((e) => [e.name, e]));
    const box = document.getElementById("spectra-charts");
    box.replaceChildren();
    const columns = Math.min(panels.length, 2);
    for (const p of panels) {
      const ref = new Map((p.lines.find((l) => l.kind === "reference") || { points: [] }).points.map(([x, y]) => [x, y]));
      const series = p.lines.filter((l) => l.kind !== "series" || !hidden.has(l.name)).map((l) => {
        const s = l.kind === "reference" ? { color: "#000", width: 2.6 } : l.kind === "free"
          ? { color: "#999", dash: "5 4", width: 1.2 } : { color: style.get(l.name).color, dash: style.get(l.name).dash };
        return Object.assign(s, { name: l.name, markers: l.kind !== "free", points: l.points.map(([x, y]) => ({
          x: val(x), y: val(y),
          info: [l.name, "Pi2 = " + fmtG(val(x), 4), "Pi1 = " + fmtG(val(y), 5)].concat(
            l.kind === "series" && ref.has(x) ? ["relative error " + fmtG(Math.abs(y - ref.get(x)) / ref.get(x), 3)] : []),
        })) });
      });
      const ys = p.lines.filter((l) => l.kind === "reference" || l.kind === "series")
        .flatMap((l) => l.points.map(([, y]) => val(y))).filter((y) => y > 0);
      const ylog = ys.length > 0 && Math.max(...ys) / Math.min(...ys) > Math.pow(10, 1.5);
      box.appendChild(chart({ width: chartWidth(columns), height: 340, xlog: true, ylog, title: p.title,
                              xlabel: S.x, ylabel: S.y, series }));
    }
    legend(document.getElementById("spectra-legend"), entries, hidden, draw);
  };
  family.addEventListener("change", draw);
  draw();
}

if (DATA.answer) { chooser(); answerTables(); }
if (DATA.diagrams) diagrams();
if (DATA.spectra) spectra();
window.addEventListener("resize", () => {
  if (DATA.diagrams) document.getElementById("wp-measure").dispatchEvent(new Event("change"));
  if (DATA.spectra) document.getElementById("spectra-family").dispatchEvent(new Event("change"));
});
