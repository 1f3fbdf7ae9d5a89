"""The report's section on multi-storey buildings (issue 49): cases/sets/buildings.toml through
the exact reference and, beside it, the time-steppers of the scene. Reads the rows of `poundbench
spectrum cases/sets/buildings.toml --solver S` (one row per floor: rows/buildings_rows.hpp;
scripts/main.sh: results/buildings-*.csv) and says, from them:

- how pounding changes each building's response: per point the top floor's peak and the
  largest storey drift over their values without contact, and whether the single
  oscillators' finding carries over (pounding amplifies the stiffer, shorter building and
  shields the flexible one: the paper's Pi5 trends), counted over the set;
- a figure of the peaks up the height, with and without contact, and the drift ratios of the
  uniform pairs over Pi2;
- per solver setting, how far its floor peaks are from the reference's (the largest relative
  error over a point's floors) and what a point costs, a work-precision figure, and per target
  the cheapest setting of each solver that meets it by the study's one answer rule;
- on cases/sets/buildings-stress.toml, per solver setting and family, which points ended ok.

Writes buildings-summary.csv beside the report. Used by make_report.py."""

import csv
import json
import math
import os
from collections import defaultdict

from robust import robust, step_split
from rows import num, settings_fields
from study import percentile

SUMMARY = "buildings-summary.csv"
REFERENCE = "event-driven"
TARGETS = (1e-2, 1e-3, 1e-4)  # relative error of the worst floor peak of a point


def points(rows):
    """{(solver, settings): {point: {(building, floor): row}}}."""
    by = defaultdict(lambda: defaultdict(dict))
    for r in rows:
        by[(r["solver"], r["settings"])][int(r["point"])][(int(r["building"]), int(r["floor"]))] = r
    return by


def building_response(floors, b, key):
    """A building's top floor peak and largest storey drift, under `key` ("" or "_no_contact")."""
    mine = [r for (bb, _), r in sorted(floors.items()) if bb == b]
    return num(mine[-1], f"floor_peak{key}_m"), max(num(r, f"drift_peak{key}_m") for r in mine), len(mine)


def amplification(reference):
    """Per point of the reference that ended ok: its family, load, and per building (storeys,
    top floor ratio, largest drift ratio, first-mode order: 0 the stiffer, shorter one)."""
    out = []
    for point, floors in sorted(reference.items()):
        first = next(iter(floors.values()))
        if first["status"] != "ok":
            continue
        buildings = sorted({b for b, _ in floors})
        per = []
        for b in buildings:
            top, drift, storeys = building_response(floors, b, "")
            top0, drift0, _ = building_response(floors, b, "_no_contact")
            per.append((storeys, top / top0 if top0 > 0 else float("nan"), drift / drift0 if drift0 > 0 else float("nan")))
        impacts = sum(int(r["impacts_right"]) for r in floors.values() if r["impacts_right"])
        out.append(dict(point=point, family=first["family"], load=load_name(first), per=per, impacts=impacts,
                        pi2=first["pi2"]))
    return out


def load_name(r):
    what = os.path.basename(r["record"]) if r["record"] else r["pulse"]
    return f"{what} {r['directivity']}"


def peak_errors(reference, solved):
    """Per point both solved ok: the largest relative error of the floor peaks, and the solve's CPU."""
    out = []
    for point, floors in solved.items():
        truth = reference.get(point)
        if not truth or next(iter(floors.values()))["status"] != "ok" or next(iter(truth.values()))["status"] != "ok":
            continue
        error = max(abs(num(r, "floor_peak_m") / num(truth[k], "floor_peak_m") - 1) for k, r in floors.items())
        out.append((error, num(next(iter(floors.values())), "cpu_seconds")))
    return out


def solver_table(by):
    """Per solver setting but the reference: (solver, settings, points ok, not ok, median and
    worst error, robust error, median CPU). The robust error is study.robust's rule (issue 48):
    the worst error of this setting and of every finer step of the same solver and settings,
    NaN where any of them failed a point, so that no lucky coarse step is picked."""
    reference = next((v for (s, _), v in by.items() if s == REFERENCE), None)
    if reference is None:
        return []
    lines, items = [], []

    def order(key):
        rest, fineness = step_split(settings_fields(dict(settings=key[1])))
        return key[0], rest, fineness or 0

    for (solver, settings), solved in sorted(by.items(), key=lambda kv: order(kv[0])):
        if solver == REFERENCE:
            continue
        errors = peak_errors(reference, solved)
        e = [x for x, _ in errors]
        failed = len(solved) - len(errors)
        worst = max(e) if e and not failed else float("nan")
        rest, fineness = step_split(settings_fields(dict(settings=settings)))
        items.append(((solver, rest), fineness, worst))
        lines.append((solver, settings, len(errors), failed, percentile(e, 50) if e else float("nan"),
                      max(e) if e else float("nan"), percentile([c for _, c in errors], 50) if e else float("nan")))
    return [line[:6] + (r,) + line[6:] for line, r in zip(lines, robust(items))]


