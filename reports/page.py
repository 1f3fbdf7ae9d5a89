"""The report as one HTML page to explore in a browser: report.html, a single file with its
data, its style (page.css) and its script (page.js) inside, so that it works from a file
with no network at all. The charts are inline SVG drawn by page.js from the data, with no
chart library: log axes, lines, markers, a tooltip and a legend that toggles series are a
few hundred lines, less than vendoring one. The answer's chooser computes the cheapest
setting in the page from the summary rows the markdown table is written from, by the same
rule (answer.py's cheapest over robust.py's robust errors, in page.js's cheapest over its
robustErrors); tests/report_page_test.py holds the two to the same answers in a real browser.

Each method adds a section (its place in the page is the order of the calls) and the data
its script draws; the report's sections call them (report.py)."""

import html
import json
import math
import os
import re
from collections import defaultdict

import answer
import robust
from rows import by_family, config_label, num, setting_label, settings_fields, steps_of, unresolved
from styles import svg_dash

HERE = os.path.dirname(os.path.abspath(__file__))


def number(x):
    """A float for JSON: NaN and infinities (which JSON cannot hold) as null."""
    return x if isinstance(x, (int, float)) and math.isfinite(x) else None


def inline(text):
    """Markdown's inline code and bold as HTML, the rest escaped."""
    text = html.escape(text, quote=False)
    text = re.sub(r"`([^`]*)`", r"<code>\1</code>", text)
    return re.sub(r"\*\*([^*]*)\*\*", r"<b>\1</b>", text)


def table_html(lines):
    """A markdown table (as report.py writes them) as an HTML table."""
    def cells(line):
        # Split at the '|' that end cells, not at an escaped one (rows.md_cell), then unescape.
        found = [c.strip() for c in re.findall(r"((?:\\.|[^|\\])*)\|", line.strip()[1:])]
        return [re.sub(r"\\(.)", r"\1", c) for c in found]

    head, align = cells(lines[0]), cells(lines[1])
    right = [a.endswith(":") for a in align]
    out = ["<table><thead><tr>" + "".join(f"<th>{inline(c)}</th>" for c in head) + "</tr></thead><tbody>"]
    for line in lines[2:]:
        tds = [("<td class=\"num\">" if i < len(right) and right[i] else "<td>") + inline(c) + "</td>"
               for i, c in enumerate(cells(line))]
        out.append("<tr>" + "".join(tds) + "</tr>")
    return "\n".join(out + ["</tbody></table>"])


# The numbers of a summary row the answer reads, in the order page.py writes them.
ROW_FIELDS = ["family", "setting", "failed", "unresolved", "err_median", "err_p95", "cpu", "cost", "imp_median",
              "imp_p95"]


def slug(title):
    return re.sub(r"[^a-z0-9]+", "-", title.lower()).strip("-")


