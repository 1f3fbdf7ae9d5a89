#!/usr/bin/python3
"""Turns poundbench result rows (CSV from `poundbench spectrum`) into reports/README.md
and its figures. Run by scripts/main.sh; uses Debian's python3-matplotlib.

    reports/make_report.py RESULTS.csv [...] --out reports
"""

import argparse
import csv
import datetime
import os
import platform
import subprocess
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# Columns that label a curve of a spectrum (everything that is neither the abscissa nor a result).
CASE_KEYS = ["scene", "pulse", "directivity", "eps", "pi3", "pi5", "pi6", "pi7", "pi8", "xi", "n_free", "a_p", "w_p"]


def load(paths):
    rows = []
    for path in paths:
        with open(path, newline="") as f:
            rows.extend(csv.DictReader(f))
    if not rows:
        sys.exit("make_report.py: no result rows in " + ", ".join(paths))
    return rows


def num(row, key):
    value = row.get(key, "")
    return float(value) if value not in ("", None) else float("nan")


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


def plot_family(family, rows, out_dir):
    """Pi1 against Pi2: rows of panels per pulse, columns per directivity, a line per case."""
    pulses = sorted({r["pulse"] for r in rows}, reverse=True)  # sine first, as in the paper
    directivities = sorted({r["directivity"] for r in rows})
    keys = [k for k in varying(rows, CASE_KEYS) if k not in ("pulse", "directivity")]
    fig, axes = plt.subplots(len(pulses), len(directivities), figsize=(5.6 * len(directivities), 3.9 * len(pulses)),
                             squeeze=False, sharex=True)
    for pi, pulse in enumerate(pulses):
        for di, direc in enumerate(directivities):
            ax = axes[pi][di]
            curves = defaultdict(list)
            for r in rows:
                if r["pulse"] == pulse and r["directivity"] == direc:
                    curves[(r["solver"],) + tuple(r[k] for k in keys)].append(r)
            drawn = set()
            for ci, label in enumerate(sorted(curves, key=sort_key)):
                crow = sorted(curves[label], key=lambda r: num(r, "pi2"))
                x = [num(r, "pi2") for r in crow]
                free = tuple(num(r, "pi1_no_contact") for r in crow)
                if free not in drawn:  # curves of the same body 0 share one no-contact line
                    drawn.add(free)
                    ax.plot(x, free, color="0.55", lw=1.0, alpha=0.6)
                text = ", ".join(f"{k}={v}" for k, v in zip(keys, label[1:])) or label[0]
                ax.plot(x, [num(r, "pi1") for r in crow], color=f"C{ci % 10}", lw=1.5, label=text)
            ax.set_xscale("log")
            ax.set_title(f"{pulse} pulse, {direc} directivity", fontsize=10)
            ax.grid(True, which="both", alpha=0.25)
            if pi == len(pulses) - 1:
                ax.set_xlabel(r"$\Pi_2 = \omega_0/\omega_p$")
            if di == 0:
                ax.set_ylabel(r"$\Pi_1 = u_{0,\max}\,\omega_p^2/a_p$")
    axes[0][-1].legend(fontsize=7, loc="upper right")
    fig.suptitle(f"{family}: Pi-spectra of body 0 (colour: with contact, grey: no contact)", fontsize=11)
    fig.tight_layout(rect=(0, 0, 1, 0.96))
    stem = os.path.join(out_dir, "figures", f"spectrum-{family}")
    for ext in ("png", "svg"):
        fig.savefig(f"{stem}.{ext}", dpi=100)
    plt.close(fig)
    return f"figures/spectrum-{family}.png"


def command_output(cmd):
    try:
        return subprocess.run(cmd, capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def footer():
    cpu = "unknown"
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next(line.split(":", 1)[1].strip() for line in f if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    lines = [
        f"- machine: {platform.machine()}, {os.cpu_count()} cores, {cpu}",
        f"- system: {platform.platform()}",
        f"- compiler: {command_output(['c++', '--version']).splitlines()[0] if command_output(['c++', '--version']) != 'unknown' else 'unknown'}",
        f"- libraries: Eigen {command_output(['dpkg-query', '-W', '-f=${Version}', 'libeigen3-dev'])}, "
        f"toml++ {command_output(['dpkg-query', '-W', '-f=${Version}', 'libtomlplusplus-dev'])}, "
        f"matplotlib {matplotlib.__version__}",
        f"- commit: {command_output(['git', 'rev-parse', '--short', 'HEAD'])}",
        f"- date: {datetime.datetime.now(datetime.timezone.utc).strftime('%Y-%m-%d %H:%M UTC')}",
    ]
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results", nargs="+", help="result CSV files from `poundbench spectrum`")
    parser.add_argument("--out", default="reports", help="folder for README.md and figures/")
    args = parser.parse_args()

    rows = load(args.results)
    os.makedirs(os.path.join(args.out, "figures"), exist_ok=True)
    families = defaultdict(list)
    for r in rows:
        families[r["family"]].append(r)

    text = ["# poundbench report", ""]
    text.append("Generated by `scripts/main.sh` from the shipped paper case set "
                "(`cases/sets/paper.toml`); regenerate it with that one command.")
    text.append("")
    text.append("## Runs")
    text.append("")
    text.append("| family | solver | points | failed | impacts (median) | run time per point, median (us) | total CPU (s) |")
    text.append("|---|---|---:|---:|---:|---:|---:|")
    for family, frows in families.items():
        by_solver = defaultdict(list)
        for r in frows:
            by_solver[r["solver"]].append(r)
        for solver, srows in by_solver.items():
            secs = sorted(num(r, "seconds") for r in srows)
            imps = sorted(num(r, "impacts") for r in srows)
            failed = sum(r["status"] != "ok" for r in srows)
            text.append(f"| {family} | {solver} | {len(srows)} | {failed} | {imps[len(imps) // 2]:.0f} | "
                        f"{1e6 * secs[len(secs) // 2]:.1f} | {sum(secs):.2f} |")
    text.append("")
    text.append("## Pi-spectra")
    text.append("")
    text.append("Pi1 of body 0 against Pi2 for every family of the paper's case set. Light lines: the same "
                "case with every contact removed.")
    text.append("")
    for family, frows in families.items():
        if len({r["pi2"] for r in frows}) < 20:
            continue  # not a spectrum over Pi2 (fig10 sweeps Pi6; issue 7 plots it)
        figure = plot_family(family, frows, args.out)
        text.append(f"### {family}")
        text.append("")
        text.append(f"![{family}]({figure})")
        text.append("")
    text.append("## Where this ran")
    text.append("")
    text.append(footer())
    text.append("")
    path = os.path.join(args.out, "README.md")
    with open(path + ".tmp", "w") as f:
        f.write("\n".join(text))
    os.replace(path + ".tmp", path)
    print(f"make_report.py: wrote {path}")


if __name__ == "__main__":
    main()
