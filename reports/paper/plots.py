"""The figures of the paper report. Each function draws one figure from curves
(analysis.Curve) and returns its path relative to the report (figure.save)."""

import math

import numpy as np
from matplotlib.lines import Line2D

import analysis
from styles import DASHES, matplotlib_dash
from figure import PAGE_WIDTH, plt, save  # reports/figure.py: matplotlib set up for files

# Every figure is README's width (PAGE_WIDTH at 100 dpi: shown at its own size) and laid out by
# hand in inches: tight_layout measured every tick label of every panel twice a figure, half of
# the paper report's drawing.

PI1 = "Π₁ = u₀,ₘₐₓ ωₚ²/aₚ"
PI2 = "Π₂ = ω₀/ωₚ"
NO_CONTACT = dict(color="0.45", lw=1.0, ls="--", alpha=0.8, zorder=3)  # on top: visible where contact changes nothing
PULSES = ("sine", "cosine")  # rows of the paper's figures, sine first


def _margins(fig, left, right, top, bottom, **space):
    """The plots' margins in inches (the figure's size made fractions), and their spacing."""
    width, height = fig.get_size_inches()
    fig.subplots_adjust(left=left / width, right=1 - right / width, top=1 - top / height, bottom=bottom / height,
                        **space)


def _dash(i):
    """The i-th line's dash (styles.py's): lines of a panel tell apart without their colours."""
    return matplotlib_dash(DASHES[i % len(DASHES)])


def _spectrum_axes(ax, title, yscale="log"):
    ax.set_xscale("log")
    ax.set_yscale(yscale)
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="both", alpha=0.25)


def _no_contact(ax, curve_list):
    """The no-contact line: body 0 alone, the same for every curve of a panel that shares
    its Pi2 grid (Pi5 and Pi6 do not enter it)."""
    drawn = []
    for c in curve_list:
        if not any(len(d) == len(c.x) and np.allclose(d, c.pi1_nc, rtol=1e-12) for d in drawn):
            drawn.append(c.pi1_nc)
            ax.plot(c.x, c.pi1_nc, **NO_CONTACT)


def _legend(ax, title, loc="lower left"):
    handles, labels = ax.get_legend_handles_labels()
    handles.append(Line2D([], [], **NO_CONTACT))
    labels.append("no contact")
    ax.legend(handles, labels, title=title, fontsize=8, title_fontsize=8, loc=loc, ncol=1)


def fig3(by_amplitude, by_duration, note, out_dir):
    """Left: u_max in metres against T0 in seconds; right: the same curves in Pi terms,
    with a note (the measured spread) in the corner."""
    fig, (phys, pi) = plt.subplots(1, 2, figsize=(PAGE_WIDTH, 4.4))
    _margins(fig, left=0.75, right=0.15, top=0.6, bottom=0.55, wspace=0.3)
    # the amplitudes in lines of decreasing width, so that all show where they coincide; the durations dashed
    styles = [dict(lw=5.0, alpha=0.35), dict(lw=2.8, alpha=0.7), dict(lw=1.2)]
    lines = [(c, dict(color=f"C{i}", **styles[i % 3]))
             for i, c in enumerate(sorted(by_amplitude, key=lambda c: float(c["a_p"])))]
    lines += [(c, dict(color=f"C{len(by_amplitude) + i}", lw=1.0, ls=(0, (4, 2))))
              for i, c in enumerate(sorted(by_duration, key=lambda c: float(c["w_p"])))]
    for c, style in lines:
        a_p, w_p = float(c["a_p"]), float(c["w_p"])
        label = f"aₚ = {a_p:.3g} m/s², Tₚ = {2 * math.pi / w_p:.3g} s"
        t0 = 2 * math.pi / (c.x * w_p)
        phys.plot(t0, c.pi1 * a_p / w_p ** 2, label=label, **style)
        phys.plot(t0, c.pi1_nc * a_p / w_p ** 2, color=style["color"], lw=0.8, alpha=0.45)
        pi.plot(c.x, c.pi1, label=label, **style)
        pi.plot(c.x, c.pi1_nc, color=style["color"], lw=0.8, alpha=0.45)
    for ax in (phys, pi):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.grid(True, which="both", alpha=0.25)
    phys.set_xlabel("T₀ = 2π/ω₀ (s)")
    phys.set_ylabel("u₀,ₘₐₓ (m)")
    phys.set_title("physical units", fontsize=10)
    pi.set_xlabel(PI2)
    pi.set_ylabel(PI1)
    pi.set_title("Pi terms: one master curve", fontsize=10)
    pi.text(0.03, 0.05, note, transform=pi.transAxes, fontsize=8)
    phys.legend(fontsize=8, loc="lower right", title="heavy: contact, light: no contact", title_fontsize=8)
    fig.suptitle("Fig. 3: asymmetric row3 (Π₅ = 0.5, Π₆ = 2, Π₇ = 2, Π₈ = 0.5), cosine pulse, Π₃ = 0.5", fontsize=11)
    return save(fig, out_dir, "fig3-self-similarity")


