#!/usr/bin/env python3
"""Writes the example ground-motion records of cases/records/ (issue 21): each a
Mavroeidis-Papageorgiou (2003) velocity pulse plus band-limited noise from a fixed seed,
in both formats poundbench reads, a two-column CSV (t, a_g in m/s^2) and a PEER NGA .AT2
file (values in g, g = 9.80665 m/s^2). They are synthetic: no data can be downloaded here,
and they stand in for the near-fault records a user has (cases/README.md, "Records").

    python3 scripts/make_records.py [OUTDIR]     # default: cases/records

Only the standard library: random.Random(seed) (Mersenne Twister) gives the same noise on
every machine; the files are committed, so poundbench's tests read them, not this script.

The acceleration is a_g = a_MP(t - t_start) + e(t) n(t):
  a_MP   the derivative of the Mavroeidis-Papageorgiou velocity pulse
         v(t) = A/2 (1 + cos(2 pi f_p t' / gamma)) cos(2 pi f_p t' + nu), |t'| <= gamma / (2 f_p),
         t' = t - t_start - gamma / (2 f_p), written in closed form (cases/load.cpp has the same);
  n      a sum of 200 sinusoids with random frequencies in [f_lo, f_hi] and random phases,
         scaled to the noise RMS: band-limited noise;
  e      a smooth envelope rising over the first 20 % of the record and decaying over the
         last 40 %, so that the record starts and ends near rest.
"""

import math
import os
import random
import sys

G = 9.80665


def mp_accel(t, A, fp, nu_deg, gamma):
    """Derivative of the Mavroeidis-Papageorgiou velocity pulse centred at gamma / (2 fp)."""
    half = gamma / (2.0 * fp)
    tau = t - half
    if tau < -half or tau > half:
        return 0.0
    w = 2.0 * math.pi * fp
    nu = math.radians(nu_deg)
    return -(A / 2.0) * ((w / gamma) * math.sin(w * tau / gamma) * math.cos(w * tau + nu)
                         + w * (1.0 + math.cos(w * tau / gamma)) * math.sin(w * tau + nu))


def envelope(t, length):
    rise, fall = 0.2 * length, 0.4 * length
    if t < rise:
        return math.sin(0.5 * math.pi * t / rise) ** 2
    if t > length - fall:
        return math.cos(0.5 * math.pi * (t - (length - fall)) / fall) ** 2
    return 1.0


def record(spec):
    rng = random.Random(spec["seed"])
    n = int(round(spec["length"] / spec["dt"])) + 1
    freqs = [rng.uniform(spec["f_lo"], spec["f_hi"]) for _ in range(200)]
    phases = [rng.uniform(0.0, 2.0 * math.pi) for _ in range(200)]
    scale = spec["noise_rms"] * math.sqrt(2.0 / len(freqs))  # each sinusoid's RMS is amplitude / sqrt(2)
    out = []
    for i in range(n):
        t = i * spec["dt"]
        noise = scale * sum(math.sin(2.0 * math.pi * f * t + p) for f, p in zip(freqs, phases))
        a = mp_accel(t - spec["t_start"], spec["A"], spec["fp"], spec["nu"], spec["gamma"])
        out.append((t, a + envelope(t, spec["length"]) * noise))
    return out


RECORDS = [
    # 40 s at 0.005 s (8001 samples, the cost benchmark): a 1 s pulse at 10 s.
    dict(name="mp-noise-40s", seed=21, length=40.0, dt=0.005, A=0.6, fp=1.0, nu=90.0, gamma=2.0, t_start=10.0,
         f_lo=1.0, f_hi=12.0, noise_rms=0.6),
    # 20 s at 0.01 s (2001 samples): a 2 s pulse of more cycles at 4 s, rougher noise.
    dict(name="mp-noise-20s", seed=2003, length=20.0, dt=0.01, A=0.8, fp=0.5, nu=0.0, gamma=2.5, t_start=4.0,
         f_lo=2.0, f_hi=20.0, noise_rms=0.8),
]


def write_csv(path, rows, spec):
    with open(path, "w") as f:
        f.write("# poundbench example record %s (scripts/make_records.py): synthetic, not recorded\n" % spec["name"])
        f.write("# Mavroeidis-Papageorgiou pulse A = %g m/s, f_p = %g Hz, nu = %g deg, gamma = %g at t = %g s, "
                "plus band-limited noise (%g-%g Hz, RMS %g m/s^2, seed %d)\n"
                % (spec["A"], spec["fp"], spec["nu"], spec["gamma"], spec["t_start"], spec["f_lo"], spec["f_hi"],
                   spec["noise_rms"], spec["seed"]))
        f.write("t,a_g\n")
        for t, a in rows:
            f.write("%.10g,%.9g\n" % (t, a))


def write_at2(path, rows, spec):
    with open(path, "w") as f:
        f.write("PEER NGA STRONG MOTION DATABASE RECORD (format only: poundbench synthetic example)\n")
        f.write("%s, MP PULSE A=%g M/S FP=%g HZ NU=%g GAMMA=%g + NOISE SEED %d\n"
                % (spec["name"].upper(), spec["A"], spec["fp"], spec["nu"], spec["gamma"], spec["seed"]))
        f.write("ACCELERATION TIME SERIES IN UNITS OF G\n")
        f.write("NPTS=%7d, DT=%9.4f SEC\n" % (len(rows), spec["dt"]))
        values = ["%15.7E" % (a / G) for _, a in rows]
        for i in range(0, len(values), 5):
            f.write("".join(values[i:i + 5]) + "\n")


def main():
    outdir = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "cases", "records")
    os.makedirs(outdir, exist_ok=True)
    for spec in RECORDS:
        rows = record(spec)
        write_csv(os.path.join(outdir, spec["name"] + ".csv"), rows, spec)
        write_at2(os.path.join(outdir, spec["name"] + ".at2"), rows, spec)
        peak = max(abs(a) for _, a in rows)
        print("%s: %d samples, %g s, peak %.4g m/s^2 (%.4g g)" % (spec["name"], len(rows), rows[-1][0], peak, peak / G))


if __name__ == "__main__":
    main()
