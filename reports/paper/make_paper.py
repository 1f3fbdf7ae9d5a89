#!/usr/bin/python3
"""Writes reports/paper/README.md and its figures: whether the event-driven reference
reproduces the findings of Dimitrakopoulos, Makris & Kappos (2009). Run by
scripts/paper.sh; uses Debian's python3-matplotlib.

    reports/paper/make_paper.py PAPER.csv PAPER_REPORT.csv --poundbench build/poundbench --out reports/paper

PAPER.csv and PAPER_REPORT.csv are `poundbench spectrum --solver event-driven` over
cases/sets/paper.toml and cases/sets/paper-report.toml. The binary runs the two time
histories of Fig. 6. Every number of the text is computed here from those rows.
"""

import argparse
import csv
import json
import math
import os
import subprocess
import sys
import re
import tempfile
from dataclasses import dataclass

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # reports/

import numpy as np  # noqa: E402

import analysis  # noqa: E402
import plots  # noqa: E402
from analysis import NEAR, select  # noqa: E402
import provenance  # noqa: E402
from make_report import footer  # noqa: E402
from rows import load, write_page  # noqa: E402

NO_CONTACT_GAP = 1e6  # Pi3 of the no-contact history: a gap that never closes
G = 9.81  # m/s², for the pulse amplitudes of Fig. 3
STIFFNESS = "THE INFLUENCE OF THE OSCILLATORS' STIFFNESS RATIO ON THE RESPONSE"


def g(x):
    return f"{x:.3g}"


def pct(part, whole):
    return f"{100 * part / whole:.0f}%" if whole else "n/a"


def span(values):
    lo, hi = g(min(values)), g(max(values))
    return lo if lo == hi else f"{lo}–{hi}"


def listed(values):
    return ", ".join(g(v) for v in values)


def table(header, rows):
    return ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)] + \
        ["| " + " | ".join(str(v) for v in r) + " |" for r in rows] + [""]


def flexible(c):
    return float(c["pi5"]) < 1


def pi5_spectra(fam, number):
    """The spectra of Fig. 4, 5 (flexible and stiff families) or 7."""
    if number == 7:
        return fam["fig7"]
    return fam[f"fig{number}-flexible"] + fam[f"fig{number}-stiff"]


# ---------------------------------------------------------------- Fig. 3

def fig3_section(fam, out):
    by_amplitude, by_duration = fam["fig3"], fam["fig3-duration"]
    spread, at = analysis.largest_spread(by_amplitude)
    spread_nc, _ = analysis.largest_spread(by_amplitude, "pi1_nc")
    spread_all, at_all = analysis.largest_spread(by_amplitude + by_duration)
    spread_all_nc, _ = analysis.largest_spread(by_amplitude + by_duration, "pi1_nc")
    figure = plots.fig3(by_amplitude, by_duration, f"all {len(by_amplitude + by_duration)} curves drawn; largest "
                        f"relative spread\nbetween them: {spread_all:.0e} with contact (heavy), {spread_all_nc:.0e} "
                        "without (light)", out)
    a_p = sorted(float(c["a_p"]) for c in by_amplitude)
    tp = {2 * math.pi / float(c["w_p"]) for c in by_amplitude}
    tp_other = sorted(2 * math.pi / float(c["w_p"]) for c in by_duration)
    impacted = int((by_amplitude[0].impacts > 0).sum())
    agrees = spread_all < analysis.UNCHANGED
    text = [
        "## Fig. 3: self-similarity", "", f"![Fig. 3]({figure})", "",
        f"The asymmetric row of three under a cosine pulse of T_p = {listed(tp)} s at a_p = "
        f"{', '.join(f'{a:.3g} m/s² ({a / G:.2g} g)' for a in a_p)}, and at a_p = "
        f"{listed({float(c['a_p']) for c in by_duration})} m/s² with T_p = {listed(tp_other)} s (`fig3-duration` "
        "of `cases/sets/paper-report.toml`), all at Pi3 = 0.5. In metres (left) the spectra scale with the "
        f"pulse's length a_p T_p² / 4π² (a factor {g(a_p[-1] / a_p[0])} between the smallest and largest "
        "amplitude) and the durations shift them along T0; in Pi terms (right) they lie exactly on each other, "
        "which is the finding: the curves are drawn in decreasing widths, the other durations dashed, so that "
        "each one shows under the others. The "
        "largest relative spread (max - min) / max of Pi1 between the amplitudes at one Pi2 is "
        f"**{spread:.1e}** (at Pi2 = {g(at)}; no contact: {spread_nc:.1e}); with the other durations as well, "
        f"{spread_all:.1e} (at Pi2 = {g(at_all)}). Impacts occur at {impacted} of the {len(by_amplitude[0].x)} "
        "Pi2 points. The paper's self-similarity (\"IMPLEMENTATION OF DIMENSIONAL ANALYSIS\") "
        f"{'holds' if agrees else 'does not hold'} for this pounding row, impacts included (the test: a spread "
        f"below {analysis.UNCHANGED:g}; the reference's own error is about 1e-9).", ""]
    return text, Claim("spectra for any a_p and T_p collapse onto one curve in Pi terms (Fig. 3)",
                       "IMPLEMENTATION OF DIMENSIONAL ANALYSIS",
                       f"largest relative spread of Pi1 {spread_all:.1e} over {len(a_p)} amplitudes and "
                       f"{len(tp) + len(tp_other)} durations", agrees,
                       f"the {len(by_amplitude + by_duration)} pulses' spectra differ by {spread_all:.0e} at most")


