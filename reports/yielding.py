"""The report's section on yielding bodies (issue 39): the Pi-spectra of cases/sets/yielding.toml
through the exact reference (Pi1 and the ductility demand mu of body 0 against Pi2, a curve per
Pi_y0, elastic included), which findings of the elastic case survive yielding (self-similarity,
the effect of Pi5 and of Pi6, measured here from the rows), and how Moreau-Jean at its default
N answers on yielding cases. Reads the rows of `poundbench spectrum cases/sets/yielding.toml
--solver S` (scripts/main.sh: results/yielding-*.csv). Used by make_report.py."""

import math
from collections import defaultdict

from figure import colors, figure_width, legend_below, save, with_legend_below, xlabel_below, ylabel_beside
from rows import config_label, median, num
from styles import DASHES, matplotlib_dash

REFERENCE = "event-driven"
ALPHA = "0.05"  # the spectra's alpha; the findings use every alpha


def _pi_y(r):
    return num(r, "pi_y0") if r["pi_y0"] else math.inf


def _reference(rows):
    return [r for r in rows if r["solver"] == REFERENCE and r["status"] == "ok"]


def plot_spectra(rows, family, out_dir):
    """Pi1 (top) and mu (bottom) against Pi2, a column per pulse and Pi5, a curve per Pi_y0."""
    # alpha at its elastic default 0 is an empty column: the yielding rows at ALPHA, and the
    # elastic ones (no Pi_y0: alpha changes nothing) once.
    rows = [r for r in rows if r["family"] == family and (r["alpha"] == ALPHA if r["pi_y0"] else r["alpha"] == "")]
    columns = sorted({(r["pulse"], r["pi5"]) for r in rows}, key=lambda k: (k[0], float(k[1])))
    levels = sorted({_pi_y(r) for r in rows})
    palette = colors(len(levels))
    width = figure_width(len(columns), 2.0)
    fig, grid = with_legend_below(width, 5.6, len(levels), columns=min(len(levels), 6), wspace=0.3)
    fig.subplots(2, len(columns), squeeze=False, sharex=True, gridspec_kw=dict(grid, height_ratios=[3, 2]))
    axes = [fig.axes[:len(columns)], fig.axes[len(columns):]]
    for col, (pulse, pi5) in enumerate(columns):
        top, bottom = axes[0][col], axes[1][col]
        for i, (level, color) in enumerate(zip(levels, palette)):
            curve = sorted((r for r in rows if (r["pulse"], r["pi5"]) == (pulse, pi5) and _pi_y(r) == level),
                           key=lambda r: num(r, "pi2"))
            label = "elastic" if math.isinf(level) else f"Pi_y0 = {level:g}"
            x = [num(r, "pi2") for r in curve]
            line = dict(color=color, lw=1.2, ls=matplotlib_dash(DASHES[i % len(DASHES)]))  # reads without colour
            top.plot(x, [num(r, "pi1") for r in curve], label=label,
                     **(dict(color="black", lw=2.2) if math.isinf(level) else line))
            if not math.isinf(level):
                bottom.plot(x, [num(r, "mu") for r in curve], **line)
        top.set_xscale("log")
        top.set_yscale("log")
        bottom.set_yscale("log")
        top.set_title(f"{pulse}, Pi5 = {pi5}")
        for ax in (top, bottom):
            ax.grid(True, which="major", alpha=0.3)
    xlabel_below(fig, axes[1], "Pi2")
    ylabel_beside(fig, axes[0][:1], "Pi1")
    ylabel_beside(fig, axes[1][:1], "mu = max|u0| / u_y0")
    legend_below(fig, *axes[0][0].get_legend_handles_labels(), columns=min(len(levels), 6))
    fig.suptitle(f"{family}: the reference's spectra of Pi1 and mu, alpha = {ALPHA}")
    return save(fig, out_dir, f"yielding-{family}")


