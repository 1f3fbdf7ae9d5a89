"""One line style per solver setting for the whole report: its colour, dash and marker, the
same in every figure and on the page (report.html draws with them), so that a setting looks
alike wherever it is shown and no two settings share both a colour and a dash (issue 47: ODE
and a Kelvin-Voigt reference did on the page). The dash and the marker tell the lines apart
without their colours too. No matplotlib here: the page is written without it."""

# matplotlib's tab10 without its grey, which is kept for what is not a result (the other
# solvers behind a panel, no-contact lines).
PALETTE = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#bcbd22", "#17becf"]
# On-off lengths in units of the line's width (matplotlib scales dashes by it; the page too).
DASHES = [(), (5.0, 2.0), (1.2, 1.6), (5.0, 1.6, 1.2, 1.6), (2.5, 1.6), (8.0, 2.0, 1.2, 1.6, 1.2, 1.6), (1.0, 3.5)]
MARKERS = "osD^vP<>Xh*"


def style(i):
    """The i-th style: colour, dash and marker each cycling at its own length, so that two
    settings share colour and dash only 63 (9 x 7) apart, and neighbours differ in all three."""
    return dict(color=PALETTE[i % len(PALETTE)], dash=DASHES[i % len(DASHES)], marker=MARKERS[i % len(MARKERS)])


def assign(labels):
    """Each label's style, by its place in `labels` (in the order the legends list them)."""
    return {label: style(i) for i, label in enumerate(dict.fromkeys(labels))}


def matplotlib_dash(dash):
    """A style's dash as matplotlib's linestyle."""
    return "-" if not dash else (0, dash)


def svg_dash(dash, width=1.6):
    """A style's dash as an SVG stroke-dasharray for a line `width` px wide."""
    return " ".join(f"{width * d:g}" for d in dash)