def floor_step_cost(solved):
    """The median over points of a solve's CPU over its steps times the point's floors (s); NaN
    without a fixed step (the reference, CVODE)."""
    costs = []
    for floors in solved.values():
        first = next(iter(floors.values()))
        if first["status"] != "ok" or not first["step_s"]:
            continue
        steps = num(first, "t_end_s") / num(first, "step_s")
        costs.append(num(first, "cpu_seconds") / (steps * len(floors)))
    return percentile(costs, 50) if costs else float("nan")


def engine_lines(by, stress_by):
    """Per solver and settings but the step (a variant): its observed order (the slope of the
    median floor-peak error against the step, from its coarsest to its finest step), its CPU
    per floor-step, and the stress families where some point did not end ok or was off by more
    than 10 %."""
    reference = next((v for (s, _), v in by.items() if s == REFERENCE), None)
    stress_ref = next((v for (s, _), v in stress_by.items() if s == REFERENCE), {}) if stress_by else {}
    lines = ["Per solver and variant: the order its median floor-peak error shows from its coarsest step to its "
             "finest (`error ~ h^p`), its CPU per floor and step, and where it fails on the stress set (a family "
             "with a point that did not end ok, or off the reference by more than 10 %, at any of its steps).", "",
             "| solver | variant | steps N | order p | CPU per floor-step (ns) | fails on |",
             "|---|---|---|---:|---:|---|"]
    groups = defaultdict(list)
    for (solver, settings), solved in by.items():
        if solver == REFERENCE:
            continue
        rest, fineness = step_split(settings_fields(dict(settings=settings)))
        groups[(solver, rest)].append((fineness, solved, settings))
    for (solver, rest), members in sorted(groups.items()):
        stepped = sorted((m for m in members if m[0]), key=lambda m: m[0])
        order = float("nan")
        if len(stepped) >= 2:
            coarse, fine = stepped[0], stepped[-1]
            e0 = [e for e, _ in peak_errors(reference, coarse[1])]
            e1 = [e for e, _ in peak_errors(reference, fine[1])]
            if e0 and e1 and percentile(e1, 50) > 0:
                order = math.log(percentile(e0, 50) / percentile(e1, 50)) / math.log(fine[0] / coarse[0])
        cost = percentile([c for c in (floor_step_cost(m[1]) for m in members) if c == c] or [float("nan")], 50)
        fails, stressed = set(), False
        for (s2, settings2), solved in (stress_by or {}).items():
            if s2 != solver or step_split(settings_fields(dict(settings=settings2)))[0] != rest:
                continue
            stressed = True
            for point, floors in solved.items():
                first = next(iter(floors.values()))
                errs = [e for e, _ in peak_errors(stress_ref, {point: floors})]
                if first["status"] != "ok" or (errs and errs[0] > 0.1):
                    fails.add(first["family"])
        steps = ", ".join(f"{m[0]:g}" for m in stepped) or "its own"
        fields = json.loads(rest)
        variant = fields.get("variant") or fields.get("integrator") or "–"
        if "stiffness" in fields:  # the compliant elements: a line per stiffness
            variant += f" {fields.get('integrator', 'cvode')} K={float(fields['stiffness']):g}"
        lines.append(f"| {solver} | {variant} | {steps} | {order:.2g} | {cost * 1e9:.3g} | "
                     f"{(', '.join(sorted(fails)) or 'none') if stressed else 'not run there'} |")
    return lines + [""]


