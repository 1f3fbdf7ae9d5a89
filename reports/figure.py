"""Saving a figure of the reports: matplotlib without a display, and reproducible SVGs."""

import hashlib
import math
import os
import re
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
# Reproducible SVGs, so that regenerating a committed report changes a file only when its
# data changed: fixed element ids, and the creation date of reproducible builds.
matplotlib.rcParams["svg.hashsalt"] = "poundbench"
os.environ.setdefault("SOURCE_DATE_EPOCH", "0")
import matplotlib.pyplot as plt  # noqa: E402
from PIL import Image  # noqa: E402  (matplotlib's own PNG writer)
from matplotlib.ticker import FuncFormatter, LogLocator, NullLocator  # noqa: E402

from rows import config_label  # noqa: E402

DPI = 100  # a figure's pixels an inch: README shows it at its own size
# Every text of a figure at one size, the legends' too: a figure is drawn at 100 dpi no wider
# than README's column (some 830 px on GitHub), so it is shown at its own size and 10 pt reads
# as the page's text. A title stays where it is put (axes.titley): matplotlib otherwise moves
# it above the tick labels, measuring every one of them at each draw (11 of the smoke study's
# 40 profiled seconds).
matplotlib.rcParams.update({"font.size": 10, "legend.fontsize": 10, "axes.titley": 1.0, "figure.dpi": DPI})
LEGEND_LINE = 0.21  # inches a line of a legend takes at that size (measured on the stress figure: 9 in 1.9)
PAGE_WIDTH = 8.3  # inches at 100 dpi: README's column on GitHub


def figure_width(columns, per_column=4.1):
    """Inches: a figure is shown at most some 830 px wide (GitHub's page column), so at 100 dpi
    and no wider than this its text is drawn at the size it is read."""
    return min(per_column * columns + 0.8, PAGE_WIDTH)


def log_spans(values, decades=1.5):
    """Whether positive values span more than `decades` decades: an axis for them is
    logarithmic, or the smaller ones are drawn on top of each other at its foot."""
    values = [v for v in values if v > 0 and math.isfinite(v)]
    return bool(values) and max(values) / min(values) > 10 ** decades


def _legend_room(width, height, entries, columns, wspace, hspace):
    legend = LEGEND_LINE * math.ceil(entries / columns) + 0.15
    total = height + legend
    grid = dict(left=0.85 / width, right=1 - 0.15 / width, top=1 - 0.62 / total, bottom=(legend + 0.55) / total,
                wspace=wspace, hspace=hspace)
    return total, legend / total, grid


def with_legend_below(width, height, entries, columns=2, wspace=0.12, hspace=0.08):
    """A figure `width` inches wide: `height` inches of plots over room for a legend of
    `entries` entries in `columns` columns (outside the plots, where it hides no line).
    Returns the figure and the keywords of its subplots' grid (its margins in inches made
    fractions). Laid out by hand: matplotlib's constrained layout took two thirds of a
    report's time (17 of 26 s on a 16-figure study)."""
    total, fig_legend_top, grid = _legend_room(width, height, entries, columns, wspace, hspace)
    fig = plt.figure(figsize=(width, total))
    fig.legend_top = fig_legend_top  # where legend_below hangs the legend from
    return fig, grid


# A report draws many figures of a few layouts (a family's diagram, its spectra): each layout's
# figure is made once and drawn again with the next family's lines. Most of a figure's cost
# was making its axes and, at its first draw, their ticks (7,400 ticks' artists for the smoke
# study's 64 figures: half its CPU), which a figure drawn again keeps.
_kept = {}  # a layout's key -> (figure, its axes as rows of columns)


def reused_figure(key, width, height, entries, shape, columns=2, wspace=0.12, hspace=0.08, **subplots):
    """with_legend_below's figure with its grid of axes (`shape`: rows, columns; `subplots`:
    fig.subplots' sharex, sharey, gridspec_kw), the one made for `key` before when there is
    one, emptied of what was drawn on it (its lines, patches, texts, legends, titles, labels;
    its axes' scales are kept: set them). Returns the figure, its axes as rows of columns, and
    whether it is new (set what every figure of the layout shares, such as the grid, then)."""
    total, fig_legend_top, grid = _legend_room(width, height, entries, columns, wspace, hspace)
    kept = _kept.get(key)
    if kept is None:
        fig = plt.figure(figsize=(width, total))
        gridspec_kw = dict(grid, **subplots.pop("gridspec_kw", {}))
        axes = fig.subplots(*shape, squeeze=False, gridspec_kw=gridspec_kw, **subplots)
        fig.kept = True
        _kept[key] = fig, axes
    else:
        fig, axes = kept
        _empty(fig)
        fig.set_size_inches(width, total)
        axes[0][0].get_subplotspec().get_gridspec().update(**grid)
    fig.legend_top = fig_legend_top
    return fig, axes, kept is None


def _empty(fig):
    for ax in fig.axes:
        for artist in [*ax.lines, *ax.collections, *ax.patches, *ax.texts, *ax.images]:
            artist.remove()
        ax.containers.clear()
        if ax.legend_ is not None:
            ax.legend_.remove()
        for title in (ax.title, ax._left_title, ax._right_title):
            title.set_text("")
        ax.set_xlabel("")
        ax.set_ylabel("")
        ax.set_autoscale_on(True)
        ax.ignore_existing_data_limits = True  # the next lines' data alone sets the limits
    for legend in list(fig.legends):
        legend.remove()
    if fig._suptitle is not None:
        fig._suptitle.set_text("")