# ---------------------------------------------------------------- Figs 4, 5: stiffness ratio

def figs_4_5_section(fam, out):
    text = []
    for number, direc in ((4, "normal"), (5, "reverse")):
        spectra = pi5_spectra(fam, number)
        figure = plots.pi5_spectra(spectra, f"Fig. {number}: pair, Π₆ = 1, Π₃ = 0.5, {direc} directivity",
                                   f"fig{number}-{direc}", out)
        cells = []
        for side, name in ((True, "flexible"), (False, "stiff")):
            c = max((c for c in spectra if flexible(c) == side), key=lambda c: c.ratio.max())
            i = int(np.argmax(c.ratio))
            cells.append(f"{g(c.ratio[i])} times on the {name} side ({c['pulse']}, Pi5 = {c['pi5']}, "
                         f"Pi2 = {g(c.x[i])})")
        pi5s = sorted({float(c["pi5"]) for c in spectra})
        text += [f"## Fig. {number}: stiffness ratio, {direc} directivity", "", f"![Fig. {number}]({figure})", "",
                 f"Pi1 of body 0 against Pi2 for Pi5 = {listed(p for p in pi5s if p < 1)} (flexible body 0, "
                 f"left) and {listed(p for p in pi5s if p > 1)} (stiff, right); dashed: no contact (body 0 "
                 "alone, the same for every Pi5), drawn on top so that it shows where contact changes nothing. "
                 f"Contact amplifies Pi1 at most {cells[0]} and {cells[1]}.", ""]
    return text


def pi5_limit_section(fam, out):
    """Claim 2: the largest |Pi1 / Pi1_nc - 1| over Pi2 shrinks to 0 as Pi5 -> 1."""
    table_rows, plotted, monotone, nil, touched, steps = [], [], True, {}, set(), []
    for pulse in plots.PULSES:
        by_pi5 = {float(c["pi5"]): c for c in select(pi5_spectra(fam, 4) + fam["pi5-near-1"], pulse=pulse)}
        dev = {p: float(np.max(np.abs(c.ratio - 1))) for p, c in by_pi5.items()}
        nil[pulse] = {p for p in dev if dev[p] < analysis.UNCHANGED}
        touched |= {p for p, c in by_pi5.items() if (c.impacts > 0).any()}
        for side in (sorted(p for p in dev if p < 1), sorted((p for p in dev if p > 1), reverse=True)):
            monotone &= all(dev[b] <= dev[a] for a, b in zip(side, side[1:]))
            last = [p for p in side if p not in nil[pulse]][-1:]  # the closest to 1 still changed by contact
            steps.append(f"{pulse} {dev[side[0]]:.2g} at Pi5 = {g(side[0])}"
                         + "".join(f", {dev[p]:.2g} at {g(p)}" for p in last))
        for p, c in sorted(by_pi5.items()):
            plotted.append((pulse, p, float(c.ratio.max()), float(c.ratio.min())))
            table_rows.append([pulse, f"{p:.4g}", g(c.ratio.max()), g(c.ratio.min()), f"{dev[p]:.2g}",
                               int((c.impacts > 0).sum())])
    figure = plots.pi5_limit(plotted, out)
    pi5s = sorted({r[1] for r in plotted})
    untouched = [p for p in pi5s if p not in touched]
    unchanged = [p for p in pi5s if p in touched and all(p in ps for ps in nil.values())]
    closest = min(pi5s, key=lambda p: abs(math.log(p)))
    agrees = monotone and all(closest in ps for ps in nil.values())
    text = [
        "### Pi5 -> 1: the response tends to the no-contact one", "", f"![Pi5 limit]({figure})", "",
        "The Fig. 4 spectra and the `pi5-near-1` family (Pi5 near 1 from both sides, "
        "`cases/sets/paper-report.toml`): the largest and smallest Pi1 / Pi1_nc over Pi2 in [0.1, 10] for each "
        f"Pi5. Contact's largest effect on Pi1 {'shrinks' if monotone else 'does not shrink'} monotonically "
        f"from either side as Pi5 -> 1 ({'; '.join(steps)}). At Pi5 = {listed(untouched) or 'none'} the bodies "
        f"never touch within t_end; at {listed(unchanged) or 'none'} they touch, under both pulses, but Pi1 "
        f"changes by less than {analysis.UNCHANGED:g} at every Pi2. The paper's statement "
        f"(\"{STIFFNESS}\") {'holds' if agrees else 'does not hold'} for both pulses.", ""]
    text += table(["pulse", "Pi5", "largest Pi1/Pi1_nc", "smallest Pi1/Pi1_nc", "largest abs(Pi1/Pi1_nc - 1)",
                   "points with impacts (of 200)"], table_rows)
    return text, Claim("as Pi5 -> 1 (Pi6 = 1) the response tends to the no-contact one", STIFFNESS,
                       f"largest abs(Pi1/Pi1_nc - 1) over Pi2: {'; '.join(steps)}; below {analysis.UNCHANGED:g} at "
                       f"Pi5 = {listed(sorted(set.intersection(*nil.values())))}", agrees,
                       f"contact's effect {'shrinks' if monotone else 'does not shrink'} monotonically; below "
                       f"{analysis.UNCHANGED:g} at Pi5 = {listed(sorted(set.intersection(*nil.values())))}")