def answer_lines(table):
    """Per target, per solver: the cheapest setting (median CPU a point) whose robust error meets it."""
    out = ["The cheapest setting of each solver that meets a target on every point, by the study's rule (the "
           "setting and every finer step of it meet the target: `reports/robust.py`), and its median CPU a point:", "",
           "| target | " + " | ".join(sorted({t[0] for t in table})) + " |",
           "|---:|" + "---|" * len({t[0] for t in table})]
    for target in TARGETS:
        cells = []
        for solver in sorted({t[0] for t in table}):
            meets = [t for t in table if t[0] == solver and t[6] <= target]
            best = min(meets, key=lambda t: t[7], default=None)
            cells.append(f"`{best[1]}` ({best[7] * 1e3:.3g} ms)" if best else "none")
        out.append(f"| {target:.0e} | " + " | ".join(cells) + " |")
    return out + [""]


def plot_work_precision(table, reference_cpu, out_dir):
    from figure import colors, figure_width, legend_below, save, with_legend_below

    # One line per solver and integrator: Moreau-Jean and Newmark over their steps, CVODE over
    # the element's stiffness (its error is the element's, its tolerance fixed).
    lines = defaultdict(list)
    for solver, settings, ok, failed, med, worst, rob, cpu in table:
        fields = settings_fields(dict(settings=settings))
        lines[solver + (f" ({fields['integrator']})" if "integrator" in fields else "")].append((cpu, worst))
    fig, grid = with_legend_below(figure_width(1, 6.0), 3.6, len(lines) + 1, columns=2)
    ax = fig.subplots(1, 1, gridspec_kw=grid)
    for (label, pts), color, marker in zip(sorted(lines.items()), colors(len(lines)), "osD^v<>ph*"):
        pts.sort()
        ax.plot([p[0] * 1e3 for p in pts], [p[1] for p in pts], color=color, marker=marker, ms=4, label=label)
    ax.axvline(reference_cpu * 1e3, color="0.3", ls=":", lw=1, label="the exact reference")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("median CPU a point (ms)")
    ax.set_ylabel("worst relative error of a floor peak")
    ax.grid(True, which="both", alpha=0.3)
    legend_below(fig, *ax.get_legend_handles_labels(), columns=2)
    fig.suptitle("Buildings: work against precision of the solvers of the scene")
    return save(fig, out_dir, "buildings-work-precision")


def write_summary(amp, path):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["family", "point", "load", "pi2", "building", "storeys", "top_floor_ratio", "max_drift_ratio",
                    "impacts"])
        for a in amp:
            for b, (storeys, top, drift) in enumerate(a["per"]):
                w.writerow([a["family"], a["point"], a["load"], a["pi2"], b, storeys, f"{top:.6g}", f"{drift:.6g}",
                            a["impacts"]])


def carry_over(amp):
    """Over the points with an impact: how often pounding raised the shorter building's largest
    drift and lowered the taller one's (the single oscillators' finding for a stiff body
    against a flexible one), and the median ratios."""
    hit = [a for a in amp if a["impacts"] > 0 and len(a["per"]) == 2 and a["per"][0][0] != a["per"][1][0]]
    short = [min(a["per"], key=lambda p: p[0])[2] for a in hit]
    tall = [max(a["per"], key=lambda p: p[0])[2] for a in hit]
    return len(hit), sum(x > 1 for x in short), sum(x < 1 for x in tall), short, tall


def top_floor_spectra(reference):
    """{storeys: [(Pi2, [(top floor Pi1, the same without contact) per building])]} of the
    reference's points in Pi terms that ended ok."""
    out = defaultdict(list)
    for point, floors in sorted(reference.items()):
        first = next(iter(floors.values()))
        if not first["pi2"] or first["status"] != "ok":
            continue
        per = []
        for b in sorted({b for b, _ in floors}):
            top = [r for (bb, _), r in sorted(floors.items()) if bb == b][-1]
            per.append((num(top, "floor_peak_pi"), num(top, "floor_peak_no_contact_pi"), int(top["floors"])))
        out[tuple(p[2] for p in per)].append((num(first, "pi2"), per))
    return out


