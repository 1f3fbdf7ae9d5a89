"""The reference's Pi-spectra of the paper case set, a figure per family: Pi1 against Pi2,
with contact and without. Used by make_report.py."""

from collections import defaultdict

from matplotlib.lines import Line2D

from figure import clipped, colors, title_room, figure_width, joined, legend_below, log_spans, save, with_legend_below
from rows import CASE_KEYS, num
from styles import DASHES, matplotlib_dash


def varying(rows, keys):
    return [k for k in keys if len({r.get(k, "") for r in rows}) > 1]


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


# A family's figure has a row of panels per pulse and a column per directivity, up to these
# many (a case set has at most four pulses and two directivities; more panels than this would
# be too small to read), and a line per case up to MAX_LINES: more are drawn as a crowd, in
# one colour, with one legend entry (past 18 colours nobody tells lines apart).
MAX_ROWS, MAX_COLUMNS, MAX_LINES = 4, 4, 18


def plot_family(family, rows, out_dir):
    """Pi1 against Pi2: rows of panels per pulse, columns per directivity, a line per case.
    Returns the figure and a caption naming the curves that coincide, if any."""
    all_pulses = sorted({r["pulse"] for r in rows}, reverse=True)  # sine first, as in the paper
    all_directivities = sorted({r["directivity"] for r in rows})
    pulses, directivities = all_pulses[:MAX_ROWS], all_directivities[:MAX_COLUMNS]
    keys = [k for k in varying(rows, CASE_KEYS) if k not in ("pulse", "directivity")]
    labels = sorted({tuple(r.get(k, "") for k in keys) for r in rows}, key=sort_key)
    crowd = len(labels) > MAX_LINES
    names = {label: clipped(", ".join(f"{k}={v}" for k, v in zip(keys, label)) or family) for label in labels}
    columns = 4 if max(len(n) for n in names.values()) <= 22 else 2  # a column of a 9 in figure holds ~25 characters
    columns = 1 if crowd else columns
    fig, grid = with_legend_below(figure_width(len(directivities)), 3.3 * len(pulses) + 0.4,
                                  2 if crowd else len(labels) + 1, columns=columns, wspace=0.18, hspace=0.3)
    fig.subplots(len(pulses), len(directivities), squeeze=False, sharex=True, gridspec_kw=grid)
    axes = [fig.axes[i * len(directivities):(i + 1) * len(directivities)] for i in range(len(pulses))]
    logy = log_spans([num(r, "pi1") for r in rows])
    palette = dict(zip(labels, colors(0 if crowd else len(labels))))
    dashes = {label: matplotlib_dash(DASHES[i % len(DASHES)]) for i, label in enumerate(labels)}  # without colour too
    together = []  # coinciding curves: their labels, largest difference, whether they are all of their panel
    for pi, pulse in enumerate(pulses):
        for di, direc in enumerate(directivities):
            ax = axes[pi][di]
            by_label = defaultdict(list)
            for r in rows:
                if r["pulse"] == pulse and r["directivity"] == direc:
                    by_label[tuple(r.get(k, "") for k in keys)].append(r)
            curves = []
            for label in labels:
                crow = sorted(by_label.get(label, []), key=lambda r: num(r, "pi2"))
                curves.append((label, [num(r, "pi2") for r in crow], [num(r, "pi1") for r in crow]))
            drawn, free_lines = set(), []
            for crow in by_label.values():  # curves of the same body 0 share one no-contact line
                crow = sorted(crow, key=lambda r: num(r, "pi2"))
                free = tuple(num(r, "pi1_no_contact") for r in crow)
                if free not in drawn:
                    drawn.add(free)
                    free_lines.append(([num(r, "pi2") for r in crow], free))
            if crowd:  # one artist each for every case's line and every no-contact line: a NaN between two
                ax.plot(*joined(free_lines), **NO_CONTACT)
                ax.plot(*joined([c[1:] for c in curves]), color="tab:blue", lw=0.6, alpha=0.35,
                        label=f"{len(labels)} cases, too many to tell apart (report.html names each)")
            else:
                for x, free in free_lines:
                    ax.plot(x, free, **NO_CONTACT)
            groups, spread = coinciding([c for c in curves if c[1]]) if not crowd else ([], 0.0)
            for group in groups:
                if len(group) > 1:
                    together.append(([names[g[0]] for g in group], spread, len(groups) == 1))
                for i, (label, x, y) in enumerate(group):
                    width = WIDTHS[i % len(WIDTHS)] if len(group) > 1 else 1.5
                    ax.plot(x, y, color=palette[label], lw=width, alpha=0.45 if width > 3 else 1.0,
                            ls="-" if len(group) > 1 else dashes[label], label=names[label])
            ax.set_xscale("log")
            if logy:
                ax.set_yscale("log")
            ax.set_title(clipped(f"{pulse} pulse, {direc} directivity"))
            ax.grid(True, which="both", alpha=0.25)
            if pi == len(pulses) - 1:
                ax.set_xlabel("Π₂ = ω₀/ωₚ")
            if di == 0:
                ax.set_ylabel("Π₁ = u₀,max ωₚ²/aₚ")
    handles, texts = axes[0][-1].get_legend_handles_labels()
    unique = dict(zip(texts, handles))
    unique["no contact"] = Line2D([], [], **NO_CONTACT)
    legend_below(fig, list(unique.values()), list(unique.keys()), columns=columns)
    left_out = "" if (pulses, directivities) == (all_pulses, all_directivities) else \
        f"; the first {len(pulses)} of {len(all_pulses)} pulses, {len(directivities)} of {len(all_directivities)} " \
        "directivities"
    fig.suptitle(clipped(f"{family}: Pi-spectra of body 0{left_out}", title_room(fig)))
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