def local_maxima_section(fam):
    """Claim 3: the flexible body's spectrum has a local maximum near Pi2 = Pi5."""
    low = fam["flexible-low-pi2"]
    lines, hits = [], {p: 0 for p in plots.PULSES}
    for number in (4, 5):
        for c in (c for c in pi5_spectra(fam, number) if flexible(c)):
            pi5 = float(c["pi5"])
            extension = select(low, pulse=c["pulse"], directivity=c["directivity"], pi5=c["pi5"])
            if extension:
                c = analysis.joined(extension[0], c)
            i = analysis.nearest_local_maximum(c, pi5)
            if i is None:
                lines.append([f"Fig. {number}", c["pulse"], g(pi5), "none", "", "", "no"])
                continue
            hit = analysis.near(c.x[i], pi5)
            hits[c["pulse"]] += hit
            lines.append([f"Fig. {number}", c["pulse"], g(pi5), g(c.x[i]), g(c.x[i] / pi5), g(c.ratio[i]),
                          "yes" if hit else "no"])
    per_pulse = len(lines) // len(plots.PULSES)
    free = {p: analysis.peak(select(pi5_spectra(fam, 4), pulse=p)[0], "pi1_nc") for p in plots.PULSES}
    notes = []
    for pulse, (x, _, edge) in free.items():
        close = sorted({float(r[2]) for r in lines if r[1] == pulse and analysis.near(x, float(r[2]))})
        notes.append(f"under the {pulse} pulse the no-contact spectrum peaks at Pi2 = {g(x)}"
                     + (" (the end of the grid)" if edge else "")
                     + (f", within a factor {NEAR} of Pi5 = {listed(close)}, so there a maximum near Pi2 = Pi5 "
                        "cannot be told from body 0's own" if close else ""))
    text = [
        "### Local maximum of the flexible body at Pi2 = Pi5", "",
        f"The paper (\"{STIFFNESS}\") finds the flexible body's maxima at the resonance of its stiffer "
        "neighbour, Pi2 = Pi5. For each flexible spectrum of Figs 4 and 5: the interior local maximum of Pi1 "
        "nearest to Pi2 = Pi5 (a grid point higher than the one before and not lower than the one after), and "
        f"whether it lies within a factor {NEAR} of Pi5. Where Pi2 = Pi5 is the first point of the paper's grid "
        "(Pi5 = 0.1) the spectrum is extended below it (`flexible-low-pi2` of `cases/sets/paper-report.toml`, "
        f"Pi2 from {g(min(c.x[0] for c in low))}).", ""]
    text += table(["figure", "pulse", "Pi5", "nearest local max at Pi2", "its Pi2 / Pi5", "Pi1/Pi1_nc there",
                   f"within x{NEAR}"], lines)
    text += [f"A maximum near Pi2 = Pi5: {hits['cosine']} of {per_pulse} spectra under the cosine pulse, "
             f"{hits['sine']} of {per_pulse} under the sine pulse (for which the paper itself says its trends are "
             f"hard to see). For comparison, {'; '.join(notes)}.", ""]
    total = sum(hits.values())
    return text, Claim("the flexible body's spectrum has a local maximum near Pi2 = Pi5 (Figs 4, 5)", STIFFNESS,
                       f"within x{NEAR} of Pi5 on {hits['cosine']} of {per_pulse} cosine and {hits['sine']} of "
                       f"{per_pulse} sine spectra", True if total == len(lines) else "partly" if total else False,
                       f"{hits['cosine']} of {per_pulse} cosine, {hits['sine']} of {per_pulse} sine spectra")


# ---------------------------------------------------------------- Fig. 6: time histories

def run_history(pb, row, pi3, path):
    """`poundbench run` on the case of a result row with gap Pi3, its history to path:
    (the run's JSON summary, the history's columns)."""
    flags = ["--scene", row["scene"], "--pulse", row["pulse"], "--directivity", row["directivity"],
             "--pi2", row["pi2"], "--pi3", str(pi3), "--eps", row["eps"], "--pi5", row["pi5"], "--pi6", row["pi6"],
             "--xi", row["xi"], "--n-free", row["n_free"], "--a-p", row["a_p"], "--w-p", row["w_p"]]
    out = subprocess.run([pb, "run", *flags, "--history", path, "--samples", "4000", "--json"],
                         capture_output=True, text=True, check=True).stdout
    with open(path, newline="") as f:
        data = list(csv.DictReader(f))
    return json.loads(out), {k: np.array([float(r[k]) for r in data]) for k in data[0]}