def self_similarity(ref):
    """The largest relative spread of Pi1, mu and the residual over the pulse scales of yield-scales."""
    groups = defaultdict(list)
    for r in ref:
        if r["family"] == "yield-scales":
            groups[r["pi2"]].append(r)
    spread = 0.0
    for group in groups.values():
        for key in ("pi1", "mu", "residual"):
            values = [num(r, key) for r in group]
            scale = max(abs(v) for v in values)
            if scale > 0:
                spread = max(spread, (max(values) - min(values)) / scale)
    return spread, len(groups)


def amplification(ref, family_prefix):
    """{(pi5, Pi_y0): median of Pi1 / Pi1 without contact} over the points with impacts, both
    pulses and directivities and every alpha."""
    ratios = defaultdict(list)
    for r in ref:
        if r["family"].startswith(family_prefix) and num(r, "pi1_no_contact") > 0 and num(r, "impacts") > 0:
            ratios[(r["pi5"], _pi_y(r))].append(num(r, "pi1") / num(r, "pi1_no_contact"))
    return {k: median(v) for k, v in ratios.items()}


def mass_ratio_effect(ref):
    """{Pi_y0: median over Pi2 of Pi1(Pi6 = 2) / Pi1(Pi6 = 0.5)} on the yield-pi6 family."""
    by = defaultdict(dict)
    for r in ref:
        if r["family"] == "yield-pi6":
            by[(_pi_y(r), r["pi2"])][r["pi6"]] = num(r, "pi1")
    out = defaultdict(list)
    for (level, _), pi1 in by.items():
        if "2" in pi1 and "0.5" in pi1 and pi1["0.5"] > 0:
            out[level].append(pi1["2"] / pi1["0.5"])
    return {k: median(v) for k, v in out.items()}


def errors(rows):
    """{(config, family): [relative errors of Pi1, of mu]} of the time-steppers against the reference."""
    key = lambda r: (r["family"], r["point"])  # noqa: E731 (the same case set, point by point)
    ref = {key(r): r for r in _reference(rows)}
    errs, failed = defaultdict(lambda: ([], [])), defaultdict(int)
    for r in rows:
        if r["solver"] == REFERENCE:
            continue
        label = config_label(r)
        if r["status"] != "ok":
            failed[label] += 1
            continue
        exact = ref.get(key(r))
        if exact and num(exact, "pi1") > 0 and r["pi_y0"]:
            pi1, mu = errs[label]
            pi1.append(abs(num(r, "pi1") - num(exact, "pi1")) / num(exact, "pi1"))
            mu.append(abs(num(r, "mu") - num(exact, "mu")) / num(exact, "mu"))
    return errs, failed


