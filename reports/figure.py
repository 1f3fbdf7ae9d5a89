"""Saving a figure of the reports: matplotlib without a display, and reproducible SVGs."""

import os
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
# Reproducible SVGs, so that regenerating a committed report changes a file only when its
# data changed: fixed element ids, and the creation date of reproducible builds.
matplotlib.rcParams["svg.hashsalt"] = "poundbench"
os.environ.setdefault("SOURCE_DATE_EPOCH", "0")
import matplotlib.pyplot as plt  # noqa: E402

from rows import config_label  # noqa: E402


def save(fig, out_dir, stem, vector=True):
    """Writes figures/STEM.png, and .svg unless `vector` is false, under out_dir; returns the
    PNG's path relative to it."""
    path = os.path.join(out_dir, "figures", stem)
    for ext in ("png", "svg") if vector else ("png",):
        fig.savefig(f"{path}.{ext}", dpi=100)
    plt.close(fig)
    return f"figures/{stem}.png"


# Colours for lines that must be told apart: matplotlib's tab10 and tab20 without their greys,
# which are kept for what is not a result (no-contact lines, other solvers drawn for context).
DISTINCT = [c for i, c in enumerate(plt.get_cmap("tab10").colors) if i != 7]
PAIRED = [c for i, c in enumerate(plt.get_cmap("tab20").colors) if i not in (14, 15)]
MARKERS = "osD^vP<>Xh*"  # with the colours, so that lines of close colours still tell apart


def colors(n):
    """n colours, none of them grey: DISTINCT while it lasts, then PAIRED (a dark and a light
    shade of each hue), else evenly along viridis."""
    for palette in (DISTINCT, PAIRED):
        if n <= len(palette):
            return palette[:n]
    return [plt.get_cmap("viridis")(0.92 * i / max(n - 1, 1)) for i in range(n)]


VARIANT_STYLES = ["-", "--", ":", "-.", (0, (5, 1, 1, 1, 1, 1)), (0, (1, 3)), (0, (8, 2))]


def solver_styles(rows):
    """A line style per configuration: a colour per solver, a dash pattern and a marker per
    configuration of that solver, so that many overlapping lines still tell apart."""
    by_solver = defaultdict(list)
    for label, solver in sorted({(config_label(r), r["solver"]) for r in rows}):
        by_solver[solver].append(label)
    palette = colors(len(by_solver))
    return {label: dict(color=palette[i], ls=VARIANT_STYLES[j % len(VARIANT_STYLES)], marker=MARKERS[j % len(MARKERS)])
            for i, labels in enumerate(by_solver.values()) for j, label in enumerate(labels)}