def fig6_section(fam, pb, out):
    """Two points of the Fig. 4 cosine spectra where contact amplifies body 0 most."""
    spectra = pi5_spectra(fam, 4)
    panels, described, amplified = [], [], []
    with tempfile.TemporaryDirectory() as tmp:
        for name, pi5 in (("flexible", "0.5"), ("stiff", "2")):
            c = select(spectra, pulse="cosine", pi5=pi5)[0]
            i = int(np.argmax(c.ratio))
            row = c.rows[i]
            run, hist = run_history(pb, row, row["pi3"], os.path.join(tmp, "contact.csv"))
            free_run, free = run_history(pb, row, NO_CONTACT_GAP, os.path.join(tmp, "free.csv"))
            for got, want in ((run["pi1"], c.pi1[i]), (free_run["pi1"], c.pi1_nc[i])):
                if abs(got - want) > 1e-9 * want:
                    sys.exit(f"make_paper.py: a Fig. 6 run gives Pi1 = {got}, its spectrum row {want}")
            impacts = analysis.impact_times(hist)
            tp = 2 * math.pi / float(row["w_p"])
            before = impacts[impacts <= run["t_max"]]
            panels.append(dict(title=f"{name} body 0: cosine pulse, normal, Π₅ = {pi5}, Π₂ = {g(c.x[i])}: "
                               f"Π₁ = {g(run['pi1'])} with contact, {g(free_run['pi1'])} without",
                               contact=hist, free=free, impacts=impacts, tp=tp,
                               length=float(row["a_p"]) / float(row["w_p"]) ** 2))
            amplified.append(run["pi1"] > (1 + analysis.NO_EFFECT) * free_run["pi1"])
            described.append(
                f"the {name} body 0 (Pi5 = {pi5}) at Pi2 = {g(c.x[i])}: Pi1 = {g(run['pi1'])} against "
                f"{g(free_run['pi1'])} without contact ({g(run['pi1'] / free_run['pi1'])} times); "
                f"{run['impacts']} impacts ({len(impacts)} seen between the samples), the maximum at t = "
                f"{g(run['t_max'] / tp)} T_p "
                + (f"follows {len(before)} of them, the last at t = {g(before[-1] / tp)} T_p" if len(before)
                   else "comes before the first one"))
    figure = plots.histories(panels, out)
    return ["## Fig. 6: time histories where contact amplifies", "", f"![Fig. 6]({figure})", "",
            "The points are chosen by a rule: on the Fig. 4 cosine spectra of Pi5 = 0.5 (flexible) and Pi5 = 2 "
            "(stiff), the Pi2 where Pi1 / Pi1_nc is largest. They are " + "; and ".join(described) + ". "
            "The no-contact history is the same case run with a gap that never closes (Pi3 = "
            f"{NO_CONTACT_GAP:.0e}); both runs reproduce their spectrum row's Pi1 and Pi1_nc to 1e-9 "
            "(the script checks it). Impacts are marked where the gap rate turns from closing to opening "
            "between two samples. "
            + (f"As in the paper's Fig. 6 (\"{STIFFNESS}\"), contact makes both a flexible and a stiff body "
               "swing further than they would alone, at different excitation frequencies." if all(amplified) else
               "Contact does not amplify both bodies here, unlike the paper's Fig. 6."), ""]


# ---------------------------------------------------------------- Fig. 7 and the three regions

def fig7_section(fam, out):
    figure = plots.pi5_spectra(pi5_spectra(fam, 7), "Fig. 7: symmetric row3 (body 2 = body 1), "
                               "Π₆ = Π₈ = 1, Π₃ = 0.5", "fig7-two-sided", out)
    return ["## Fig. 7: two-sided pounding", "", f"![Fig. 7]({figure})", "",
            "Body 0 between two identical neighbours (Pi7 = Pi5, Pi8 = Pi6 = 1), in the layout of Figs 4 and 5. "
            "The row is its own mirror image, so the case set runs normal directivity only. The numbers are "
            "compared with one-sided pounding in the two sections below.", ""]


def regions_section(fam, out):
    """Claim 4: three spectral regions, for the flexible and the stiff body."""
    groups = [(f"Fig. {n}: {name}", sorted(pi5_spectra(fam, n), key=lambda c: (plots.PULSES.index(c["pulse"]),
                                                                                float(c["pi5"]))))
              for n, name in ((4, "pair, normal"), (5, "pair, reverse"), (7, "symmetric row3"))]
    figure = plots.region_map(groups, out)
    lines, score, misses = [], {}, {}
    for title, curve_list in groups:
        fig_name = title.split(":")[0]
        for c in curve_list:
            body = "flexible" if flexible(c) else "stiff"
            ok, why = analysis.three_regions(c, flexible(c))
            score.setdefault((fig_name, body), [0, 0])
            score[(fig_name, body)][0] += ok
            score[(fig_name, body)][1] += 1
            if not ok:
                misses.setdefault(why, []).append(f"{fig_name} {c['pulse']} {c['pi5']}")
            found = analysis.regions(c)
            cells = ["; ".join(f"{g(r.lo)}–{g(r.hi)}" for r in found if r.kind == kind)
                     for kind in ("amplified", "deamplified", "none")]
            lines.append([fig_name, c["pulse"], c["pi5"], *cells, "yes" if ok else f"no: {why}"])
    agree, total = sum(s[0] for s in score.values()), sum(s[1] for s in score.values())
    located = []
    for title, curve_list in groups:
        for body in ("flexible", "stiff"):
            for pulse in plots.PULSES:
                found = [analysis.regions(c) for c in curve_list
                         if c["pulse"] == pulse and (body == "flexible") == flexible(c)]
                cells = []
                for kind in ("amplified", "deamplified"):
                    main = [r for r in (analysis.main_region(f, kind) for f in found) if r]
                    cells.append(f"{g(min(r.lo for r in main))}–{g(max(r.hi for r in main))} ({len(main)})" if main
                                 else "none")
                far = [f[-1].lo if body == "flexible" else f[0].hi for f in found
                       if (f[-1] if body == "flexible" else f[0]).kind == "none"]
                cells.append((f"above {span(far)}" if body == "flexible" else f"below {span(far)}") + f" ({len(far)})"
                             if far else "none")
                located.append([title.split(":")[0], body, pulse, *cells])
    text = [
        "## Three spectral regions", "", f"![regions]({figure})", "",
        f"The paper (\"{STIFFNESS}\", for one- and two-sided pounding) finds three regions along Pi2: one "
        "where contact amplifies the response, one near Pi2 = 1 where it deamplifies it, and one where it has "
        "virtually no effect; the amplified region lies at low Pi2 for the flexible body and at high Pi2 for "
        f"the stiff body. Rule used here: a point is amplified when Pi1 / Pi1_nc > {1 + analysis.NO_EFFECT:g}, "
        f"deamplified when it is < {1 - analysis.NO_EFFECT:g}, otherwise no effect; a region is a run of at "
        f"least {analysis.MIN_RUN} consecutive grid points of one kind. A spectrum agrees when its longest "
        "amplified region lies below (flexible) or above (stiff) its longest deamplified region, that region "
        f"reaches to within a factor {NEAR} of Pi2 = 1, and the far end of the grid (Pi2 = 10 flexible, 0.1 "
        "stiff) is a no-effect region.", ""]
    text += table(["figure", "body 0", "spectra with the three regions"],
                  [[k[0], k[1], f"{s[0]} of {s[1]}"] for k, s in score.items()])
    text += [f"{agree} of {total} spectra show the three regions in the paper's order. The others: "
             + "; ".join(f"{why}: {', '.join(which)}" for why, which in misses.items()) + ".", "",
             "Where the regions lie, per figure, body and pulse: the Pi2 span covered by the longest amplified "
             "and the longest deamplified region of each of the four spectra, and where the no-effect region "
             "at the far end of the grid begins (flexible) or ends (stiff); in brackets, how many of the four "
             "spectra have that region.", ""]
    text += table(["figure", "body 0", "pulse", "amplified", "deamplified", "no effect at the far end"], located)
    text += [f"Pi2 ranges of every region of every spectrum (runs of at least {analysis.MIN_RUN} points):", ""]
    text += table(["figure", "pulse", "Pi5", "amplified", "deamplified", "no effect", "three regions"], lines)
    return text, Claim("three regions: amplification (flexible: low Pi2, stiff: high Pi2), deamplification near "
                       "Pi2 = 1, no effect", STIFFNESS,
                       f"{agree} of {total} spectra of Figs 4, 5, 7 (" +
                       ", ".join(f"{k[0]} {k[1]} {s[0]}/{s[1]}" for k, s in score.items()) + ")",
                       True if agree == total else "partly" if agree else False,
                       f"{agree} of {total} spectra of Figs 4, 5, 7")