class Page:
    def __init__(self, title):
        self.title = title
        self.sections = []  # (id, title, html)
        self.data = {}

    def section(self, title, body):
        self.sections.append((slug(title), title, body))

    def table(self, title, lines):
        self.section(title, table_html(lines))

    def answer(self, summary, scopes, impacting):
        """The chooser and the live answer table: every summary row with what the rule reads
        (answer.cheapest, by the one rule of robust.py) and what the answer shows, and the scopes of the markdown table,
        then each family as a scope of its own."""
        # Compact: each setting once (its label, whether it is a time-stepper), each row a list
        # of its family and setting indices and the numbers the rule reads (ROW_FIELDS).
        # Each setting names its line (its solver and variant, its settings apart from the step)
        # and how fine its step is, which the one rule (robust.py, page.js's robustErrors) reads.
        settings, index, lines = [], {}, {}
        families = list(dict.fromkeys(r["family"] for r in summary))
        family_index = {f: i for i, f in enumerate(families)}
        rows = []
        for r in summary:
            setting = (r["solver"], r["variant"], r["settings"])
            if setting not in index:
                index[setting] = len(settings)
                rest, fineness = robust.step_split(settings_fields(r))
                line = lines.setdefault((r["solver"], r["variant"], rest), len(lines))
                settings.append(dict(label=answer.answer_label(r), time_stepper=not answer.is_event_driven(r),
                                     line=line, fineness=fineness))
            imp = (impacting or {}).get((r["family"], *setting), {})
            rows.append([family_index[r["family"]], index[setting], int(r["failed"]), unresolved(r),
                         number(num(r, "err_median")), number(num(r, "err_p95")), number(num(r, "cpu_median_s")),
                         answer.cost_cell(r), number(imp.get("err_median", float("nan"))),
                         number(imp.get("err_p95", float("nan")))])
        single = {tuple(s["families"]) for s in scopes}
        extra = [dict(name=f"family {f}", families=[f], time_steppers_only=False) for f in families
                 if (f,) not in single]
        self.data["answer"] = dict(families=families, settings=settings, fields=ROW_FIELDS, rows=rows,
                                   scopes=scopes + extra, table_scopes=len(scopes),
                                   targets=answer.TARGETS, measures=[list(m) for m in answer.ERRORS],
                                   impacting=impacting is not None, all=[answer.ALL, answer.ALL_TIME_STEPPERS])
        self.section("Which setting for which accuracy", (
            "<p>Choose where and how accurately: the cheapest setting of the study that meets the target on every "
            "family of the choice, with no failed or unresolved run, and so does every finer step of its solver "
            "and variant (a lucky coarse step whose finer neighbours fail is never the answer), computed here from "
            "the study's rows by the rule of the markdown report.</p>"
            "<div class=\"chooser\"><label>scene <select id=\"chooser-scope\"></select></label>"
            "<label>target <select id=\"chooser-target\"></select></label>"
            "<label>error <select id=\"chooser-measure\"></select></label></div>"
            "<div class=\"answer\" id=\"chooser-answer\"><div>cheapest setting: <b id=\"chooser-setting\"></b></div>"
            "<div>CPU per run (us): <span id=\"chooser-cost\"></span>, set by family <span id=\"chooser-family\">"
            "</span></div><div>error on the worst family: <span id=\"chooser-error\"></span></div></div>"
            "<h3>Every scene and target</h3><div id=\"answer-tables\"></div>"))

    def styles(self, styles):
        """Each configuration's colour and dash (wp.setting_styles), as the figures draw it."""
        self.data["styles"] = {label: dict(color=st["color"], dash=svg_dash(st["dash"])) for label, st in styles.items()}

    def diagrams(self, summary, panels_of):
        """The work-precision diagrams: per family, a series per configuration (its settings
        over N, cheapest first), grouped and ordered as the figures' panels (wp.panels_of)."""
        families = {}
        for family, frows in by_family(summary).items():
            lines, panels = panels_of(frows)
            out = []
            for group, label in ((g, lb) for g, labels in panels.items() for lb in labels):
                srows = lines[label]
                out.append(dict(name=label, group=group, points=[
                    dict(setting=setting_label(r), n=steps_of(r), cpu=number(num(r, "cpu_median_s")),
                         cost=answer.cost_cell(r), err_median=number(num(r, "err_median")),
                         err_p95=number(num(r, "err_p95")), failed=int(r["failed"]), runs=int(r["points"]))
                    for r in srows]))
            families[family] = out
        self.data["diagrams"] = families
        self.section("Work-precision diagrams", (
            "<p>Relative Pi1 error against median CPU time per run over the points of a family: a line per "
            "configuration over its step counts N. Hover a point for its setting, N, error and cost; click a "
            "legend entry to grey its line out or back, a group's name to show that group alone against the others "
            "in grey. Hollow: some runs failed. Errors below 1e-13 are round-off and drawn at it; the thick grey "
            "band is the Pareto front of the lines shown.</p>"
            "<div class=\"controls\"><label>family <select id=\"wp-family\"></select></label>"
            "<label>error <select id=\"wp-measure\"></select></label>"
            "<button id=\"wp-all\" type=\"button\">show every group</button></div>"
            "<div id=\"wp-chart\" class=\"chart\"></div><div id=\"wp-legend\" class=\"legend\"></div>"))

    def spectra(self, points, n, panel_of, panel_rank):
        """The spectra at N = n over the truth: per family, a panel per (pulse, Pi5), its lines
        in the order of the figures' panels (panel_rank)."""
        truth = {}
        for r in points:
            truth.setdefault(r["point"], r)
        families = {}
        for family, frows in by_family(points).items():
            panels = []
            by_panel = defaultdict(list)
            for r in frows:
                by_panel[(r["pulse"], r.get("pi5", ""))].append(r)
            for pulse, pi5 in sorted(by_panel, reverse=True):
                prows = by_panel[(pulse, pi5)]
                refs = sorted({r["point"]: truth[r["point"]] for r in prows}.values(), key=lambda r: num(r, "pi2"))
                lines = [dict(name="reference", kind="reference", points=[[number(num(r, "pi2")), number(num(r, "pi1"))]
                                                                          for r in refs if r["status"] == "ok"]),
                         dict(name="no contact", kind="free", points=[
                             [number(num(r, "pi2")), number(num(r, "pi1_no_contact"))] for r in refs])]
                by_config = defaultdict(list)
                for r in prows:
                    if truth[r["point"]] is not r and steps_of(r) in (None, n) and r["status"] == "ok":
                        by_config[config_label(r)].append(r)
                for label in sorted(by_config, key=lambda lb: (panel_rank(panel_of(by_config[lb][0])), lb)):
                    crows = sorted(by_config[label], key=lambda r: num(r, "pi2"))
                    lines.append(dict(name=label, kind="series", group=panel_of(crows[0]), points=[
                        [number(num(r, "pi2")), number(num(r, "pi1"))] for r in crows]))
                panels.append(dict(title=f"{pulse}" + (f", Pi5 = {pi5}" if pi5 else ""), lines=lines))
            families[family] = panels
        self.data["spectra"] = dict(n=n, families=families, x="Pi2 = w0/w_p", y="Pi1")
        self.section("Spectra", (
            f"<p>Pi1 of body 0 against Pi2 at N = {n}: the reference (black, rigid contact solved 100x tighter), "
            "the same case with no contact (dashed grey) and each configuration (those without a step at their "
            "one setting). Hover a point for its values; click a legend entry to hide or show it.</p>"
            "<div class=\"controls\"><label>family <select id=\"spectra-family\"></select></label></div>"
            "<div id=\"spectra-charts\" class=\"charts\"></div><div id=\"spectra-legend\" class=\"legend\"></div>"))

    def curves(self, rows):
        """A spectrum's rows: per family, a panel per (pulse, directivity), a line per case
        label (what varies besides Pi2), the no-contact lines dashed."""
        from rows import CASE_KEYS

        families = {}
        for family, frows in by_family(rows).items():
            keys = [k for k in CASE_KEYS if k not in ("pulse", "directivity") and len({r.get(k) for r in frows}) > 1]
            panels = []
            by_panel = defaultdict(list)
            for r in frows:
                by_panel[(r["pulse"], r["directivity"])].append(r)
            for pulse, directivity in sorted(by_panel, reverse=True):
                prows = sorted(by_panel[(pulse, directivity)], key=lambda r: num(r, "pi2"))
                by_case = defaultdict(list)
                for r in prows:
                    by_case[", ".join(f"{k}={r.get(k, '')}" for k in keys) or family].append(r)
                lines = []
                for label, crows in by_case.items():
                    lines.append(dict(name=label, kind="series", group=config_label(crows[0]), points=[
                        [number(num(r, "pi2")), number(num(r, "pi1"))] for r in crows if r["status"] == "ok"]))
                    lines.append(dict(name=f"{label}: no contact", kind="free", points=[
                        [number(num(r, "pi2")), number(num(r, "pi1_no_contact"))] for r in crows]))
                panels.append(dict(title=f"{pulse} pulse, {directivity}", lines=lines))
            families[family] = panels
        self.data["spectra"] = dict(n=None, families=families, x="Pi2 = w0/w_p", y="Pi1")
        self.section("Spectra", (
            "<p>Pi1 of body 0 against Pi2 per family, a panel per pulse and directivity, the same case with no "
            "contact dashed. Hover a point for its values; click a legend entry to hide or show it.</p>"
            "<div class=\"controls\"><label>family <select id=\"spectra-family\"></select></label></div>"
            "<div id=\"spectra-charts\" class=\"charts\"></div><div id=\"spectra-legend\" class=\"legend\"></div>"))

    def verdicts(self, summary, checks, label_of):
        """The stress checks as a table: a row per setting, a column per family and check."""
        families = list(dict.fromkeys(r["family"] for r in summary))
        settings = list(dict.fromkeys(label_of(r) for r in summary))
        cells = {(label_of(r), r["family"]): r for r in summary}
        head = "<tr><th rowspan=\"2\">setting</th>" + "".join(
            f"<th colspan=\"{len(checks)}\">{html.escape(f)}</th>" for f in families) + "</tr><tr>" + "".join(
            f"<th title=\"{c}\">{c[0].upper()}</th>" for _ in families for c in checks) + "</tr>"
        body = []
        for s in settings:
            tds = []
            for f in families:
                r = cells.get((s, f))
                for c in checks:
                    v = r[c] if r else ""
                    tds.append(f"<td class=\"verdict {v or 'none'}\" title=\"{html.escape(f)}: {c}: "
                               f"{v or 'nothing to judge'}\"></td>")
            body.append(f"<tr><th class=\"setting\">{html.escape(s)}</th>{''.join(tds)}</tr>")
        self.section("Stress checks", (
            "<p>Green ✓ pass, red ✗ fail, grey nothing to judge; " + ", ".join(f"{c[0].upper()}: {c}" for c in checks)
            + ". Hover a cell for its family and check.</p><div class=\"wide\"><table class=\"verdicts\">"
            + head + "".join(body) + "</table></div>"))

    def provenance(self, lines):
        items = [inline(line[2:]) for line in lines if line.startswith("- ")]
        self.section("Provenance", "<ul>" + "".join(f"<li>{i}</li>" for i in items) + "</ul>")

    def write(self, path):
        """The page, through a temporary file. The data is JSON inside a script element: "</"
        is written "<\\/" so that no value can end the element."""
        with open(os.path.join(HERE, "page.css")) as f:
            css = f.read()
        with open(os.path.join(HERE, "page.js")) as f:
            js = f.read()
        data = json.dumps(self.data, separators=(",", ":"), allow_nan=False).replace("</", "<\\/")
        nav = " · ".join(f"<a href=\"#{i}\">{html.escape(t)}</a>" for i, t, _ in self.sections)
        body = "\n".join(f"<section id=\"{i}\"><h2>{html.escape(t)}</h2>\n{b}\n</section>" for i, t, b in self.sections)
        text = (f"<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>{html.escape(self.title)}"
                f"</title>\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<style>\n{css}"
                f"</style></head>\n<body>\n<h1>{html.escape(self.title)}</h1>\n<nav>{nav}</nav>\n{body}\n"
                f"<div id=\"tooltip\" role=\"tooltip\"></div>\n"
                f"<script type=\"application/json\" id=\"report-data\">{data}</script>\n<script>\n{js}</script>\n"
                "</body></html>\n")
        with open(path + ".tmp", "w") as f:
            f.write(text)
        os.replace(path + ".tmp", path)