def plot(by, amp, out_dir):
    """Two pounding points' peaks up the height; the uniform pairs' top floor spectra and their
    largest drift, pounding over none, against Pi2."""
    from figure import colors, figure_width, legend_below, save, with_legend_below

    reference = next(v for (s, _), v in by.items() if s == REFERENCE)
    shown = [a for a in amp if a["impacts"] > 0][:2]
    spectra = top_floor_spectra(reference)
    rows = 2 if spectra else 1
    fig, grid = with_legend_below(figure_width(2, 3.6), 3.2 * rows, 4 + 2 * len(spectra), columns=3, wspace=0.3,
                                  hspace=0.45)
    axes = fig.subplots(rows, 2, squeeze=False, gridspec_kw=grid)
    palette = colors(2)
    for ax, a in zip(axes[0], shown):
        floors = reference[a["point"]]
        for b, color in zip(sorted({b for b, _ in floors}), palette):
            mine = [r for (bb, _), r in sorted(floors.items()) if bb == b]
            height = [0] + [int(r["floor"]) for r in mine]
            ax.plot([0] + [num(r, "floor_peak_m") * 1e3 for r in mine], height, color=color, lw=1.8, marker="o",
                    ms=3, label=f"building {b}, pounding")
            ax.plot([0] + [num(r, "floor_peak_no_contact_m") * 1e3 for r in mine], height, color=color, lw=1.0,
                    ls="--", label=f"building {b}, no contact")
        ax.set_title(f"{a['family']}, {a['load']}", fontsize=9)
        ax.set_xlabel("peak |u| (mm)")
        ax.set_ylabel("floor")
        ax.grid(True, alpha=0.3)
    if spectra:
        first = min(spectra)  # the shorter pair: its two buildings, with and without contact
        ax = axes[1][0]
        values = sorted(spectra[first])
        for b, color in enumerate(palette[:len(first)]):
            ax.plot([v[0] for v in values], [v[1][b][0] for v in values], color=color, lw=1.8, marker="o", ms=3)
            ax.plot([v[0] for v in values], [v[1][b][1] for v in values], color=color, lw=1.0, ls="--")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(f"uniform {' + '.join(map(str, first))} storeys: top floor", fontsize=9)
        ax.set_ylabel("Pi1 = u w_p^2 / a_p")
        ax.set_xlabel("Pi2 = w_1,left / w_p")
        ax.grid(True, which="both", alpha=0.3)
        ax = axes[1][1]
        for (storeys, values), dash in zip(sorted(spectra.items()), ("-", ":", "-.")):
            drift = {a["pi2"]: a["per"] for a in amp if a["pi2"] and tuple(p[0] for p in a["per"]) == storeys}
            xs = sorted(float(k) for k in drift)
            for b, color in zip(range(len(storeys)), palette):
                ax.plot(xs, [drift[next(k for k in drift if float(k) == x)][b][2] for x in xs], color=color, ls=dash,
                        marker="o", ms=3, label=f"{storeys[b]} storeys (of {'+'.join(map(str, storeys))})")
        ax.axhline(1.0, color="0.5", lw=0.8)
        ax.set_xscale("log")
        ax.set_title("uniform pairs: largest storey drift", fontsize=9)
        ax.set_ylabel("pounding / no contact")
        ax.set_xlabel("Pi2 = w_1,left / w_p")
        ax.grid(True, which="both", alpha=0.3)
    handles, labels = [], []
    for ax in fig.axes:
        for h, label in zip(*ax.get_legend_handles_labels()):
            if label not in labels:
                handles.append(h)
                labels.append(label)
    legend_below(fig, handles, labels, columns=3)
    fig.suptitle("Buildings pounding floor against floor: the exact reference")
    return save(fig, out_dir, "buildings")


def stress_lines(rows):
    """Per solver setting and family of cases/sets/buildings-stress.toml: the points that ended
    ok, the statuses of the others, and the worst floor-peak error against the reference."""
    by = points(rows)
    reference = next((v for (s, _), v in by.items() if s == REFERENCE), {})
    lines = ["The stress set (`cases/sets/buildings-stress.toml`: eps 0 and 1, buildings touching at rest, three "
             "buildings in a row, contact at some floors only, pairs of 20 storeys): per solver setting and family, "
             "the points that ended ok, and the largest relative error of a floor peak against the reference.", "",
             "| solver | settings | family | ok | not ok | worst error |", "|---|---|---|---:|---|---:|"]
    for (solver, settings), solved in sorted(by.items()):
        families = defaultdict(list)
        for point, floors in sorted(solved.items()):
            families[next(iter(floors.values()))["family"]].append(point)
        for family, pts in families.items():
            statuses = [next(iter(solved[p].values()))["status"] for p in pts]
            bad = defaultdict(int)
            for st in statuses:
                if st != "ok":
                    bad[st] += 1
            errors = [e for e, _ in peak_errors(reference, {p: solved[p] for p in pts})] if solver != REFERENCE else []
            worst = f"{max(errors):.2e}" if errors else "–"
            not_ok = ", ".join(f"{n} {st}" for st, n in sorted(bad.items())) or "–"
            lines.append(f"| {solver} | `{settings}` | {family} | {statuses.count('ok')} | {not_ok} | {worst} |")
    return lines + [""]