def sided_section(fam):
    """Claim 5: one-sided (pair, Figs 4 and 5) against two-sided (row3, Fig. 7) pounding."""
    configs = [("one-sided normal", 4), ("one-sided reverse", 5), ("two-sided", 7)]
    spectra = {name: pi5_spectra(fam, n) for name, n in configs}
    pi5s = sorted({float(c["pi5"]) for c in spectra["two-sided"]})
    amp_rows, shift_rows, found = [], [], {}
    for pulse in plots.PULSES:
        for pi5 in pi5s:
            found[(pulse, pi5)] = per = {n: select(spectra[n], pulse=pulse, pi5=g(pi5))[0] for n, _ in configs}
            amp_rows.append([pulse, g(pi5)] + [f"{g(c.ratio.max())} / {g(c.pi1.max())}" for c in per.values()])
            free_x, _, free_edge = analysis.peak(per["two-sided"], "pi1_nc")
            cells = []
            for c in per.values():
                x, _, edge = analysis.peak(c)
                cells.append(f"{g(x)}{' (grid end)' if edge else ''}, x{g(x / free_x)}")
            shift_rows.append([pulse, g(pi5), f"{g(free_x)}{' (grid end)' if free_edge else ''}"] + cells
                              + [g(c.ratio.min()) for c in per.values()])

    def amp(pulse, pi5, name):
        return float(found[(pulse, pi5)][name].ratio.max())

    def smallest(key, name):
        return float(found[key][name].ratio.min())

    one_sided = ("one-sided normal", "one-sided reverse")
    flex = [k for k in found if k[1] < 1]
    stiff = [k for k in found if k[1] > 1]
    compare = {}  # one-sided directivity -> (two-sided less, equal, more) on the flexible spectra
    for one in one_sided:
        d = [amp(*k, "two-sided") / amp(*k, one) - 1 for k in flex]
        compare[one] = [sum(x < -1e-9 for x in d), sum(abs(x) <= 1e-9 for x in d), sum(x > 1e-9 for x in d)]
    more = [f"{k[0]} Pi5 = {g(k[1])}: {g(amp(*k, 'two-sided'))} against {g(amp(*k, one))} ({one})"
            for one in compare for k in flex if amp(*k, "two-sided") > (1 + 1e-9) * amp(*k, one)]
    stiff_ratio = [amp(*k, "two-sided") / amp(*k, "one-sided normal") for k in stiff]
    deeper = [k for k in stiff if smallest(k, "two-sided") <= min(smallest(k, n) for n in one_sided)]
    by_pulse = "; ".join(
        f"{p}: two-sided {span([amp(p, q, 'two-sided') for q in pi5s if q < 1])} against one-sided "
        f"{span([amp(p, q, 'one-sided normal') for q in pi5s if q < 1])} (normal) and "
        f"{span([amp(p, q, 'one-sided reverse') for q in pi5s if q < 1])} (reverse)" for p in plots.PULSES)
    peaks = {k: {n: analysis.peak(c) for n, c in per.items()} for k, per in found.items()}
    readable = [k for k in flex if not any(p[2] for p in peaks[k].values())]
    lower = [k for k in readable if peaks[k]["two-sided"][0] <= peaks[k]["one-sided normal"][0]]
    free_x = {k: analysis.peak(found[k]["two-sided"], "pi1_nc")[0] for k in readable}
    free_peaks = [(p, analysis.peak(found[(p, pi5s[0])]["two-sided"], "pi1_nc")) for p in plots.PULSES]
    shift = "; ".join(f"{k[0]} Pi5 = {g(k[1])}: no contact {g(free_x[k])}, one-sided normal "
                      f"{g(peaks[k]['one-sided normal'][0])}, two-sided {g(peaks[k]['two-sided'][0])}"
                      for k in readable)
    text = [
        "## One-sided against two-sided pounding", "",
        "\"COMPARISON OF ONE-SIDED AND TWO-SIDED POUNDING\": the paper finds that two-sided pounding amplifies "
        "the response much less, above all for flexible bodies, and suppresses a stiff body's response near "
        "its resonance more, while shifting the spectral peak as much as one-sided pounding does. Same Pi5, "
        "same pulse, Pi6 = 1; one-sided is the pair of Figs 4 (normal) and 5 (reverse), two-sided the "
        "symmetric row3 of Fig. 7.", "",
        "**Amplification**: the largest Pi1 / Pi1_nc over Pi2, then the largest Pi1 itself.", ""]
    text += table(["pulse", "Pi5"] + [n for n, _ in configs], amp_rows)
    text += [
        "**Period shift and suppression**: the Pi2 of the spectral peak (largest Pi1) and its ratio to the "
        "no-contact peak's Pi2, then the smallest Pi1 / Pi1_nc over Pi2 (the deepest suppression).", ""]
    text += table(["pulse", "Pi5", "no-contact peak"] + [f"peak, {n}" for n, _ in configs]
                  + [f"smallest ratio, {n}" for n, _ in configs], shift_rows)
    text += [
        "**Flexible body**: against one-sided pounding, two-sided pounding's largest Pi1 / Pi1_nc is "
        + "; ".join(f"lower on {c[0]}, equal (to 1e-9) on {c[1]} and higher on {c[2]} of {len(flex)} spectra "
                    f"({one})" for one, c in compare.items())
        + (f"; higher at {'; '.join(more)}" if more else "")
        + f". By pulse, {by_pulse}. "
        f"**Stiff body**: the two-sided amplification is {span(stiff_ratio)} times the one-sided (normal) one, "
        f"and its deepest suppression is at least as deep as one-sided on {len(deeper)} of {len(stiff)} spectra. "
        f"**Period shift**: a spectral peak inside the grid (not at an end) with and without contact exists on "
        f"{len(readable)} of {len(flex)} flexible spectra ({shift}); there the two-sided peak lies at the same or "
        f"a lower Pi2 than the one-sided (normal) one on {len(lower)} of {len(readable)}."
        + "".join(f" Under the {p} pulse the no-contact spectrum is largest at the grid's end Pi2 = {g(x)}, so no "
                  "shift can be read from it." for p, (x, _, edge) in free_peaks if edge), ""]
    return text, Claim("two-sided pounding amplifies a flexible body less than one-sided; the period shift is as "
                       "large", "COMPARISON OF ONE-SIDED AND TWO-SIDED POUNDING",
                       "largest Pi1/Pi1_nc of the flexible body two-sided against one-sided: "
                       + ", ".join(f"{c[0]} lower / {c[1]} equal / {c[2]} higher ({one.split()[-1]})"
                                   for one, c in compare.items())
                       + f" of {len(flex)}; peak at the same or lower Pi2 two-sided on {len(lower)} of "
                       f"{len(readable)} readable spectra",
                       True if not more and len(lower) == len(readable) else "partly" if lower or
                       any(c[0] for c in compare.values()) else False,
                       f"less than one-sided on {sum(c[0] for c in compare.values())}, more on "
                       f"{sum(c[2] for c in compare.values())} of {len(flex) * len(compare)} flexible spectra "
                       f"(normal and reverse); peak shift as large on {len(lower)} of {len(readable)}")


