"""The measurements of the paper report, from the reference's result rows: curves, the
collapse of Fig. 3, spectral regions, local maxima, peaks and the scaling-law branches of
Fig. 10. No plotting (plots.py) and no text (make_paper.py) here."""

import itertools
import math
from collections import defaultdict
from dataclasses import dataclass

import numpy as np

from rows import CASE_KEYS, num  # reports/rows.py

# Below this relative change of Pi1, contact left the maximum as it was (no impact, or
# none that changed it). Far above the reference's error (~1e-9).
UNCHANGED = 1e-6
# Contact changes Pi1 by less than this fraction: the "no effect" region of a spectrum.
NO_EFFECT = 0.02
# "Near" a value of Pi2: within this factor of it.
NEAR = 1.25
# The fewest grid points of a spectral region or a Fig. 10 branch.
MIN_RUN = 3
MIN_BRANCH = 4


def near(a, b):
    """Whether two values of Pi2 are within a factor NEAR of each other."""
    return abs(math.log(a / b)) <= math.log(NEAR)


@dataclass
class Curve:
    """One line of a figure: Pi1 with and without contact along one abscissa (Pi2 or Pi6)."""
    family: str
    case: dict  # the case keys shared by every point (pulse, directivity, pi5, ...)
    x: np.ndarray
    pi1: np.ndarray
    pi1_nc: np.ndarray
    impacts: np.ndarray
    rows: list  # the result rows, in the order of x

    def __getitem__(self, key):
        return self.case[key]

    @property
    def ratio(self):
        return self.pi1 / self.pi1_nc


def families(rows):
    """Every family's curves, by family name: along Pi2, or along Pi6 for a family with more
    Pi6 than Pi2 values (fig10)."""
    grouped = defaultdict(list)
    for r in rows:
        grouped[r["family"]].append(r)
    return {name: curves(frows, "pi6" if len({r["pi6"] for r in frows}) > len({r["pi2"] for r in frows}) else "pi2")
            for name, frows in grouped.items()}


def curves(rows, along):
    """The rows of one family as curves along `along`, one per combination of the other
    case keys, in file order."""
    keys = [k for k in CASE_KEYS + ["pi2"] if k != along]
    groups = defaultdict(list)
    for r in rows:
        groups[tuple(r[k] for k in keys)].append(r)
    out = []
    for label, grows in groups.items():
        grows.sort(key=lambda r: num(r, along))
        column = lambda key: np.array([num(r, key) for r in grows])  # noqa: E731
        out.append(Curve(grows[0]["family"], dict(zip(keys, label)), column(along), column("pi1"),
                         column("pi1_no_contact"), column("impacts"), grows))
    return out


def select(curve_list, **case):
    """The curves whose case has every given key at the given value (compared as text)."""
    return [c for c in curve_list if all(c[k] == str(v) for k, v in case.items())]


def joined(a, b):
    """Two curves of the same case on adjacent abscissa ranges as one curve."""
    x = np.concatenate([a.x, b.x])
    order = np.argsort(x, kind="stable")
    keep = np.concatenate([[True], np.diff(x[order]) > 1e-12 * x[order][1:]])
    pick = order[keep]
    return Curve(a.family + "+" + b.family, a.case, x[pick], np.concatenate([a.pi1, b.pi1])[pick],
                 np.concatenate([a.pi1_nc, b.pi1_nc])[pick], np.concatenate([a.impacts, b.impacts])[pick],
                 [(a.rows + b.rows)[i] for i in pick])


# ---------------------------------------------------------------- Fig. 3: the collapse

def largest_spread(curve_list, values="pi1"):
    """The largest relative spread (max - min) / max of Pi1 between curves on one grid,
    and the abscissa where it occurs."""
    y = np.array([getattr(c, values) for c in curve_list])
    spread = (y.max(axis=0) - y.min(axis=0)) / y.max(axis=0)
    i = int(np.argmax(spread))
    return float(spread[i]), float(curve_list[0].x[i])


# ---------------------------------------------------------------- spectra

def peak(curve, values="pi1"):
    """(Pi2 of the largest value, the value, whether it is an end of the grid)."""
    y = getattr(curve, values)
    i = int(np.argmax(y))
    return float(curve.x[i]), float(y[i]), i in (0, len(y) - 1)


def local_maxima(curve):
    """Indices of the interior grid points higher than the point before and at least as
    high as the point after."""
    y = curve.pi1
    return [i for i in range(1, len(y) - 1) if y[i] > y[i - 1] and y[i] >= y[i + 1]]


def nearest_local_maximum(curve, target):
    """The interior local maximum of Pi1 nearest to Pi2 = target on a log scale, or None."""
    maxima = local_maxima(curve)
    if not maxima:
        return None
    return min(maxima, key=lambda i: abs(math.log(curve.x[i] / target)))


def effect(curve):
    """Per point: 'amplified', 'deamplified' or 'none' (|Pi1 / Pi1_nc - 1| < NO_EFFECT)."""
    q = curve.ratio
    return np.where(q > 1 + NO_EFFECT, "amplified", np.where(q < 1 - NO_EFFECT, "deamplified", "none"))


