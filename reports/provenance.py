#!/usr/bin/python3
"""Where and from what the results were measured: the commit, the date, the machine and the
compiler of the build that ran them. scripts/main.sh writes it beside the results before the
sweeps (results/provenance.json); make_report.py copies it to reports/provenance.json and
names it in every block of numbers it writes into README.md.

    reports/provenance.py --build-dir build > results/provenance.json
"""

import argparse
import datetime
import json
import os
import subprocess
import sys


def command_output(cmd):
    """The first line of a command's output, or "unknown" where it cannot run."""
    try:
        out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"
    return out.splitlines()[0] if out else "unknown"


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            return next(line.split(":", 1)[1].strip() for line in f if line.startswith("model name"))
    except (OSError, StopIteration):
        return "unknown"


def cmake_cache(build_dir):
    """The entries of a CMake build's cache (NAME:TYPE=VALUE lines) by name."""
    entries = {}
    try:
        with open(os.path.join(build_dir, "CMakeCache.txt")) as f:
            for line in f:
                name, sep, value = line.rstrip("\n").partition("=")
                if sep and not line.startswith(("#", "//")):
                    entries[name.split(":")[0]] = value
    except OSError:
        pass
    return entries


def measure(build_dir):
    cache = cmake_cache(build_dir)
    compiler = cache.get("CMAKE_CXX_COMPILER", "c++")
    return {
        "commit": command_output(["git", "rev-parse", "--short", "HEAD"]),
        "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d"),
        "cpu": cpu_model(),
        "cores": os.cpu_count(),
        "compiler": command_output([compiler, "--version"]),
        "build_type": cache.get("CMAKE_BUILD_TYPE", "unknown") or "unknown",
    }


def describe(p):
    """One line naming what the numbers were measured on."""
    return (f"commit {p['commit']}, {p['date']}, {p['cpu']} ({p['cores']} cores), {p['compiler']}, "
            f"{p['build_type']} build")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build-dir", default="build", help="the CMake build whose binaries run the results")
    args = parser.parse_args()
    json.dump(measure(args.build_dir), sys.stdout, indent=2)
    sys.stdout.write("\n")


if __name__ == "__main__":
    main()
