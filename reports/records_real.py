"""The report's section on the real record suite (issue 34): the Pi-spectra of
cases/sets/records-real.toml (the 25 accelerograms of cases/records/real through the wall, a
flexible and a stiff pair and the symmetric row3, both directivities) through the reference,
as engineers read a suite: per Pi2 the median and the 16th and 84th percentiles of Pi1 over
the records, a figure of them on log axes, and the median per earthquake (the earthquake of
each record from cases/records/real/manifest.csv). Reads the rows of `poundbench spectrum
cases/sets/records-real.toml --solver event-driven` (scripts/main.sh:
results/real-records-event-driven.csv), and writes the statistics it draws as
records-real-stats.csv beside the report. Used by make_report.py."""

import csv
import os
from collections import defaultdict

from rows import num
from study import percentile

HERE = os.path.dirname(os.path.abspath(__file__))
MANIFEST = os.path.join(os.path.dirname(HERE), "cases", "records", "real", "manifest.csv")
STATS = "records-real-stats.csv"
QUANTILES = (16, 50, 84)  # the median and the median +- one standard deviation of a lognormal spread


def earthquakes(path=MANIFEST):
    """{record file name: earthquake} from the suite's manifest."""
    with open(path, newline="") as f:
        return {r["file"]: r["earthquake"] for r in csv.DictReader(f)}


def config(r):
    """One curve of the suite: the scene, body 0's contrast (none for the wall) and the directivity."""
    pi5 = "" if r["scene"] == "wall" else r["pi5"]
    return (r["family"], r["scene"], pi5, r["directivity"])


def config_name(c):
    family, scene, pi5, directivity = c
    return f"{scene}" + (f", Pi5 = {pi5}" if pi5 else "") + f", {directivity}"


def statistics(rows):
    """{config: [(Pi2, n records, p16, p50, p84 of Pi1, p50 of the no-contact Pi1)]}, from the
    reference's rows that ended ok (a failed run is counted out, and `failed` says so)."""
    by = defaultdict(lambda: defaultdict(list))
    for r in rows:
        if r["status"] == "ok":
            by[config(r)][num(r, "pi2")].append((num(r, "pi1"), num(r, "pi1_no_contact")))
    stats = {}
    for c, per_pi2 in by.items():
        stats[c] = [(pi2, len(v), *(percentile([p for p, _ in v], q) for q in QUANTILES),
                     percentile([n for _, n in v], 50)) for pi2, v in sorted(per_pi2.items())]
    return stats


def per_earthquake(rows, quake_of):
    """{(config, earthquake): [(Pi2, median Pi1 over its records)]}."""
    by = defaultdict(lambda: defaultdict(list))
    for r in rows:
        if r["status"] == "ok":
            by[(config(r), quake_of[os.path.basename(r["record"])])][num(r, "pi2")].append(num(r, "pi1"))
    return {k: [(pi2, percentile(v, 50)) for pi2, v in sorted(per.items())] for k, per in by.items()}


def write_stats(stats, path):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["family", "scene", "pi5", "directivity", "pi2", "records", "pi1_p16", "pi1_median", "pi1_p84",
                    "pi1_no_contact_median"])
        for c, points in stats.items():
            for p in points:
                w.writerow([*c, repr(p[0]), p[1], *(f"{x:.6g}" for x in p[2:])])