def label_axes(fig, bottom, left, xlabel, ylabel):
    """One x label centred under the axes of `bottom` (a row), one y label beside those of
    `left` (a column), at places set in inches from the axes: two panels side by side share
    their label rather than each writing its own into the other's (issue 47), and a label
    placed needs no measuring of the tick labels at each draw (a sixth of the drawing)."""
    xlabel_below(fig, bottom, xlabel)
    ylabel_beside(fig, left, ylabel)


def xlabel_below(fig, row, text):
    """One x label centred under a row of axes (label_axes)."""
    first, last = row[0].get_position(), row[-1].get_position()
    row[0].set_xlabel(text)
    row[0].xaxis.set_label_coords((first.x0 + last.x1) / 2, first.y0 - 0.3 / fig.get_size_inches()[1],
                                  transform=fig.transFigure)


def ylabel_beside(fig, column, text):
    """One y label beside a column of axes, its lines ending half an inch left of them (room
    for tick labels such as 10⁻¹³; label_axes)."""
    top, low = column[0].get_position(), column[-1].get_position()
    column[0].set_ylabel(text)
    column[0].yaxis.set_label_coords(top.x0 - 0.5 / fig.get_size_inches()[0], (top.y1 + low.y0) / 2,
                                     transform=fig.transFigure)


def legend_columns(width, crowd=False):
    """How many columns a legend below a figure `width` inches wide has: two where two
    entries of a setting's name (up to some 35 characters) fit side by side; one in a narrower
    figure, or for a crowd's one entry, a sentence."""
    return 1 if crowd or width < 7 else 2


def legend_below(fig, handles, labels=None, columns=2):
    labels = [h.get_label() for h in handles] if labels is None else labels
    fig.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.5, fig.legend_top), ncols=columns,
               frameon=False)


SUPERSCRIPT = str.maketrans("-0123456789", "\u207b\u2070\u00b9\u00b2\u00b3\u2074\u2075\u2076\u2077\u2078\u2079")


def _decade(x, _pos=None):
    return f"10{str(round(math.log10(x))).translate(SUPERSCRIPT)}"


def _plain(x, _pos=None):
    return f"{x:g}"


def log_ticks(axis):
    """A log axis' ticks: at 1, 2 and 5 of each decade, as plain numbers, over less than two
    and a half decades between 0.001 and 10⁴ where a decade has room for them; else at decades (at most eight), as 10 and a superscript. No minor
    ticks: making the eight of each decade's artists was 45 % of the report's drawing, and
    matplotlib's labels of powers of ten are mathtext, parsed anew for each figure (a fifth)."""
    lo, hi = sorted(axis.get_view_interval())
    box = axis.axes.get_position()
    width, height = axis.axes.figure.get_size_inches()
    length = box.width * width if axis is axis.axes.xaxis else box.height * height  # inches
    short = lo >= 1e-3 and hi < 1e4  # plain numbers of at most five characters
    if short and hi / lo < 10 ** 2.5 and length / max(math.log10(hi / lo), 0.1) > 0.8:  # room for 2 and 5
        axis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
        axis.set_major_formatter(FuncFormatter(_plain))
    else:
        axis.set_major_locator(LogLocator(numticks=8))
        axis.set_major_formatter(FuncFormatter(_decade))
    axis.set_minor_locator(NullLocator())


def _write(fig, path, vector):
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            if axis.get_scale() == "log":
                log_ticks(axis)
    # Renamed into place: never a half-written figure. The PNG in 256 colours: a figure of lines
    # has few more, and it is a third of the file and of the time to encode (PIL's RGBA encoder
    # took 30 ms a figure, an eighth of the report).
    fig.canvas.draw()
    pixels = Image.frombuffer("RGBA", fig.canvas.get_width_height(), fig.canvas.buffer_rgba(), "raw", "RGBA", 0, 1)
    pixels.convert("RGB").quantize(256, method=Image.Quantize.FASTOCTREE).save(f"{path}.tmp.png", format="png")
    os.replace(f"{path}.tmp.png", f"{path}.png")
    if vector:
        fig.savefig(f"{path}.tmp.svg", dpi=DPI)
        os.replace(f"{path}.tmp.svg", f"{path}.svg")


def clipped(text, most=60):
    """A name as a figure shows it: one line of at most `most` characters (a legend entry of a
    5,000-character family is wider than any figure)."""
    text = " ".join(str(text).splitlines())
    return text if len(text) <= most else text[:most - 1] + "…"


def title_room(fig):
    """How many characters of a figure's title (12 pt) fit its width."""
    return int(fig.get_size_inches()[0] * 11.5)


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
    """Writes figures/STEM.png, and .svg unless `vector` is false, under out_dir, STEM made a
    file's name (file_stem); returns the PNG's path relative to out_dir. A figure of
    reused_figure is kept for the next of its layout; any other is closed."""
    stem = file_stem(stem)
    _write(fig, os.path.join(out_dir, "figures", stem), vector)
    if not getattr(fig, "kept", False):
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
