"""The report's section on the gap that avoids pounding (issue 51): the per-case table of
`poundbench separation cases/sets/separation.toml --gap-fractions ...` (scripts/main.sh:
results/separation.csv) says, per family (elastic and yielding bodies) and rule (ABS, SRSS,
DDC), how each rule's gap compares with the exact one over the shipped real records:

- the classic figure: each rule's gap over the required one against the period ratio T1 / T0,
  the median over the records and the 16th-84th percentile band, one line per rule, a panel
  per family and period of body 0;
- per family, period-ratio band and rule: the median ratio, its spread and the share of cases
  where the rule is short of the required gap (unconservative);
- how much pounding amplifies body 0's peak at fractions of the required gap.

Writes separation-summary.csv beside the report. Used by make_report.py."""

import csv
import os
from collections import defaultdict

from rows import num
from study import percentile

SUMMARY = "separation-summary.csv"
RULES = ("abs", "srss", "ddc")
RULE_NAMES = {"abs": "ABS", "srss": "SRSS", "ddc": "DDC"}
# Where the periods are close (the rules' correlation matters) and where they are far apart.
BANDS = (("T1/T0 < 0.5", lambda r: r < 0.5), ("0.5 <= T1/T0 <= 2", lambda r: 0.5 <= r <= 2.0),
         ("T1/T0 > 2", lambda r: r > 2.0))


def ok(rows):
    return [r for r in rows if r["status"] == "ok"]


def by_ratio(rows):
    """{(family, pi2): {period ratio: {rule: [ratios over the records]}}}."""
    out = defaultdict(lambda: defaultdict(lambda: defaultdict(list)))
    for r in ok(rows):
        for rule in RULES:
            out[(r["family"], round(num(r, "pi2"), 6))][num(r, "period_ratio")][rule].append(num(r, rule))
    return out


def summary(rows):
    """[(family, band, rule, cases, median, p16, p84, unconservative share)]."""
    out = []
    families = list(dict.fromkeys(r["family"] for r in rows))
    for family in families:
        mine = [r for r in ok(rows) if r["family"] == family]
        for band, inside in BANDS:
            sel = [r for r in mine if inside(num(r, "period_ratio"))]
            for rule in RULES:
                x = [num(r, rule) for r in sel]
                if not x:
                    continue
                out.append((family, band, rule, len(x), percentile(x, 50), percentile(x, 16), percentile(x, 84),
                            sum(v < 1.0 for v in x) / len(x)))
    return out


def amplification(rows):
    """{(family, fraction): [body 0's peak over its no-contact peak]} over the cases that ran."""
    out = defaultdict(list)
    for r in ok(rows):
        for key in r:
            if key.startswith("amplification_") and r[key]:
                out[(r["family"], key[len("amplification_"):])].append(num(r, key))
    return out


def write_summary(stats, path):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["family", "period_ratio_band", "rule", "cases", "median", "p16", "p84", "unconservative"])
        for s in stats:
            w.writerow([*s[:4], *(f"{x:.6g}" for x in s[4:])])


def plot(rows, out_dir):
    from figure import figure_width, legend_below, save, with_legend_below

    curves = by_ratio(rows)
    panels = sorted(curves)
    colors = {"abs": "tab:red", "srss": "tab:blue", "ddc": "tab:green"}
    fig, grid = with_legend_below(figure_width(len(panels), 3.3), 3.6, 4, columns=4, wspace=0.25)
    fig.subplots(1, len(panels), squeeze=False, sharey=True, gridspec_kw=grid)
    for ax, key in zip(fig.axes, panels):
        per = curves[key]
        x = sorted(per)
        for rule in RULES:
            ax.fill_between(x, [percentile(per[v][rule], 16) for v in x], [percentile(per[v][rule], 84) for v in x],
                            color=colors[rule], alpha=0.15, lw=0)
            ax.plot(x, [percentile(per[v][rule], 50) for v in x], color=colors[rule], lw=1.8,
                    label=f"{RULE_NAMES[rule]}: median over the records")
        ax.axhline(1.0, color="black", lw=0.8, ls="--", label="the exact gap")
        ax.set_xscale("log")
        ax.set_title(f"{key[0]}, Pi2 = {key[1]:.3g}", fontsize=9)
        ax.set_xlabel("T1 / T0")
        ax.grid(True, which="both", alpha=0.3)
    fig.axes[0].set_ylabel("rule's gap / exact required gap")
    handles, labels = fig.axes[0].get_legend_handles_labels()
    legend_below(fig, handles, labels, columns=4)
    fig.suptitle("The rules against the gap that avoids pounding (bands: 16th-84th percentile over the records)")
    return save(fig, out_dir, "separation")


def section(rows, out_dir):
    """The section's lines (markdown), its figure, and separation-summary.csv."""
    stats = summary(rows)
    write_summary(stats, os.path.join(out_dir, SUMMARY))
    records = sorted({os.path.basename(r["record"]) for r in rows})
    failed = sum(r["status"] != "ok" for r in rows)
    text = ["## The gap that avoids pounding, and the rules", "",
            f"`cases/sets/separation.toml` through `poundbench separation`: {len(rows)} cases ({failed} failed) of two "
            f"buildings as single oscillators under {len(records)} real records scaled to a PGA of 0.35 g, body 0's "
            "period against a neighbour from a sixth to nine times its period, elastic and yielding. The exact gap "
            "is the larger over the two signs of the record of the largest relative approach without contact; each "
            "rule's gap is divided by it (cases/README.md, \"Separation\"). Below 1 a rule is unconservative: the "
            "buildings pound at the gap it gives.", "",
            "| family | T1 / T0 | rule | cases | median | 16th–84th | unconservative |",
            "|---|---|---|---:|---:|---|---:|"]
    for family, band, rule, n, med, p16, p84, short in stats:
        text.append(f"| {family} | {band} | {RULE_NAMES[rule]} | {n} | {med:.3g} | {p16:.3g}–{p84:.3g} | "
                    f"{100 * short:.0f} % |")
    holds = []
    for family in dict.fromkeys(s[0] for s in stats):
        for band, _ in BANDS:
            safe = [RULE_NAMES[s[2]] for s in stats if s[0] == family and s[1] == band and s[7] == 0.0]
            tight = [s for s in stats if s[0] == family and s[1] == band and s[7] == 0.0]
            best = min(tight, key=lambda s: s[4]) if tight else None
            holds.append(f"- {family}, {band}: "
                         + (f"never short: {', '.join(safe)}; the tightest of them {RULE_NAMES[best[2]]} (median "
                            f"{best[4]:.3g} of the exact gap)." if safe else "every rule is short somewhere."))
    text += ["", "Which rule holds where, over these records (a rule holds where no case is short of the gap):", "",
             *holds, ""]
    amp = amplification(rows)
    if amp:
        text += ["Pounding at a fraction of the exact gap (the record as given): body 0's peak over its peak "
                 "without contact (for a single storey, its drift's too).", "",
                 "| family | gap / exact | cases | median | 16th–84th | largest |", "|---|---:|---:|---:|---|---:|"]
        for (family, frac), x in sorted(amp.items()):
            text.append(f"| {family} | {frac} | {len(x)} | {percentile(x, 50):.3g} | "
                        f"{percentile(x, 16):.3g}–{percentile(x, 84):.3g} | {max(x):.3g} |")
    text += ["", f"![the rules against the exact gap]({plot(rows, out_dir)})", ""]
    return text
