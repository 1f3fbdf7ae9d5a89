"""The reference's Pi-spectra of the paper case set, a figure per family: Pi1 against Pi2,
with contact and without. Used by make_report.py."""

from collections import defaultdict

from matplotlib.lines import Line2D

from figure import colors, figure_width, legend_below, log_spans, save, with_legend_below
from rows import CASE_KEYS, num


def varying(rows, keys):
    return [k for k in keys if len({r[k] for r in rows}) > 1]


def sort_key(label):
    """Curve labels in numeric order where their values are numbers."""
    out = []
    for v in label:
        try:
            out.append((0, float(v), ""))
        except ValueError:
            out.append((1, 0.0, v))
    return out


NO_CONTACT = dict(color="0.45", lw=1.0, ls="--", alpha=0.8)
COINCIDE = 1e-9  # curves closer than this (relative Pi1) are one curve: drawn in decreasing widths
WIDTHS = (5.0, 2.8, 1.2)


def coinciding(curves):
    """Groups of curves (label, x, y) that lie on each other: the same grid and Pi1 within
    COINCIDE; and the largest relative difference inside a group."""
    groups, spread = [], 0.0
    for label, x, y in curves:
        for g in groups:
            gx, gy = g[0][1], g[0][2]
            if x == gx:
                diff = max(abs(a - b) / max(abs(b), 1e-300) for a, b in zip(y, gy))
                if diff < COINCIDE:
                    g.append((label, x, y))
                    spread = max(spread, diff)
                    break
        else:
            groups.append([(label, x, y)])
    return groups, spread


def plot_family(family, rows, out_dir):
    """Pi1 against Pi2: rows of panels per pulse, columns per directivity, a line per case.
    Returns the figure and a caption naming the curves that coincide, if any."""
    pulses = sorted({r["pulse"] for r in rows}, reverse=True)  # sine first, as in the paper
    directivities = sorted({r["directivity"] for r in rows})
    keys = [k for k in varying(rows, CASE_KEYS) if k not in ("pulse", "directivity")]
    labels = sorted({tuple(r[k] for k in keys) for r in rows}, key=sort_key)
    names = {label: ", ".join(f"{k}={v}" for k, v in zip(keys, label)) or family for label in labels}
    columns = 4 if max(len(n) for n in names.values()) <= 22 else 2  # a column of a 9 in figure holds ~25 characters
    fig, grid = with_legend_below(figure_width(len(directivities)), 3.3 * len(pulses) + 0.4, len(labels) + 1,
                                  columns=columns, wspace=0.18, hspace=0.3)
    fig.subplots(len(pulses), len(directivities), squeeze=False, sharex=True, gridspec_kw=grid)
    axes = [fig.axes[i * len(directivities):(i + 1) * len(directivities)] for i in range(len(pulses))]
    logy = log_spans([num(r, "pi1") for r in rows])
    palette = dict(zip(labels, colors(len(labels))))
    together = []  # coinciding curves: their labels, largest difference, whether they are all of their panel
    for pi, pulse in enumerate(pulses):
        for di, direc in enumerate(directivities):
            ax = axes[pi][di]
            by_label = defaultdict(list)
            for r in rows:
                if r["pulse"] == pulse and r["directivity"] == direc:
                    by_label[tuple(r[k] for k in keys)].append(r)
            curves = []
            for label in labels:
                crow = sorted(by_label.get(label, []), key=lambda r: num(r, "pi2"))
                curves.append((label, [num(r, "pi2") for r in crow], [num(r, "pi1") for r in crow]))
            drawn = []
            for crow in by_label.values():  # curves of the same body 0 share one no-contact line
                crow = sorted(crow, key=lambda r: num(r, "pi2"))
                free = [num(r, "pi1_no_contact") for r in crow]
                if free not in drawn:
                    drawn.append(free)
                    ax.plot([num(r, "pi2") for r in crow], free, **NO_CONTACT)
            groups, spread = coinciding([c for c in curves if c[1]])
            for group in groups:
                if len(group) > 1:
                    together.append(([names[g[0]] for g in group], spread, len(groups) == 1))
                for i, (label, x, y) in enumerate(group):
                    width = WIDTHS[i % len(WIDTHS)] if len(group) > 1 else 1.5
                    ax.plot(x, y, color=palette[label], lw=width, alpha=0.45 if width > 3 else 1.0,
                            label=names[label])
            ax.set_xscale("log")
            if logy:
                ax.set_yscale("log")
            ax.set_title(f"{pulse} pulse, {direc} directivity")
            ax.grid(True, which="both", alpha=0.25)
            if pi == len(pulses) - 1:
                ax.set_xlabel(r"$\Pi_2 = \omega_0/\omega_p$")
            if di == 0:
                ax.set_ylabel(r"$\Pi_1 = u_{0,\max}\,\omega_p^2/a_p$")
    handles, texts = axes[0][-1].get_legend_handles_labels()
    unique = dict(zip(texts, handles))
    unique["no contact"] = Line2D([], [], **NO_CONTACT)
    legend_below(fig, list(unique.values()), list(unique.keys()), columns=columns)
    fig.suptitle(f"{family}: Pi-spectra of body 0 (colour: with contact, dashed grey: no contact)")
    note = None
    if together:
        members = together[0][0]
        spread = max(t[1] for t in together)
        if all(t[2] for t in together):  # every curve of every panel on one
            note = (f"The {len(members)} curves of each panel ({'; '.join(members)}) lie exactly on each other "
                    f"(largest relative difference of Pi1 {spread:.0e}): in Pi terms the response does not depend on "
                    f"{' or '.join(keys)}" + (", which is the paper's self-similarity" if set(keys) <= {"a_p", "w_p"}
                                              else "") + ". They are drawn in decreasing widths so that each shows.")
        else:
            note = ("Some curves lie exactly on each other (largest relative difference of Pi1 "
                    f"{spread:.0e}; first: {'; '.join(members)}); they are drawn in decreasing widths so that each "
                    "shows.")
    return save(fig, out_dir, f"spectrum-{family}"), note