def _save_grid(fig, axes, title, out_dir, stem):
    """A 2 x 2 grid of spectra: Pi2 under the bottom row, Pi1 beside the left column, the title."""
    for ax in axes[1]:
        ax.set_xlabel(PI2)
    for row in axes:
        row[0].set_ylabel(PI1)
    fig.suptitle(title, fontsize=11)
    return save(fig, out_dir, stem)


def pi5_spectra(curve_list, title, stem, out_dir):
    """Figs 4, 5, 7: rows pulses, columns the flexible (Pi5 < 1) and the stiff (Pi5 > 1)
    body 0, a line per Pi5."""
    fig, axes = plt.subplots(2, 2, figsize=(PAGE_WIDTH, 7.4), sharex=True)
    _margins(fig, left=0.75, right=0.15, top=0.65, bottom=0.55, wspace=0.22, hspace=0.2)
    for row, pulse in enumerate(PULSES):
        for col, (name, flexible) in enumerate((("flexible body 0", True), ("stiff body 0", False))):
            ax = axes[row][col]
            panel = sorted((c for c in analysis.select(curve_list, pulse=pulse) if (float(c["pi5"]) < 1) == flexible),
                           key=lambda c: float(c["pi5"]))
            _no_contact(ax, panel)
            for i, c in enumerate(panel):
                ax.plot(c.x, c.pi1, color=f"C{i}", lw=1.5, ls=_dash(i), label=f"{float(c['pi5']):g}")
            _spectrum_axes(ax, f"{pulse} pulse, {name}")
            _legend(ax, "Π₅ = ω₀/ω₁")
    return _save_grid(fig, axes, title, out_dir, stem)


def pi6_spectra(curve_list, title, stem, out_dir):
    """Figs 8, 9: rows pulses, columns directivities, a line per Pi6. Linear Pi1: the mass
    ratio matters where Pi1 is large."""
    fig, axes = plt.subplots(2, 2, figsize=(PAGE_WIDTH, 7.4), sharex=True, sharey="row")
    _margins(fig, left=0.75, right=0.15, top=0.65, bottom=0.55, wspace=0.08, hspace=0.2)
    colors = plt.get_cmap("viridis")
    for row, pulse in enumerate(PULSES):
        for col, direc in enumerate(("normal", "reverse")):
            ax = axes[row][col]
            panel = sorted(analysis.select(curve_list, pulse=pulse, directivity=direc), key=lambda c: float(c["pi6"]))
            _no_contact(ax, panel)
            for i, c in enumerate(panel):
                ax.plot(c.x, c.pi1, color=colors(i / max(len(panel) - 1, 1) * 0.92), lw=1.4, ls=_dash(i),
                        label=f"{float(c['pi6']):g}")
            _spectrum_axes(ax, f"{pulse} pulse, {direc} directivity", yscale="linear")
            _legend(ax, "Π₆ = m₀/m₁", loc="upper right")
    return _save_grid(fig, axes, title, out_dir, stem)