def section(rows, out_dir):
    """The section's lines (markdown)."""
    ref = _reference(rows)
    text = ["## Yielding bodies", "",
            "Pi-spectra of `cases/sets/yielding.toml` through the exact reference: the pairs of the paper's "
            "Figs 4-5 (flexible Pi5 = 0.5 and stiff Pi5 = 2, Pi6 = 1) with body 0 bilinear with kinematic "
            "hardening (`cases/README.md`, *Yielding*), Pi_y0 from 0.1 (strongly yielding) to 2 and elastic, "
            "alpha 0, 0.05 and 0.2. The figures show alpha = " + ALPHA + "; mu is body 0's ductility demand "
            "max|u0| / u_y0.", ""]
    for family in ("yield-fig4", "yield-fig5"):
        if any(r["family"] == family for r in ref):
            text += [f"![yielding {family}]({plot_spectra(ref, family, out_dir)})", ""]
    text += ["### Which findings of the elastic case survive yielding", ""]
    spread, points = self_similarity(ref)
    if points:
        text += [f"* **Self-similarity (master curves).** At the same Pi terms, three pulse scales (a_p = g/5, "
                 f"g/2, g) give Pi1, mu and the residual within {spread:.1e} of each other (relative, over "
                 f"{points} Pi2 points of `yield-scales`): with Pi_y0 and alpha among the Pi terms, the "
                 "spectra of yielding pairs collapse as the elastic ones do."]
    amp = amplification(ref, "yield-fig")
    if amp:
        levels = sorted({level for _, level in amp})
        cells = lambda pi5: " | ".join(f"{amp.get((pi5, l), float('nan')):.3g}" for l in levels)  # noqa: E731
        text += ["* **The effect of Pi5.** Median of Pi1 over Pi1 without contact over the points where the "
                 "bodies pound (every Pi2, pulse, directivity and alpha with an impact; above 1: pounding "
                 "amplifies body 0):", "",
                 "| Pi5 | " + " | ".join("elastic" if math.isinf(l) else f"Pi_y0 = {l:g}" for l in levels) + " |",
                 "|---|" + "---:|" * len(levels),
                 f"| 0.5 (flexible) | {cells('0.5')} |", f"| 2 (stiff) | {cells('2')} |", ""]
        flexible = [amp[("0.5", l)] for l in levels if ("0.5", l) in amp]
        stiff = [amp[("2", l)] for l in levels if ("2", l) in amp]
        more = sum(f > s for f, s in zip(flexible, stiff))
        text += [f"  Pounding amplifies the flexible body 0 more than the stiff one at {more} of the "
                 f"{len(levels)} levels (elastic included), and the more the lower Pi_y0 "
                 f"({'monotonically' if flexible == sorted(flexible, reverse=True) else 'not monotonically'} "
                 f"from Pi_y0 = 0.1 to elastic); elastic: {amp.get(('0.5', math.inf), float('nan')):.3g} "
                 f"(flexible) and {amp.get(('2', math.inf), float('nan')):.3g} (stiff).", ""]
    mass = mass_ratio_effect(ref)
    if mass:
        text += ["* **The effect of Pi6.** Median over Pi2 of Pi1 at Pi6 = 2 over Pi1 at Pi6 = 0.5 (flexible "
                 "pair, cosine pulse, `yield-pi6`): " +
                 ", ".join(f"{'elastic' if math.isinf(l) else f'Pi_y0 = {l:g}'}: {v:.3g}"
                           for l, v in sorted(mass.items())) + ".", ""]
        elastic = mass.get(math.inf)
        yielding = {l: v for l, v in mass.items() if not math.isinf(l)}
        if elastic is not None and yielding:
            same = [l for l, v in yielding.items() if (v > 1) == (elastic > 1)]
            text += [f"  The elastic finding (body 0's Pi1 is {'higher' if elastic > 1 else 'lower'} beside a neighbour "
                     f"half as heavy, Pi6 = m0 / m1 = 2, than beside one twice as heavy) {'survives' if len(same) == len(yielding) else 'does not survive'} yielding: the ratio "
                     f"is on the same side of 1 at {len(same)} of {len(yielding)} yielding levels, and "
                     + ("yielding strengthens the effect at every one" if all(abs(v - 1) > abs(elastic - 1)
                                                                            for v in yielding.values())
                        else "yielding weakens the effect at every one" if all(abs(v - 1) < abs(elastic - 1)
                                                                              for v in yielding.values())
                        else "yielding strengthens it at some and weakens it at others")
                     + f" (elastic: {abs(elastic - 1):.2g} from 1).", ""]
    errs, failed = errors(rows)
    if errs or failed:
        text += ["### The time-steppers on yielding cases", "",
                 "Median and largest relative error against the reference over the yielding points of the set, "
                 "at each solver's default N (runs that failed in brackets):", "",
                 "| solver | Pi1 median | Pi1 largest | mu median | mu largest |", "|---|---:|---:|---:|---:|"]
        for label in sorted(set(errs) | set(failed)):
            pi1, mu = errs.get(label, ([], []))
            cells = [f"{median(v):.2g}" if v else "–" for v in (pi1,)] + [f"{max(pi1):.2g}" if pi1 else "–"]
            cells += [f"{median(mu):.2g}" if mu else "–", f"{max(mu):.2g}" if mu else "–"]
            note = f" ({failed[label]} failed)" if failed.get(label) else ""
            text.append(f"| {label}{note} | " + " | ".join(cells) + " |")
        text.append("")
    return text


if __name__ == "__main__":  # python3 reports/yielding.py OUT_DIR ROWS.csv...: the section alone
    import os
    import sys

    from rows import load, write_page

    out = sys.argv[1]
    os.makedirs(os.path.join(out, "figures"), exist_ok=True)
    write_page(out, section(load(sys.argv[2:]), out), "yielding.py")