# ---------------------------------------------------------------- Figs 8, 9: mass ratio

def mass_section(fam, out):
    text = []
    for number, name in ((8, "stiff"), (9, "flexible")):
        spectra = fam[f"fig{number}"]
        pi5 = spectra[0]["pi5"]
        figure = plots.pi6_spectra(spectra, f"Fig. {number}: pair, {name} body 0 (Π₅ = {pi5}), "
                                            "Π₃ = 0.5, mass ratios Π₆ = m₀/m₁",
                                   f"fig{number}-mass-{name}", out)
        falling = rising = changed_total = points = 0
        widest = (1.0, "")
        for pulse in plots.PULSES:
            for direc in ("normal", "reverse"):
                panel = sorted(select(spectra, pulse=pulse, directivity=direc), key=lambda c: float(c["pi6"]))
                y = np.array([c.pi1 for c in panel])
                changed = np.abs(y / panel[0].pi1_nc - 1).max(axis=0) >= analysis.NO_EFFECT
                steps = np.diff(y, axis=0)
                points += len(panel[0].x)
                changed_total += int(changed.sum())
                falling += int(np.sum(changed & (steps <= 0).all(axis=0)))
                rising += int(np.sum(changed & (steps >= 0).all(axis=0)))
                spread = y.max(axis=0) / y.min(axis=0)
                j = int(np.argmax(spread))
                if spread[j] > widest[0]:
                    widest = (float(spread[j]), f"{pulse}, {direc}, Pi2 = {g(panel[0].x[j])}")
        other = changed_total - falling - rising
        pi6 = sorted(float(c["pi6"]) for c in select(spectra, pulse="sine", directivity="normal"))
        main = falling > max(rising, other)
        text += [f"## Fig. {number}: mass ratio, {name} body 0 (Pi5 = {pi5})", "", f"![Fig. {number}]({figure})", "",
                 f"Rows: pulses; columns: directivities; one line per Pi6 = m0/m1 in {listed(pi6)}. \"THE ROLE "
                 "OF m0/m1 RATIO\": the paper's main trend is that the heavier body responds less, with "
                 "counter-intuitive exceptions, and that the mass ratio matters even for comparable frequencies. "
                 f"Over the Pi2 points where contact changes Pi1 by at least {pct(analysis.NO_EFFECT, 1)} for some Pi6 "
                 f"({changed_total} of {points}), Pi1 falls steadily as body 0 gets heavier at {falling} "
                 f"({pct(falling, changed_total)}), rises steadily at {rising} ({pct(rising, changed_total)}) and "
                 f"goes both ways at {other} ({pct(other, changed_total)}): the steady "
                 f"fall {'is' if main else 'is not'} the most common of the three, "
                 f"{'as' if main else 'unlike'} the paper's main trend, and the exceptions make up "
                 f"{pct(rising + other, changed_total)} of the points. The mass ratio changes "
                 f"Pi1 by up to a factor {g(widest[0])} ({widest[1]}) at a frequency ratio Pi5 = {pi5}.", ""]
    return text