def histories(panels, out_dir):
    """Fig. 6: one row per panel (dict: title, contact and free histories, impact times,
    tp = T_p, length = a_p / w_p^2): u0 and u1 against t / T_p with and without contact,
    impacts marked on u0."""
    fig, axes = plt.subplots(len(panels), 1, figsize=(PAGE_WIDTH, 3.3 * len(panels)), squeeze=False)
    _margins(fig, left=0.75, right=0.15, top=0.6, bottom=0.55, hspace=0.4)
    for ax, p in zip(axes[:, 0], panels):
        hist, free, tp, length = p["contact"], p["free"], p["tp"], p["length"]
        ax.plot(free["t"] / tp, free["u0"] / length, color="0.55", lw=1.2, ls="--", label="u₀, no contact")
        ax.plot(hist["t"] / tp, hist["u1"] / length, color="C1", lw=1.0, label="u₁ (neighbour), with contact")
        ax.plot(hist["t"] / tp, hist["u0"] / length, color="C0", lw=1.8, label="u₀, with contact")
        ax.plot(p["impacts"] / tp, np.interp(p["impacts"], hist["t"], hist["u0"]) / length, "v", color="k", ms=5,
                label=f"impact ({len(p['impacts'])})")
        ax.axvline(1.0, color="0.3", lw=0.8, ls=":")
        ax.set_title(p["title"], fontsize=10)
        ax.set_ylabel("u ωₚ²/aₚ")
        ax.grid(True, alpha=0.25)
        ax.legend(fontsize=8, loc="upper right", ncol=2)
    axes[-1][0].set_xlabel("t/Tₚ (dotted: end of the pulse)")
    fig.suptitle("Fig. 6: contact amplifies the flexible (top) and the stiff (bottom) body 0", fontsize=11)
    return save(fig, out_dir, "fig6-time-histories")


def fig10(fitted, out_dir):
    """ln Pi1 against ln Pi6 at fixed Pi2 from (curve, its branches) pairs: points where
    contact changed Pi1 filled, the others open; the fitted branches dashed."""
    panels = sorted({(c["pulse"], c["pi5"]) for c, _ in fitted}, key=lambda k: (PULSES.index(k[0]), float(k[1])))
    fig, axes = plt.subplots(2, 2, figsize=(PAGE_WIDTH, 7.8), sharex=True)
    _margins(fig, left=0.75, right=0.15, top=0.75, bottom=1.25, wspace=0.22, hspace=0.2)
    for ax, (pulse, pi5) in zip(axes.flat, panels):
        panel = sorted(((c, b) for c, b in fitted if c["pulse"] == pulse and c["pi5"] == pi5),
                       key=lambda cb: float(cb[0]["pi2"]))
        for i, (c, fits) in enumerate(panel):
            x, y = np.log(c.x), np.log(c.pi1)
            same = np.abs(c.ratio - 1) < analysis.UNCHANGED
            color = f"C{i}"
            ax.plot(x, y, color=color, lw=1.0, label=f"{float(c['pi2']):g}")
            ax.plot(x[~same], y[~same], "o", color=color, ms=3.2)
            ax.plot(x[same], y[same], "o", mfc="none", color=color, ms=3.2)
            for b in (b for b in fits if b.kind != "no effect"):  # flat by construction: the open points
                bx = np.log([b.lo, b.hi])
                ax.plot(bx, math.log(b.intercept) + b.slope * bx, color="k", lw=1.0, ls="--")
        ax.set_title(f"{pulse} pulse, Π₅ = {float(pi5):g}", fontsize=10)
        ax.grid(True, alpha=0.25)
    for ax in axes[1]:
        ax.set_xlabel("ln Π₆ = ln(m₀/m₁)")
    for ax in axes[:, 0]:
        ax.set_ylabel("ln Π₁")
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, title="Π₂ = ω₀/ωₚ", loc="lower center", ncol=5, fontsize=9,
               title_fontsize=9, frameon=False)
    fig.suptitle("Fig. 10: pair, normal directivity.\nFilled: contact changed Pi1; open: it did not; "
                 "dashed: fitted sloped branches", fontsize=10.5)
    return save(fig, out_dir, "fig10-scaling")


