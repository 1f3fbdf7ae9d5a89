"""Saving a figure of the reports: matplotlib without a display, and reproducible SVGs."""

import atexit
import hashlib
import math
import os
import re
import sys
import traceback
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
# Reproducible SVGs, so that regenerating a committed report changes a file only when its
# data changed: fixed element ids, and the creation date of reproducible builds.
matplotlib.rcParams["svg.hashsalt"] = "poundbench"
os.environ.setdefault("SOURCE_DATE_EPOCH", "0")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import LogLocator  # noqa: E402

from rows import config_label  # noqa: E402

# Every text of a figure at one size, the legends' too: a figure is drawn at 100 dpi no
# wider than the page column it is shown in (some 900 px), so 10 pt reads as the page's text.
matplotlib.rcParams.update({"font.size": 10, "legend.fontsize": 10})
LEGEND_LINE = 0.21  # inches a line of a legend takes at that size (measured on the stress figure: 9 in 1.9)


def figure_width(columns, per_column=4.6):
    """Inches: a figure is shown at most some 900 px wide (GitHub's page column), so at 100 dpi
    and no wider than this its text is drawn at the size it is read."""
    return min(per_column * columns + 0.8, 9.2)


def log_spans(values, decades=1.5):
    """Whether positive values span more than `decades` decades: an axis for them is
    logarithmic, or the smaller ones are drawn on top of each other at its foot."""
    values = [v for v in values if v > 0 and math.isfinite(v)]
    return bool(values) and max(values) / min(values) > 10 ** decades


def with_legend_below(width, height, entries, columns=2, wspace=0.12, hspace=0.08):
    """A figure `width` inches wide: `height` inches of plots over room for a legend of
    `entries` entries in `columns` columns (outside the plots, where it hides no line).
    Returns the figure and the keywords of its subplots' grid (its margins in inches made
    fractions). Laid out by hand: matplotlib's constrained layout took two thirds of a
    report's time (17 of 26 s on a 16-figure study)."""
    legend = LEGEND_LINE * math.ceil(entries / columns) + 0.15
    total = height + legend
    fig = plt.figure(figsize=(width, total))
    fig.legend_top = legend / total  # where legend_below hangs the legend from
    grid = dict(left=0.85 / width, right=1 - 0.15 / width, top=1 - 0.62 / total, bottom=(legend + 0.55) / total,
                wspace=wspace, hspace=hspace)
    return fig, grid


def legend_below(fig, handles, labels=None, columns=2):
    labels = [h.get_label() for h in handles] if labels is None else labels
    fig.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.5, fig.legend_top), ncols=columns,
               frameon=False)


# Drawing is nearly all of a report's time (115 of 139 s of the main job's report, profiled:
# savefig's draw, most of it ticks), and each figure is drawn alone: a figure is drawn in a
# child process forked when it is saved, as many at once as this process may use cores, while
# the report goes on to the next. finish() waits for them; it runs at exit too.
_DRAWERS = len(os.sched_getaffinity(0))
_drawing = {}  # pid -> the figure's stem, oldest first
_failed = []  # the stems whose drawing failed


def _write(fig, path, vector):
    # Log axes get minor ticks at 2 and 5 of each decade, not at all eight: the grid reads the
    # same, and making the eight ticks' artists was 45 % of the report's drawing (72 -> 39 s of
    # CPU over the main job's 130 figures).
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            if axis.get_scale() == "log":
                axis.set_minor_locator(LogLocator(subs=(2.0, 5.0)))
    for ext in ("png", "svg") if vector else ("png",):
        fig.savefig(f"{path}.tmp.{ext}", dpi=100)  # renamed into place: never a half-written figure
        os.replace(f"{path}.tmp.{ext}", f"{path}.{ext}")


def _wait_oldest():
    # Its own pid, never any child: os.wait() could reap a subprocess the report runs.
    pid = next(iter(_drawing))
    _, status = os.waitpid(pid, 0)
    stem = _drawing.pop(pid)
    if os.waitstatus_to_exitcode(status) != 0:
        _failed.append(stem)


def finish():
    """Waits until every figure saved so far is written; raises if one could not be."""
    while _drawing:
        _wait_oldest()
    if _failed:
        stems = ", ".join(_failed)
        _failed.clear()
        raise RuntimeError(f"figure {stems}: drawing it failed (the error is above)")


def abandon():
    """Waits until every drawing child has ended, and forgets their failures: the report they
    draw for is given up (its folder is removed next)."""
    while _drawing:
        _wait_oldest()
    _failed.clear()


def _finish_at_exit():
    try:
        finish()
    except RuntimeError as e:
        print(f"{os.path.basename(sys.argv[0])}: {e}", file=sys.stderr)
        os._exit(1)


atexit.register(_finish_at_exit)


def clipped(text, most=60):
    """A name as a figure shows it: one line of at most `most` characters (a legend entry of a
    5,000-character family is wider than any figure)."""
    text = " ".join(str(text).splitlines())
    return text if len(text) <= most else text[:most - 1] + "…"


def joined(lines):
    """Lines, each (x, y), as the x and y of one artist with a NaN between two lines (where
    matplotlib breaks a line): any number of lines drawn alike for the cost of one."""
    lines = list(lines)
    return [v for x, _ in lines for v in [*x, math.nan]], [v for _, y in lines for v in [*y, math.nan]]


FILE_NAME = re.compile(r"[A-Za-z0-9._+=-]{1,100}")


def file_stem(name):
    """A figure's name as a file's: itself where it is made of letters, digits and ._+=- and
    at most 100 characters (every name of the shipped studies); otherwise those characters of
    it, others as '-', its first 60, then a hash of the whole name, so that names that differ
    (a family "a/b" and one "a|b") never share a file, and a family's '/' or 5,000 characters
    never make a path that cannot be created."""
    if FILE_NAME.fullmatch(name) and not name.startswith("."):
        return name
    kept = re.sub(r"[^A-Za-z0-9._+=-]", "-", name)[:60].lstrip(".")
    return f"{kept}-{hashlib.sha256(name.encode('utf-8', 'surrogatepass')).hexdigest()[:10]}"


def save(fig, out_dir, stem, vector=True):
    """Writes figures/STEM.png, and .svg unless `vector` is false, under out_dir (drawn by a
    child process: finish() waits for it), STEM made a file's name (file_stem); returns the
    PNG's path relative to out_dir."""
    stem = file_stem(stem)
    path = os.path.join(out_dir, "figures", stem)
    if _DRAWERS < 2:
        _write(fig, path, vector)
    else:
        while len(_drawing) >= _DRAWERS:
            _wait_oldest()
        sys.stdout.flush()
        sys.stderr.flush()
        pid = os.fork()
        if pid == 0:  # the child draws, and leaves without the parent's exit handlers
            code = 0
            try:
                _write(fig, path, vector)
            except BaseException:
                traceback.print_exc()
                code = 1
            sys.stderr.flush()
            os._exit(code)
        _drawing[pid] = stem
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