def section(rows, out_dir, stress_rows=None):
    """The section's lines (markdown), its figure and buildings-summary.csv."""
    by = points(rows)
    reference = next((v for (s, _), v in by.items() if s == REFERENCE), None)
    if reference is None:
        return ["## Buildings", "", "No rows of the reference: nothing to compare.", ""]
    amp = amplification(reference)
    write_summary(amp, os.path.join(out_dir, SUMMARY))
    n, short_up, tall_down, short, tall = carry_over(amp)
    families = list(dict.fromkeys(a["family"] for a in amp))
    text = ["## Buildings pounding floor against floor", "",
            f"`cases/sets/buildings.toml`: {len(reference)} pairs of shear buildings ({', '.join(families)}) through the "
            "exact reference (modal closed forms between events, every impact and sticking floor an event: "
            "`solvers/buildings_reference/DERIVATION.md`), each beside its own response without contact. "
            f"Per point and building, the top floor's peak and the largest storey drift over their values without "
            f"contact are in `{SUMMARY}`.", ""]
    if n:
        text += [f"Does pounding amplify the shorter, stiffer building and shield the taller, flexible one? "
                 f"Over the {n} pairs of unequal heights that pounded, "
                 f"the shorter building's largest storey drift rose in {short_up} and fell in {n - short_up} (median "
                 f"ratio {percentile(short, 50):.3g}, {min(short):.3g} to {max(short):.3g}); the taller one's fell in "
                 f"{tall_down} and rose in {n - tall_down} (median ratio {percentile(tall, 50):.3g}, {min(tall):.3g} "
                 f"to {max(tall):.3g}). Which way it goes depends on where the pulse sits against the buildings' modes: "
                 "the uniform pairs' ratios over Pi2 are in the figure below.", ""]
    text += ["| family | point | load | storeys | top floor, pounding / none | largest drift, pounding / none | impacts |",
             "|---|---:|---|---|---|---|---:|"]
    for a in amp:
        storeys = " + ".join(str(p[0]) for p in a["per"])
        top = ", ".join(f"{p[1]:.3g}" for p in a["per"])
        drift = ", ".join(f"{p[2]:.3g}" for p in a["per"])
        text.append(f"| {a['family']} | {a['point']} | {a['load']} | {storeys} | {top} | {drift} | {a['impacts']} |")
    text += ["", f"![buildings]({plot(by, amp, out_dir)})", ""]
    table = solver_table(by)
    if table:
        reference_cpu = percentile([num(next(iter(f.values())), "cpu_seconds") for f in reference.values()], 50)
        text += ["Each setting of the other solvers against the reference: the largest relative error of a point's "
                 "floor peaks (median and worst over the points both solved ok; robust: the worst of this setting and "
                 "every finer step of it, by `reports/robust.py`'s rule) and the median CPU a point took (the "
                 f"reference's: {reference_cpu * 1e3:.3g} ms).", "",
                 "| solver | settings | points | not ok | median error | worst error | robust | median CPU (ms) |",
                 "|---|---|---:|---:|---:|---:|---:|---:|"]
        for solver, settings, ok, failed, med, worst, rob, cpu in table:
            text.append(f"| {solver} | `{settings}` | {ok} | {failed} | {med:.2e} | {worst:.2e} | {rob:.2e} | "
                        f"{cpu * 1e3:.3g} |")
        text += [""] + engine_lines(by, points(stress_rows) if stress_rows else None) + answer_lines(table)
        text += [f"![buildings work-precision]({plot_work_precision(table, reference_cpu, out_dir)})", ""]
    if stress_rows:
        text += stress_lines(stress_rows)
    return text


if __name__ == "__main__":  # python3 reports/buildings.py OUT_DIR ROWS.csv... [--stress ROWS.csv...]: the section alone
    import sys

    from rows import load, write_page

    out, args = sys.argv[1], sys.argv[2:]
    cut = args.index("--stress") if "--stress" in args else len(args)
    os.makedirs(os.path.join(out, "figures"), exist_ok=True)
    write_page(out, section(load(args[:cut]), out, load(args[cut + 1:]) if cut < len(args) else None), "buildings.py")