def pi5_limit(rows, out_dir):
    """Largest and smallest Pi1 / Pi1_nc over Pi2 against Pi5: rows of
    (pulse, pi5, largest, smallest)."""
    fig, ax = plt.subplots(figsize=(PAGE_WIDTH, 4.6))
    _margins(fig, left=0.85, right=0.2, top=0.45, bottom=0.55)
    for i, pulse in enumerate(PULSES):
        pts = sorted((r for r in rows if r[0] == pulse), key=lambda r: r[1])
        x = [r[1] for r in pts]
        ax.plot(x, [r[2] for r in pts], "o-", color=f"C{i}", ms=4, label=f"{pulse}: largest over Π₂")
        ax.plot(x, [r[3] for r in pts], "s--", color=f"C{i}", ms=4, mfc="none",
                label=f"{pulse}: smallest over Π₂")
    ax.axvline(1.0, color="0.3", lw=0.8, ls=":")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("Π₅ = ω₀/ω₁")
    ax.set_ylabel("Π₁ / Π₁ without contact")
    ax.grid(True, which="both", alpha=0.25)
    ax.legend(fontsize=8)
    ax.set_title("pair, Π₆ = 1, normal directivity: contact's effect vanishes as Π₅ → 1", fontsize=10)
    return save(fig, out_dir, "pi5-limit")


EFFECT_COLORS = {"amplified": "#d62728", "deamplified": "#1f77b4", "none": "#dddddd"}
EFFECT_HATCHES = {"amplified": "////", "deamplified": "", "none": ""}  # red and blue are one grey without colour


def region_map(groups, out_dir):
    """One panel per (title, curves): each spectrum as a strip along Pi2 coloured by the
    effect of contact; Pi2 = 1 dotted, Pi2 = Pi5 marked."""
    fig, axes = plt.subplots(1, len(groups), figsize=(PAGE_WIDTH, 6.4), sharey=True)
    _margins(fig, left=0.95, right=0.2, top=0.65, bottom=1.0, wspace=0.14)
    kinds = list(EFFECT_COLORS)
    for ax, (title, curve_list) in zip(np.atleast_1d(axes), groups):
        labels = []
        for j, c in enumerate(curve_list):
            # each grid point owns the stretch between the geometric midpoints to its neighbours
            edges = np.concatenate([[c.x[0]], np.sqrt(c.x[1:] * c.x[:-1]), [c.x[-1]]])
            kind = analysis.effect(c)
            starts = np.flatnonzero(np.concatenate([[True], kind[1:] != kind[:-1]]))
            ends = np.append(starts[1:], len(kind))
            for a, b in zip(starts, ends):
                ax.broken_barh([(edges[a], edges[b] - edges[a])], (j - 0.4, 0.8), facecolors=EFFECT_COLORS[kind[a]],
                               hatch=EFFECT_HATCHES[kind[a]], edgecolor="white", linewidth=0)
            ax.plot(float(c["pi5"]), j, "k|", ms=9, mew=1.5)
            labels.append(f"{c['pulse']} {float(c['pi5']):g}")
        ax.axvline(1.0, color="k", lw=0.8, ls=":")
        ax.set_xscale("log")
        ax.set_xlim(curve_list[0].x[0], curve_list[0].x[-1])
        ax.set_yticks(range(len(labels)))
        ax.set_yticklabels(labels, fontsize=8)
        ax.invert_yaxis()
        ax.set_title(title, fontsize=10)
        ax.set_xlabel(PI2)
    handles = [plt.Rectangle((0, 0), 1, 1, facecolor=EFFECT_COLORS[k], hatch=EFFECT_HATCHES[k], edgecolor="white",
                             linewidth=0) for k in kinds]
    handles.append(Line2D([], [], color="k", marker="|", ls="none", ms=9, mew=1.5))
    fig.legend(handles, [f"amplified (> +{analysis.NO_EFFECT:.0%})", f"deamplified (< -{analysis.NO_EFFECT:.0%})",
                         "no effect", "Π₂ = Π₅"], loc="lower center", ncol=4, fontsize=9, frameon=False)
    fig.suptitle("Effect of contact on Pi1 along Pi2, per spectrum (rows: pulse and Pi5)", fontsize=11)
    return save(fig, out_dir, "regions")