@dataclass
class Region:
    kind: str
    lo: float
    hi: float
    points: int


def regions(curve):
    """The spectral regions of a curve: maximal runs of consecutive grid points of one
    effect, at least MIN_RUN points long (shorter runs are the crossings between them)."""
    out, start = [], 0
    for kind, run in itertools.groupby(effect(curve)):
        n = len(list(run))
        if n >= MIN_RUN:
            out.append(Region(str(kind), float(curve.x[start]), float(curve.x[start + n - 1]), n))
        start += n
    return out


def main_region(region_list, kind):
    """The longest region of a kind, or None."""
    found = [r for r in region_list if r.kind == kind]
    return max(found, key=lambda r: r.points) if found else None


def three_regions(curve, flexible):
    """Whether a spectrum has the paper's three regions in its order: the main amplified
    region below (flexible body) or above (stiff body) the main deamplified one, which comes
    within a factor NEAR of Pi2 = 1, and no effect at the far end of the grid (Pi2 = 10
    flexible, 0.1 stiff). Returns (agrees, reason)."""
    found = regions(curve)
    amp, deamp = main_region(found, "amplified"), main_region(found, "deamplified")
    if amp is None:
        return False, "no amplified region"
    if deamp is None:
        return False, "no deamplified region"
    if not (deamp.lo <= 1 <= deamp.hi or near(deamp.lo, 1) or near(deamp.hi, 1)):
        return False, "deamplified region not near Pi2 = 1"
    if (amp.hi < deamp.lo) != flexible:
        return False, "amplified region on the wrong side"
    far = found[-1] if flexible else found[0]
    if far.kind != "none" or (far.hi if flexible else far.lo) != (curve.x[-1] if flexible else curve.x[0]):
        return False, "no unaffected region at the far end"
    return True, ""


# ---------------------------------------------------------------- Fig. 10: scaling law

@dataclass
class Branch:
    kind: str  # "no effect", "negative" or "positive"
    lo: float  # Pi6 range of the points fitted
    hi: float
    points: int
    slope: float  # B of ln Pi1 = ln A + B ln Pi6
    intercept: float  # A
    r2: float  # NaN when Pi1 is constant (a flat branch fits exactly)


def fit(pi6, pi1):
    """Least squares of ln Pi1 = ln A + B ln Pi6: (B, A, R^2)."""
    x, y = np.log(pi6), np.log(pi1)
    slope, ln_a = np.polyfit(x, y, 1)
    total = float(np.sum((y - y.mean()) ** 2))
    residual = float(np.sum((y - (ln_a + slope * x)) ** 2))
    r2 = 1 - residual / total if total > 1e-24 else float("nan")
    return float(slope), float(math.exp(ln_a)), r2


def branches(curve):
    """The branches of one Pi1(Pi6) curve at fixed Pi2:

    * "no effect": every point where contact left Pi1 as it was (|Pi1 / Pi1_nc - 1| <
      UNCHANGED);
    * the other points split into maximal runs of consecutive points along which ln Pi1
      keeps the sign of its change ("negative", "positive"; neighbouring runs share their
      turning point), kept when at least MIN_BRANCH points long."""
    out = []
    same = np.abs(curve.ratio - 1) < UNCHANGED
    if same.sum() >= 2:
        idx = np.flatnonzero(same)
        out.append(Branch("no effect", float(curve.x[idx[0]]), float(curve.x[idx[-1]]), len(idx),
                          *fit(curve.x[idx], curve.pi1[idx])))
    changed = np.flatnonzero(~same)
    for segment in np.split(changed, np.flatnonzero(np.diff(changed) > 1) + 1):  # consecutive changed points
        first = 0
        for sign, run in itertools.groupby(np.sign(np.diff(curve.pi1[segment]))):
            n = len(list(run))  # n changes of one sign join n + 1 points
            idx = segment[first:first + n + 1]
            if sign != 0 and len(idx) >= MIN_BRANCH:
                out.append(Branch("negative" if sign < 0 else "positive", float(curve.x[idx[0]]),
                                  float(curve.x[idx[-1]]), len(idx), *fit(curve.x[idx], curve.pi1[idx])))
            first += n
    return out


# ---------------------------------------------------------------- Fig. 6: time histories

def impact_times(hist):
    """Impacts of contact 1 in a sampled `pair` history (columns t, u1, u0, v1, v0, g1):
    the sample intervals over which the gap rate g1' = v0 - v1 turns from closing to
    opening while the gap before could close within the interval (g1 <= 2 |g1'| dt).
    Each impact is placed where the gap, at its rate before, reaches zero."""
    t, g = hist["t"], hist["g1"]
    rate = hist["v0"] - hist["v1"]
    dt = np.diff(t)
    hit = (rate[:-1] < 0) & (rate[1:] > 0) & (g[:-1] <= -2 * rate[:-1] * dt)
    k = np.flatnonzero(hit)
    return t[k] + g[k] / -rate[k]