# ---------------------------------------------------------------- Fig. 10: scaling law

def fig10_section(fam, out):
    """Claim 6: branches of ln Pi1 against ln Pi6, their slopes and intercepts."""
    fitted = [(c, analysis.branches(c)) for c in fam["fig10"]]
    figure = plots.fig10(fitted, out)
    lines = [[c["pulse"], c["pi5"], c["pi2"], b.kind, b.points, f"{g(b.lo)}–{g(b.hi)}", f"{b.slope:+.3f}",
              f"{b.intercept:.3f}", "exact" if math.isnan(b.r2) else f"{b.r2:.3f}"] for c, bs in fitted for b in bs]
    kinds = {k: [b for _, bs in fitted for b in bs if b.kind == k] for k in ("no effect", "negative", "positive")}
    flat, neg, pos = kinds["no effect"], kinds["negative"], kinds["positive"]
    unchanged = [np.abs(c.ratio - 1) < analysis.UNCHANGED for c, _ in fitted]
    with_impacts = sum(int((u & (c.impacts > 0)).sum()) for u, (c, _) in zip(unchanged, fitted))
    sloped = neg + pos
    bent = [b for b in sloped if b.r2 < 0.98]
    flat_max = max((abs(b.slope) for b in flat), default=float("nan"))
    agrees = bool(flat and neg and pos) and flat_max < 1e-9

    def slopes(found):
        return f"B from {min(b.slope for b in found):+.3f} to {max(b.slope for b in found):+.3f}" if found else "none"

    text = [
        "## Fig. 10: incomplete similarity in the mass ratio", "", f"![Fig. 10]({figure})", "",
        "\"INCOMPLETE SIMILARITY\": on the ln Pi1 – ln Pi6 plane the paper finds three almost straight branches, "
        "a horizontal one where there is no contact, a negative main branch (the heavier body responds less) "
        "and a positive, counter-intuitive one, each a scaling law Pi1 = A Pi6^B (paper eqs 13-15). The "
        f"`fig10` family: pair, normal directivity, Pi5 = {listed(sorted({float(c['pi5']) for c, _ in fitted}))}, "
        f"{len(fitted[0][0].x)} log-spaced Pi6 in [{g(fitted[0][0].x[0])}, {g(fitted[0][0].x[-1])}] at Pi2 = "
        f"{listed(sorted({float(c['pi2']) for c, _ in fitted}))}.", "",
        "**Branch rule.** On each Pi1(Pi6) curve at fixed Pi2: the *no-effect* branch is every point where "
        f"contact left Pi1 as it was (abs(Pi1 / Pi1_nc - 1) < {analysis.UNCHANGED:g}); the other points are cut "
        "into maximal runs of consecutive points along which ln Pi1 keeps the sign of its change (neighbouring "
        "runs share their turning point), and a run of at least "
        f"{analysis.MIN_BRANCH} points is a *negative* or *positive* branch. Each branch is fitted by least "
        "squares on ln Pi1 = ln A + B ln Pi6 over its own points. The no-effect rule is wider than \"no impact\" "
        f"on purpose: of the {sum(int(u.sum()) for u in unchanged)} unchanged points, {with_impacts} had impacts "
        "that left the maximum as it was. The no-contact Pi1 does not depend on Pi6, so this branch is flat by "
        "construction.", ""]
    text += table(["pulse", "Pi5", "Pi2", "branch", "points", "Pi6 range", "slope B", "A", "R²"], lines)
    text += [
        f"Found: {len(flat)} no-effect branches (largest abs(B) {flat_max:.1e}), {len(neg)} negative ({slopes(neg)}) "
        f"and {len(pos)} positive ({slopes(pos)}). "
        + ("The three kinds of branch and their slope signs are those of the paper; "
           if agrees else "The paper's three kinds of branch are not all found; ")
        + ("the negative branches are the more numerous, as a main trend should be. " if len(neg) > len(pos) else
           "the negative branches are not the more numerous, unlike a main trend. ")
        + (f"R² of the sloped branches: {span([b.r2 for b in sloped])}; {len(bent)} of {len(sloped)} have R² < 0.98 "
           "(they bend: a single power law fits them only roughly)." if sloped else ""), ""]
    return text, Claim("Fig. 10: a flat branch without contact, a negative main branch, a positive "
                       "counter-intuitive branch", "INCOMPLETE SIMILARITY",
                       f"{len(flat)} flat (abs(B) <= {flat_max:.0e}), {len(neg)} negative ({slopes(neg)}), "
                       f"{len(pos)} positive ({slopes(pos)})", agrees,
                       f"{len(flat)} flat, {len(neg)} negative, {len(pos)} positive branches")


