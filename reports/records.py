"""The report's section on recorded ground motions and pulse models (issue 21): the Pi-spectra
of cases/sets/records.toml (the example records of cases/records/ and the pulse models at the
same Pi terms) through the reference and the time-steppers at their default N, a figure per
family (Pi1 against Pi2, a panel per Pi5: the reference in black, each time-stepper in colour,
its relative error below), and a table of each solver's errors. Reads the rows of
`poundbench spectrum cases/sets/records.toml --solver S` (scripts/main.sh: results/records-*.csv).
Used by make_report.py."""

import math
from collections import defaultdict

from figure import figure_width, legend_below, log_spans, save, solver_styles, with_legend_below
from rows import config_label, median, num

REFERENCE = "event-driven"


def _key(r):
    return (r["family"], r["pi5"], r["directivity"], r["pi2"])


def errors(rows):
    """{(family, config): [relative Pi1 error per point]} against the reference's row of the
    same case, and the failed runs per (family, config)."""
    ref = {_key(r): num(r, "pi1") for r in rows if r["solver"] == REFERENCE and r["status"] == "ok"}
    errs, failed = defaultdict(list), defaultdict(int)
    for r in rows:
        if r["solver"] == REFERENCE:
            continue
        label = config_label(r)
        if r["status"] != "ok":
            failed[(r["family"], label)] += 1
            continue
        exact = ref.get(_key(r))
        if exact:
            errs[(r["family"], label)].append(abs(num(r, "pi1") - exact) / exact)
    return errs, failed


def plot_family(family, rows, out_dir):
    rows = [r for r in rows if r["family"] == family]
    pi5s = sorted({r["pi5"] for r in rows}, key=float)
    styles = solver_styles([r for r in rows if r["solver"] != REFERENCE])
    fig, grid = with_legend_below(figure_width(len(pi5s)), 5.6, len(styles) + 2, wspace=0.22, hspace=0.1)
    fig.subplots(2, len(pi5s), squeeze=False, sharex=True, gridspec_kw=dict(grid, height_ratios=[2, 1]))
    axes = [fig.axes[:len(pi5s)], fig.axes[len(pi5s):]]
    ref = {_key(r): num(r, "pi1") for r in rows if r["solver"] == REFERENCE and r["status"] == "ok"}
    for col, pi5 in enumerate(pi5s):
        top, bottom = axes[0][col], axes[1][col]
        by_config = defaultdict(list)
        for r in rows:
            if r["pi5"] == pi5 and r["status"] == "ok":
                by_config[(r["solver"], config_label(r))].append(r)
        for (solver, label), crows in sorted(by_config.items()):
            crows.sort(key=lambda r: num(r, "pi2"))
            x = [num(r, "pi2") for r in crows]
            if solver == REFERENCE:
                top.plot(x, [num(r, "pi1") for r in crows], color="black", lw=2.4, label="reference", zorder=5)
                top.plot(x, [num(r, "pi1_no_contact") for r in crows], color="0.45", lw=1.0, ls="--",
                         label="no contact", zorder=4)
                continue
            st = styles[label]
            top.plot(x, [num(r, "pi1") for r in crows], color=st["color"], ls=st["ls"], lw=1.1, label=label)
            e = [(num(r, "pi2"), abs(num(r, "pi1") - ref[_key(r)]) / ref[_key(r)]) for r in crows if ref.get(_key(r))]
            bottom.plot([p for p, _ in e], [max(v, 1e-16) for _, v in e], color=st["color"], ls=st["ls"],
                        marker=st["marker"], ms=3, lw=1.0)
        top.set_xscale("log")
        if log_spans([num(r, "pi1") for r in rows if r["pi5"] == pi5 and r["solver"] == REFERENCE]):
            top.set_yscale("log")
        top.set_title(f"{family}: Pi5 = {pi5}")
        top.set_ylabel("Pi1")
        bottom.set_yscale("log")
        bottom.set_xlabel("Pi2")
        bottom.set_ylabel("relative Pi1 error")
        top.grid(True, which="both", alpha=0.3)
        bottom.grid(True, which="both", alpha=0.3)
    handles, names = axes[0][0].get_legend_handles_labels()
    for ax in axes[0][1:]:
        for h, name in zip(*ax.get_legend_handles_labels()):
            if name not in names:
                handles.append(h)
                names.append(name)
    legend_below(fig, handles, names)
    fig.suptitle(f"{family}: Pi-spectra through the reference and the time-steppers, and their error")
    return save(fig, out_dir, f"records-{family}")


def section(rows, out_dir):
    """The section's lines (markdown)."""
    families = list(dict.fromkeys(r["family"] for r in rows))
    errs, failed = errors(rows)
    configs = sorted({label for (_, label) in list(errs) + list(failed)})
    text = ["## Recorded ground motions and pulse models", "",
            "Pi-spectra of `cases/sets/records.toml`: the two example records of `cases/records/` (synthetic: a "
            "Mavroeidis–Papageorgiou pulse in band-limited noise, `scripts/make_records.py`), their Pi terms on the "
            "pulse inside them (`tp`, and `a_p` the record's peak), on a flexible (Pi5 = 0.5) and a stiff "
            "(Pi5 = 2) pair, and the pulse models `mp` and `makris-c` at the same Pi terms. The reference "
            "takes each sample of a record as an event (its load is linear between samples, and exact between "
            "them); every time-stepper runs at its default N = 64 steps per shortest period, reading the record "
            "as it reads any load (Moreau–Jean: its exact step mean; the engines: a_g sampled at their steps).", "",
            "Median and largest relative Pi1 error against the reference, per family (failed runs in brackets):", "",
            "| solver | " + " | ".join(families) + " |", "|---|" + "---:|" * len(families)]
    for label in configs:
        cells = []
        for family in families:
            e = errs.get((family, label), [])
            f = failed.get((family, label), 0)
            cell = f"{median(e):.2g} / {max(e):.2g}" if e else "–"
            cells.append(cell + (f" ({f} failed)" if f else ""))
        text.append(f"| {label} | " + " | ".join(cells) + " |")
    text.append("")
    for family in families:
        if not any(r["solver"] == REFERENCE and r["family"] == family for r in rows):
            continue
        text += [f"### {family}", "", f"![records {family}]({plot_family(family, rows, out_dir)})", ""]
    return text


if __name__ == "__main__":  # python3 reports/records.py OUT_DIR ROWS.csv...: the section alone
    import os
    import sys

    from rows import load, write_page

    out = sys.argv[1]
    os.makedirs(os.path.join(out, "figures"), exist_ok=True)
    write_page(out, section(load(sys.argv[2:]), out), "records.py")