def plot(stats, quakes, out_dir):
    from figure import colors, figure_width, legend_below, save, with_legend_below

    configs = list(stats)
    scenes = list(dict.fromkeys((c[1], c[2]) for c in configs))
    names = sorted({q for (_, q) in quakes})
    palette = colors(len(names))
    fig, grid = with_legend_below(figure_width(len(scenes), 3.6), 7.0, len(names) + 3, columns=4, wspace=0.25)
    fig.subplots(2, len(scenes), squeeze=False, sharex=True, gridspec_kw=grid)
    for col, (scene, pi5) in enumerate(scenes):
        for row, directivity in enumerate(("normal", "reverse")):
            ax = fig.axes[row * len(scenes) + col]
            c = next((k for k in configs if k[1:] == (scene, pi5, directivity)), None)
            if c is None:
                continue
            pts = stats[c]
            x = [p[0] for p in pts]
            ax.fill_between(x, [p[2] for p in pts], [p[4] for p in pts], color="0.8", label="16th-84th percentile")
            ax.plot(x, [p[3] for p in pts], color="black", lw=2.2, label="median")
            ax.plot(x, [p[5] for p in pts], color="0.4", lw=1.0, ls="--", label="median, no contact")
            for name, color in zip(names, palette):
                e = quakes.get((c, name))
                if e:
                    ax.plot([p for p, _ in e], [v for _, v in e], color=color, lw=0.8, label=name)
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_title(config_name(c), fontsize=9)
            ax.grid(True, which="both", alpha=0.3)
            if col == 0:
                ax.set_ylabel("Pi1")
            if row == 1:
                ax.set_xlabel("Pi2 = w0 / w_p")
    handles, labels = fig.axes[0].get_legend_handles_labels()
    legend_below(fig, handles, labels, columns=4)
    fig.suptitle("The real record suite through the reference: Pi1 over the 25 records, and each earthquake's median")
    return save(fig, out_dir, "records-real")


def section(rows, out_dir):
    """The section's lines (markdown), its figure, and records-real-stats.csv."""
    stats = statistics(rows)
    quakes = per_earthquake(rows, earthquakes())
    write_stats(stats, os.path.join(out_dir, STATS))
    failed = sum(r["status"] != "ok" for r in rows)
    records = sorted({os.path.basename(r["record"]) for r in rows})
    by_quake = defaultdict(list)
    for name, quake in earthquakes().items():
        by_quake[quake].append(name)
    w_p = {os.path.basename(r["record"]): num(r, "w_p") for r in rows}
    t_m = sorted(6.283185307179586 / v for v in w_p.values())
    text = ["## The real record suite", "",
            f"`cases/sets/records-real.toml`: the {len(records)} real accelerograms of `cases/records/real/` "
            f"({len(by_quake)} earthquakes, `manifest.csv`) through the reference, {len(rows)} runs "
            f"({failed} failed). Each record's Pi terms are on its own peak (`a_p`) and mean period T_m (Rathje "
            "et al. 1998; `w_p = 2 pi / T_m`, the default when no `tp` is given): T_m runs from "
            f"{t_m[0]:.3g} s to {t_m[-1]:.3g} s over the suite (median {percentile(t_m, 50):.3g} s). The scenes are "
            "the paper's, at its Pi terms (Pi3 = 0.5, eps = 0.5, equal masses; body 0 flexible, Pi5 = 0.5, or stiff, "
            "Pi5 = 2, as in its Figs 4, 5 and 7), both directivities.", "",
            "Per Pi2 the median and the 16th and 84th percentiles of Pi1 over the records (the band an engineer "
            "reads as the median plus and minus one standard deviation of a lognormal spread), each earthquake's "
            f"median in colour (values in `{STATS}`; below, every other Pi2 of the spectrum). Each percentile is "
            "by linear interpolation between order statistics: the p-th of n sorted values is at rank "
            "(n - 1) p / 100 counted from 0 (numpy's default; `study.percentile`).", "",
            "| curve | Pi2 | median Pi1 | 16th–84th | median no contact |", "|---|---:|---:|---|---:|"]
    for c, points in stats.items():
        for p in points[::2]:
            text.append(f"| {config_name(c)} | {p[0]:.3g} | {p[3]:.3g} | {p[2]:.3g}–{p[4]:.3g} | {p[5]:.3g} |")
    text += ["", f"![the real record suite]({plot(stats, quakes, out_dir)})", ""]
    return text


if __name__ == "__main__":  # python3 reports/records_real.py OUT_DIR ROWS.csv...: the section alone
    import sys

    from rows import load, write_page

    out = sys.argv[1]
    os.makedirs(os.path.join(out, "figures"), exist_ok=True)
    write_page(out, section(load(sys.argv[2:]), out), "records_real.py")