# ---------------------------------------------------------------- the page

@dataclass
class Claim:
    """One of the paper's claims against the reference."""
    claim: str
    section: str  # the paper's section heading it comes from
    measured: str  # the numbers behind the verdict, in full
    verdict: object  # True, False or "partly"
    evidence: str  # the same in a few words, for the summary at the top of the page


def holds(v):
    return {True: "yes", False: "**no**", "partly": "**partly**"}[v]


def anchor(heading):
    """The link GitHub gives a Markdown heading: lower case, punctuation dropped, spaces to hyphens."""
    return "#" + re.sub(r"[^\w\- ]", "", heading.lstrip("#").strip().lower()).replace(" ", "-")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results", nargs="+", help="`poundbench spectrum` CSVs of paper.toml and paper-report.toml")
    parser.add_argument("--poundbench", required=True, help="the poundbench binary (for the Fig. 6 histories)")
    parser.add_argument("--out", default="reports/paper", help="folder for README.md and figures/")
    args = parser.parse_args()

    rows = [r for r in load(args.results) if r["solver"] == "event-driven"]
    failed = [r for r in rows if r["status"] != "ok"]
    if failed:
        sys.exit(f"make_paper.py: {len(failed)} reference runs did not finish (first: point {failed[0]['point']} "
                 f"of {failed[0]['family']}: {failed[0]['status']} {failed[0]['message']})")
    os.makedirs(os.path.join(args.out, "figures"), exist_ok=True)

    fam = analysis.families(rows)
    claims, body = [], []
    for section in (lambda: fig3_section(fam, args.out),
                    lambda: (figs_4_5_section(fam, args.out), None),
                    lambda: pi5_limit_section(fam, args.out),
                    lambda: local_maxima_section(fam),
                    lambda: (fig6_section(fam, args.poundbench, args.out), None),
                    lambda: (fig7_section(fam, args.out), None),
                    lambda: regions_section(fam, args.out),
                    lambda: sided_section(fam),
                    lambda: (mass_section(fam, args.out), None),
                    lambda: fig10_section(fam, args.out)):
        text, claim = section()
        body += text
        if claim:
            claims.append((claim, anchor(text[0])))  # its details: the section's heading

    eps = sorted({r["eps"] for r in rows if r["family"] != "eps-cover"})
    head = [
        "# The paper's findings, reproduced by the reference", "",
        "Which of the findings of Dimitrakopoulos, Makris & Kappos (2009) the event-driven reference reproduces, "
        "computed from its result rows (details below and in each section):", ""]
    head += table(["claim", "holds?", "evidence"],
                  [[f"[{c.claim}]({link})", holds(c.verdict), c.evidence] for c, link in claims])
    head += [
        "Regenerated by `bash scripts/paper.sh` (build, the sweeps, `reports/paper/make_paper.py`); "
        "`scripts/main.sh` runs the same step. Every number on this page is computed from the result rows.", "",
        "The paper is Dimitrakopoulos, Makris & Kappos, *Dimensional analysis of the earthquake-induced "
        "pounding between adjacent structures*, Earthquake Engng Struct Dyn 2009; 38:867-886. Its case "
        "families are `cases/sets/paper.toml`; `cases/sets/paper-report.toml` adds the few points this page "
        f"needs beyond them. {len(rows)} cases, all solved by the event-driven reference (exact motion between "
        "events, Poisson impacts, about 1e-9 accurate in Pi1); every run finished.", "",
        "* **Restitution.** The paper does not state the coefficient of restitution of its figures. Every "
        f"case of its figures here uses eps = {' and '.join(eps)} (the case set's `eps-cover` family, "
        "eps = 0 and 1, is not used on this page). Agreement is "
        "therefore with the paper's statements, not its curves point by point.",
        "* **Conventions** (`cases/README.md`): Pi1 = max abs(u0) w_p² / a_p, Pi2 = w0 / w_p, Pi3 = delta w_p² "
        "/ a_p = 0.5, Pi5 = w0 / w1, Pi6 = m0 / m1, damping 5 %, t_end = T_p + 3 longest natural periods. "
        "Pi1_nc is the same case without contacts. Spectra run over 200 log-spaced Pi2 in [0.1, 10].",
        "* Section headings in quotes are the paper's; the text here does not copy it.", "",
        "## The claims in detail", ""]
    head += table(["", "claim", "paper section", "measured", "verdict"],
                  [[i + 1, c.claim, f"\"{c.section}\"", c.measured, holds(c.verdict)]
                   for i, (c, _) in enumerate(claims)])
    head += ["", "The same claims are accuracy regression tests (`tests/paper_claims_test.cpp`): each asserts "
             "what the reference does, with the same thresholds, where it agrees with the paper and where it "
             "does not.", ""]
    measured_on = provenance.measure(os.path.dirname(args.poundbench) or ".")  # the binary's build
    page = head + body + ["## Where this ran", "", footer(measured_on), ""]
    write_page(args.out, page, "make_paper.py")


if __name__ == "__main__":
    main()
