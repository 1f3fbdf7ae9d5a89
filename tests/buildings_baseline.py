"""Accuracy regression baselines of the buildings scene (tests/baselines/buildings-*.csv): the
rows `poundbench spectrum` wrote for a buildings case set through one solver setting, under
comment lines that say how they were made:

    # cases: ../../cases/sets/buildings.toml      (relative to the file)
    # run: --solver moreau-jean --steps 64
    # tolerance: 1e-12                              (relative, on every peak)
    # commit: ..., made: ...                        (provenance, for people)

Check (the test, tests/CMakeLists.txt): reruns each file's run and compares every row: the
status and the impact counts exactly, every peak (with and without contact, in metres) within
the tolerance. Update, after a change that moves results on purpose (say which rows moved and
why in the commit):

    python3 tests/buildings_baseline.py POUNDBENCH [--update] FILE...
"""

import csv
import io
import os
import subprocess
import sys
import tempfile

PEAKS = ("floor_peak_m", "drift_peak_m", "floor_peak_no_contact_m", "drift_peak_no_contact_m")
EXACT = ("family", "point", "building", "floor", "status", "impacts_right")


def read(path):
    header, lines = {}, []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                key, _, value = line[1:].strip().partition(": ")
                header[key] = value
            else:
                lines.append(line)
    return header, list(csv.DictReader(io.StringIO("".join(lines))))


def solve(poundbench, path, header):
    cases = os.path.join(os.path.dirname(os.path.abspath(path)), header["cases"])
    with tempfile.TemporaryDirectory() as folder:
        out = os.path.join(folder, "rows.csv")
        subprocess.run([poundbench, "spectrum", cases, *header["run"].split(), "--out", out], check=True,
                       stderr=subprocess.DEVNULL)
        with open(out) as f:
            return f.read()


def differences(stored, rows, tolerance):
    """One line per row that moved: what moved, and by how much."""
    if len(stored) != len(rows):
        return [f"{len(rows)} rows, {len(stored)} stored"]
    out = []
    for s, r in zip(stored, rows):
        where = f"point {s['point']} building {s['building']} floor {s['floor']}"
        for key in EXACT:
            if s[key] != r[key]:
                out.append(f"{where}: {key} {r[key]!r}, stored {s[key]!r}")
        for key in PEAKS:
            a, b = float(r[key] or "nan"), float(s[key] or "nan")
            if not (abs(a - b) <= tolerance * max(abs(b), 1e-300)) and not (a != a and b != b):
                out.append(f"{where}: {key} {a!r}, stored {b!r} (relative {abs(a - b) / abs(b) if b else float('inf'):.2e})")
    return out


def main():
    poundbench, args = sys.argv[1], sys.argv[2:]
    update = "--update" in args
    files = [a for a in args if a != "--update"]
    listed = subprocess.run([poundbench, "solvers"], capture_output=True, text=True, check=True).stdout.split("\n")
    built = {line.split()[0] for line in listed if line and not line[0].isspace()}
    failed = 0
    for path in files:
        header, stored = read(path)
        solver = header["run"].split()[header["run"].split().index("--solver") + 1]
        if solver not in built:
            print(f"{path}: skipped, {solver} is not in this build")
            continue
        text = solve(poundbench, path, header)
        moved = differences(stored, list(csv.DictReader(io.StringIO(text))), float(header["tolerance"]))
        if update:
            commit = subprocess.run([poundbench, "--version"], capture_output=True, text=True).stdout.strip()
            with open(path, "w") as f:
                for key in ("cases", "run", "tolerance"):
                    f.write(f"# {key}: {header[key]}\n")
                f.write(f"# made by: {commit}\n")
                f.write(text)
            print(f"{path}: stored again ({len(moved)} rows moved)")
            for line in moved[:20]:
                print("  " + line)
            continue
        if moved:
            failed += 1
            print(f"{path}: {len(moved)} differences beyond {header['tolerance']} (rerun with --update if on purpose):")
            for line in moved[:20]:
                print("  " + line)
        else:
            print(f"{path}: {len(stored)} rows as stored")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
