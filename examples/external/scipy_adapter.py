#!/usr/bin/env python3
"""An external solver for poundbench, written with SciPy: an event-located integrator.

    poundbench run --solver external --command "python3 examples/external/scipy_adapter.py" \\
        --scene pair --pulse sine --directivity normal --pi2 1 --pi3 0.5 --eps 0.5 --pi5 0.5 --pi6 1

It reads one case document on stdin and writes one answer document on stdout
(docs/external.md); with --persistent it answers a stream of cases, one line each way, after
a ready line (docs/external.md, "Persistent mode"), so that Python's start and SciPy's import
are paid once per sweep worker. Every answer carries solve_seconds: the time from the case
read to its answer made, the program's own cost of the solve. Between events, scipy.integrate.solve_ivp (DOP853) integrates

    m_i u_i'' = -c_i u_i' - k_i u_i - m_i a_g(t) + sum_j W_ij lambda_j

with the contacts in persistent contact held closed by their forces lambda (found from
g'' = 0 on them); its events locate a gap closing, a contact force falling to zero (the
contact opens) and the pulse's end. At a closing gap, Newton's impact law: the gap's rate
after the impact is -eps times the rate before (several closed contacts at once: the
impulses that keep every closed contact from approaching, by a small velocity-level LCP).
An approach slower than 1e-7 a_p/w_p is taken as plastic, so that an accumulation of
impacts ends in persistent contact; whether a closed contact carries force is decided by
the acceleration-level LCP, looking at the load a moment ahead (so that touching bodies at
rest under a vanishing load, Pi3 = 0, are decided by where the load goes next).

A buildings document ("scene": "buildings", docs/external.md) is solved the same way
(BuildingsRun): one coordinate per floor, M u'' + C u' + K u = -M 1 a_g(t) + W lambda with C
as the document gives it, an event per contact, Newton's law over the contacts closing
together; its answer is every floor's peak |u| and storey's peak drift (their extrema located
as events) and per contact its impacts.

Pi1 is the largest |u0| at the extrema of u0 (located as events of its velocity), at every
event and at the ends. Its own settings are its arguments: --rtol (default 1e-10), --method.
It ignores the step (it is not a time-stepper); it honours step_cap (integrator steps and
events together), time_limit and history_samples.
"""
import argparse
import bisect
import json
import math
import sys
import time

START = time.monotonic()  # of the case being solved: its time_limit counts from it


class Answered(Exception):
    """answer()'s document, for respond() to write."""

    def __init__(self, doc):
        super().__init__()
        self.doc = doc


def write(doc):
    doc.setdefault("version", 1)
    json.dump(doc, sys.stdout, allow_nan=False)
    sys.stdout.write("\n")
    sys.stdout.flush()


def answer(doc):
    raise Answered(doc)


def refuse(message):
    answer({"status": "failed", "message": message})


try:
    import numpy as np
    from scipy.integrate import solve_ivp
except ImportError as e:  # the answer says why, rather than a traceback (in persistent mode: its first line)
    write({"status": "failed", "message": f"scipy_adapter.py needs NumPy and SciPy (Debian: python3-numpy python3-scipy): {e}"})
    sys.exit(0)


class Stop(Exception):
    def __init__(self, status, message):
        super().__init__(message)
        self.status = status


class Model:
    def __init__(self, case):
        bodies = case["bodies"]
        self.n = len(bodies)
        self.m = np.array([b["m"] for b in bodies], dtype=float)
        self.k = np.array([b["k"] for b in bodies], dtype=float)
        self.c = np.array([b["c"] for b in bodies], dtype=float)
        self.u_start = np.array([b["u"] for b in bodies], dtype=float)
        self.v_start = np.array([b["v"] for b in bodies], dtype=float)
        self.ref = case["reference"]
        self.eps = case["eps"]
        self.contacts = case["contacts"]
        self.nc = len(self.contacts)
        # W[i, j]: how contact j's force acts on body i (+1 pushes the right body to +x).
        self.W = np.zeros((self.n, self.nc))
        self.gap0 = np.zeros(self.nc)
        for j, contact in enumerate(self.contacts):
            self.W[contact["right"], j] = 1.0
            if contact["left"] is not None:
                self.W[contact["left"], j] = -1.0
            self.gap0[j] = contact["gap"]
        self.minv = 1.0 / self.m
        load = case["load"]
        self.shape = math.sin if load["shape"] == "sine" else math.cos
        self.amplitude = load["amplitude"]
        self.w_p = load["w"]
        self.t_p = load["duration"]
        self.length = case["length_scale"]
        self.speed = self.length * self.w_p  # a_p / w_p
        self.t_end = case["t_end"]

    def accel_ground(self, t):
        return self.amplitude * self.shape(self.w_p * t) if 0.0 <= t <= self.t_p else 0.0

    def next_break(self, t):
        """Where the load next changes its form (the pulse's end), or t_end: a segment's end."""
        return self.t_p if t < self.t_p else self.t_end

    def gaps(self, u):
        return self.gap0 + self.W.T @ u

    def rates(self, v):
        return self.W.T @ v

    def free_force(self, t, u, v):
        return -self.c * v - self.k * u - self.m * self.accel_ground(t)

    def contact_forces(self, active, f):
        """The forces that keep the active contacts closed (g'' = 0) under the force f."""
        if not active:
            return np.zeros(0)
        wa = self.W[:, active]
        s = wa.T @ (self.minv[:, None] * wa)
        return np.linalg.solve(s, -wa.T @ (self.minv * f))

    def rhs(self, active):
        def f(t, y):
            u, v = y[: self.n], y[self.n:]
            force = self.free_force(t, u, v)
            if active:
                force = force + self.W[:, active] @ self.contact_forces(active, force)
            return np.concatenate((v, self.minv * force))
        return f


def lcp_by_active_set(matrix_of, rhs_of, candidates):
    """x >= 0 on the candidates with matrix x = rhs where x > 0: drop the most negative until none is."""
    kept = list(candidates)
    while kept:
        x = np.linalg.solve(matrix_of(kept), rhs_of(kept))
        worst = int(np.argmin(x))
        if x[worst] >= 0.0:
            return kept, x
        kept.pop(worst)
    return [], np.zeros(0)


class Run:
    def __init__(self, model, args, case):
        self.model = model
        self.args = args
        self.tol_gap = 1e-9 * model.length
        self.tol_rate = 1e-9 * model.speed
        self.plastic_below = 1e-7 * model.speed
        self.impacts = 0
        self.phases = 0
        self.steps = 0
        self.cap = case.get("step_cap") or 0
        self.time_limit = case.get("time_limit") or 0.0
        self.u_peak = 0.0
        self.t_peak = 0.0
        self.min_gap = math.inf
        self.force_scale = float(np.max(model.m)) * model.length * model.w_p ** 2  # m a_p
        self.pieces = []  # (t0, t1, dense solution or None) for the history
        self.now = 0.0  # the time of the impacts being resolved

    def extrema(self):
        """The quantities whose extrema (zeros of their rates) are events, as functions of y: u0's."""
        n, ref = self.model.n, self.model.ref
        return [lambda t, y: y[n + ref]]

    def note_impacts(self, rate, hitting):
        """Closed contacts approaching at rate[j] < 0, j in hitting, before Newton's law acts."""

    def note_phases(self, entered):
        """The contacts that entered persistent contact."""
        self.phases += len(entered)

    def watch(self, t, u):
        a = abs(u[self.model.ref])
        if a > self.u_peak:
            self.u_peak, self.t_peak = a, t
        if self.model.nc:
            self.min_gap = min(self.min_gap, float(np.min(self.model.gaps(u))))

    def closed(self, u, active):
        g = self.model.gaps(u)
        return [j for j in range(self.model.nc) if j not in active and g[j] <= self.tol_gap]

    def impact(self, u, v, active):
        """Newton's law on the closed contacts that approach; the active ones stay closed."""
        m = self.model
        for _ in range(100):
            rate = m.rates(v)
            hitting = [j for j in self.closed(u, active) if rate[j] < -self.tol_rate]
            if not hitting:
                return v
            self.impacts += len(hitting)
            self.note_impacts(rate, hitting)
            target = {j: (-m.eps * rate[j] if -rate[j] > self.plastic_below else 0.0) for j in hitting}
            candidates = sorted(set(hitting) | set(active))

            def matrix_of(kept):
                wk = m.W[:, kept]
                return wk.T @ (m.minv[:, None] * wk)

            def rhs_of(kept):
                return np.array([target.get(j, 0.0) for j in kept]) - rate[kept]

            kept, impulse = lcp_by_active_set(matrix_of, rhs_of, candidates)
            if kept:
                v = v + m.minv * (m.W[:, kept] @ impulse)
        raise Stop("failed", "impacts did not settle in 100 rounds at one instant")

    def contact_set(self, t, u, v, active, opened):
        """The closed, resting contacts that carry force, by the acceleration LCP; those that just
        opened (their force fell to zero, an event) stay open. A force within round-off of zero is
        judged a moment ahead, along the motion with the contact held closed."""
        m = self.model
        rate = m.rates(v)
        g = m.gaps(u)
        resting = [j for j in range(m.nc) if j not in opened and (j in active or (
                   g[j] <= self.tol_gap and abs(rate[j]) <= max(self.tol_rate, self.plastic_below)))]
        if not resting:
            return [], v
        wk = m.W[:, resting]
        s = wk.T @ (m.minv[:, None] * wk)
        v = v - m.minv * (wk @ np.linalg.solve(s, wk.T @ v))  # resting contacts neither open nor close

        def matrix_of(kept):
            wk = m.W[:, kept]
            return wk.T @ (m.minv[:, None] * wk)

        def lcp_at(t_at, u_at, v_at):
            f = m.free_force(t_at, u_at, v_at)
            return lcp_by_active_set(matrix_of, lambda kept: -m.W[:, kept].T @ (m.minv * f), resting)

        kept, force = lcp_at(t, u, v)
        if len(force) and np.min(force) <= 1e-9 * self.force_scale:
            kept, force = lcp_at(*self.ahead(t, u, v, kept))
            kept = [j for j, x in zip(kept, force) if x > 0.0]
        self.note_phases([j for j in kept if j not in active])
        return sorted(kept), v

    def ahead(self, t, u, v, kept):
        """The state a moment after t along the motion with the contacts kept held closed."""
        m = self.model
        tau = 1e-6 * m.t_p
        a = m.rhs(kept)(t, np.concatenate((u, v)))[m.n:]
        return t + tau, u + tau * v + 0.5 * tau * tau * a, v + tau * a

    def rebound_flight(self, t, u, v, active):
        """The shortest time until a contact that just rebounded closes again, if its motion goes on
        as it starts (a parabola): an integrator step longer than that would step over the closing,
        and a root search from the gap's zero at the start would find the start again."""
        m = self.model
        g, rate = m.gaps(u), m.rates(v)
        accel = m.W.T @ m.rhs(active)(t, np.concatenate((u, v)))[m.n:]
        flights = [2.0 * rate[j] / -accel[j] for j in range(m.nc)
                   if j not in active and g[j] <= self.tol_gap and rate[j] > 0.0 and accel[j] < 0.0]
        return min(flights, default=math.inf)

    def segment(self, t0, t1, u, v, active, max_step=math.inf):
        m = self.model
        n = m.n
        events, kinds = [], []
        for j in range(m.nc):
            if j in active:
                k = active.index(j)

                def opens(t, y, k=k):
                    f = m.free_force(t, y[:n], y[n:])
                    return m.contact_forces(active, f)[k]
                opens.terminal, opens.direction = True, -1
                events.append(opens)
                kinds.append(("opens", j))
            else:
                def closes(t, y, j=j):
                    return m.gap0[j] + m.W[:, j] @ y[:n]
                closes.terminal, closes.direction = True, -1
                events.append(closes)
                kinds.append(("closes", j))

        extrema = self.extrema()
        events.extend(extrema)
        scale = np.concatenate((np.full(n, m.length), np.full(n, m.speed)))
        sol = solve_ivp(m.rhs(active), (t0, t1), np.concatenate((u, v)), method=self.args.method,
                        rtol=self.args.rtol, atol=1e-3 * self.args.rtol * scale, events=events,
                        dense_output=True, max_step=max_step)
        if sol.status < 0:
            raise Stop("failed", f"solve_ivp: {sol.message}")
        self.steps += len(sol.t) - 1
        for times, states in zip(sol.t_events[len(kinds):], sol.y_events[len(kinds):]):
            for ts, ys in zip(times, states):
                self.watch(ts, ys[:n])
        for k in range(sol.y.shape[1]):
            self.watch(sol.t[k], sol.y[:n, k])
        self.pieces.append((t0, sol.t[-1], sol.sol))
        y = sol.y[:, -1]
        opened = [j for (kind, j), times in zip(kinds, sol.t_events) if kind == "opens" and len(times)]
        return sol.t[-1], y[:n].copy(), y[n:].copy(), opened

    def solve(self):
        m = self.model
        t, u, v = 0.0, m.u_start.copy(), m.v_start.copy()
        self.watch(t, u)
        v = self.impact(u, v, [])
        active, v = self.contact_set(t, u, v, [], [])
        stalls = 0
        while t < m.t_end:
            if self.cap and self.steps > self.cap:
                raise Stop("step_cap", f"more than {self.cap} integrator steps and events")
            if self.time_limit and time.monotonic() - START > self.time_limit:
                raise Stop("time-limit", f"more than {self.time_limit} s of wall time at t = {t}")
            t_stop = m.next_break(t)
            flight = self.rebound_flight(t, u, v, active)
            if flight < t_stop - t:
                # To the top of the rebound's arc in steps of an eighth of its flight: from there the
                # closing is a sign change like any other.
                t_new, u, v, opened = self.segment(t, t + 0.5 * flight, u, v, active, 0.125 * flight)
            else:
                t_new, u, v, opened = self.segment(t, t_stop, u, v, active)
            stalls = stalls + 1 if t_new - t <= 1e-12 * m.t_end else 0
            if stalls > 50:
                raise Stop("failed", f"events do not advance at t = {t}")
            t = t_new
            self.now = t
            self.steps += 1
            active = [j for j in active if j not in opened]
            v = self.impact(u, v, active)
            active, v = self.contact_set(t, u, v, active, opened)
        return self.u_peak / m.length, self.t_peak

    def history(self, samples):
        times = np.linspace(0.0, self.model.t_end, samples)
        u0 = np.empty(samples)
        piece = 0
        for i, t in enumerate(times):
            while piece + 1 < len(self.pieces) and t > self.pieces[piece][1]:
                piece += 1
            u0[i] = self.pieces[piece][2](t)[self.model.ref]
        return {"t": times.tolist(), "u0": u0.tolist()}


# ---------------------------------------------------------------- the buildings scene

class Load:
    """a_g(t) of any kind a case carries: a pulse, sinusoids, a record (linear between samples,
    zero outside them); breaks are the times where its form changes, which segments end at."""

    def __init__(self, load):
        self.kind = load["kind"]
        if self.kind == "record":
            self.t = np.array(load["t"], dtype=float)
            self.a = np.array(load["a"], dtype=float)
            self.breaks = list(self.t)
        elif self.kind in ("pulse", "sinusoids"):
            self.duration = load["duration"]
            if self.kind == "pulse":
                w = load["w"]
                sin, cos = (load["amplitude"], 0.0) if load["shape"] == "sine" else (0.0, load["amplitude"])
                self.terms = [(w, sin, cos)]
            else:
                self.terms = [(term["w"], term["sin"], term["cos"]) for term in load["terms"]]
            self.breaks = [self.duration]
        else:
            refuse(f"load.kind: {self.kind!r} is not a kind this program knows (it knows 'pulse', 'sinusoids', 'record')")

    def __call__(self, t):
        if self.kind == "record":
            return float(np.interp(t, self.t, self.a, left=0.0, right=0.0)) if self.t[0] <= t <= self.t[-1] else 0.0
        if not 0.0 <= t <= self.duration:
            return 0.0
        return sum(s * math.sin(w * t) + c * math.cos(w * t) for w, s, c in self.terms)


class BuildingsModel:
    """The buildings scene as Run's model: every floor of every building one coordinate (building 0's
    floors first, floor 1 first), M diagonal, K tridiagonal per building, C as the case gives it."""

    def __init__(self, case):
        buildings = case["buildings"]
        self.floors = [len(b["masses"]) for b in buildings]
        self.first = [sum(self.floors[:b]) for b in range(len(buildings))]
        self.n = n = sum(self.floors)
        self.m = np.concatenate([np.array(b["masses"], dtype=float) for b in buildings])
        self.K = np.zeros((n, n))
        self.C = np.zeros((n, n))
        for b, building in enumerate(buildings):
            f = self.first[b]
            for i, k in enumerate(building["stiffnesses"]):  # storey i + 1: floor i to floor i + 1
                self.K[f + i, f + i] += k
                if i > 0:
                    self.K[f + i - 1, f + i - 1] += k
                    self.K[f + i, f + i - 1] -= k
                    self.K[f + i - 1, f + i] -= k
            self.C[f:f + self.floors[b], f:f + self.floors[b]] = np.array(building["C"], dtype=float)
        self.u_start = np.zeros(n)
        self.v_start = np.zeros(n)
        self.ref = 0
        self.eps = case["eps"]
        self.contacts = case["contacts"]
        self.nc = len(self.contacts)
        self.W = np.zeros((n, self.nc))  # gap j = gap0 + u[right floor] - u[left floor]
        self.gap0 = np.zeros(self.nc)
        for j, c in enumerate(self.contacts):
            self.W[self.first[c["right"]] + c["floor"] - 1, j] = 1.0
            self.W[self.first[c["left"]] + c["floor"] - 1, j] = -1.0
            self.gap0[j] = c["gap"]
        self.minv = 1.0 / self.m
        self.load = Load(case["load"])
        self.w_p = case["w_p"]
        self.length = case["length_scale"]
        self.speed = case["a_p"] / case["w_p"]
        self.t_end = case["t_end"]
        self.t_p = self.load.breaks[-1]  # the load's end: a time scale of the persistent-contact look-ahead

    def next_break(self, t):
        i = bisect.bisect_right(self.load.breaks, t * (1.0 + 1e-15))
        return min(self.load.breaks[i], self.t_end) if i < len(self.load.breaks) else self.t_end

    def gaps(self, u):
        return self.gap0 + self.W.T @ u

    def rates(self, v):
        return self.W.T @ v

    def free_force(self, t, u, v):
        return -self.C @ v - self.K @ u - self.m * self.load(t)

    contact_forces = Model.contact_forces
    rhs = Model.rhs


class BuildingsRun(Run):
    """Run on the buildings: the peak |u| of every floor and |drift| of every storey (their extrema
    located as events), and per contact its impacts, fastest approach and first impact."""

    def __init__(self, model, args, case):
        super().__init__(model, args, case)
        self.t_min = case["t_min"]
        n = model.n
        self.below = np.full(n, -1)  # the floor under each floor (-1: the ground)
        for f, count in zip(model.first, model.floors):
            self.below[f + 1:f + count] = np.arange(f, f + count - 1)
        self.floor_peak, self.floor_time = np.zeros(n), np.zeros(n)
        self.drift_peak, self.drift_time = np.zeros(n), np.zeros(n)
        self.hits = [0] * model.nc
        self.entries = [0] * model.nc
        self.fastest = [None] * model.nc
        self.first_hit = [None] * model.nc

    def ahead(self, t, u, v, kept):
        """Integrated rather than a Taylor step, and longer: buildings touching at rest under a
        load that starts from zero (a gap of 0) move apart or together only at third order in
        time (both are carried by the ground alike at first), which a parabola does not see."""
        m = self.model
        tau = 1e-4 * self.t_min
        sol = solve_ivp(m.rhs(kept), (t, t + tau), np.concatenate((u, v)), method=self.args.method,
                        rtol=self.args.rtol, atol=1e-6 * self.args.rtol * np.concatenate(
                            (np.full(m.n, m.length), np.full(m.n, m.speed))))
        return t + tau, sol.y[:m.n, -1], sol.y[m.n:, -1]

    def drifts(self, u):
        return u - np.where(self.below >= 0, u[np.maximum(self.below, 0)], 0.0)

    def extrema(self):
        n = self.model.n
        events = [lambda t, y, i=i: y[n + i] for i in range(n)]  # every floor's velocity
        events += [lambda t, y, i=i, j=j: y[n + i] - y[n + j] for i, j in enumerate(self.below) if j >= 0]
        return events

    def watch(self, t, u):
        a, d = np.abs(u), np.abs(self.drifts(u))
        up, dp = a > self.floor_peak, d > self.drift_peak
        self.floor_peak[up], self.floor_time[up] = a[up], t
        self.drift_peak[dp], self.drift_time[dp] = d[dp], t
        if self.model.nc:
            self.min_gap = min(self.min_gap, float(np.min(self.model.gaps(u))))

    def note_impacts(self, rate, hitting):
        for j in hitting:
            speed = -rate[j]
            if speed <= self.plastic_below:
                continue
            self.hits[j] += 1
            self.fastest[j] = max(self.fastest[j] or 0.0, speed)
            if self.first_hit[j] is None:
                self.first_hit[j] = self.now

    def note_phases(self, entered):
        super().note_phases(entered)
        for j in entered:
            self.entries[j] += 1

    def per_building(self, values):
        m = self.model
        return [[float(x) for x in values[f:f + count]] for f, count in zip(m.first, m.floors)]

    def answer(self):
        contacts = [{"left": c["left"], "right": c["right"], "floor": c["floor"], "impacts": self.hits[j],
                     "contact_phases": self.entries[j],
                     "impact_velocity_max": self.fastest[j], "first_impact": self.first_hit[j]}
                    for j, c in enumerate(self.model.contacts)]
        return {"floor_peak": self.per_building(self.floor_peak), "floor_peak_time": self.per_building(self.floor_time),
                "drift_peak": self.per_building(self.drift_peak), "drift_peak_time": self.per_building(self.drift_time),
                "contacts": contacts}


def solve_buildings(case, args):
    """Raises Answered with the answer to a buildings document."""
    model = BuildingsModel(case)
    if model.eps < 0 or model.eps > 1:
        refuse("eps: must be in [0, 1]")
    run = BuildingsRun(model, args, case)
    try:
        run.solve()
    except Stop as stop:
        answer({"status": stop.status, "message": str(stop), "steps": run.steps})
    doc = {"status": "ok", **run.answer(), "steps": run.steps,
           "message": f"scipy {args.method} rtol {args.rtol:g}, events per contact, Newton's law over the contacts closing together"}
    if math.isfinite(run.min_gap):
        doc["min_gap"] = run.min_gap
    answer(doc)


def solve_case(text, args):
    """Raises Answered with the answer to one case document."""
    try:
        case = json.loads(text)
    except ValueError as e:
        refuse(f"stdin: not JSON: {e}")
    if case.get("version") != 1:
        refuse(f"version: this program speaks version 1, not {case.get('version')!r}")
    if case.get("scene") == "buildings":
        solve_buildings(case, args)
    if "scene" in case:
        refuse(f"scene: {case['scene']!r} is not a scene this program knows (it knows 'buildings' and the oscillators')")
    kind = case.get("load", {}).get("kind")
    if kind != "pulse":
        refuse(f"load.kind: {kind!r} is not a kind this program knows (it knows 'pulse')")
    model = Model(case)
    if model.eps < 0 or model.eps > 1:
        refuse("eps: must be in [0, 1]")
    run = Run(model, args, case)
    try:
        pi1, t_max = run.solve()
    except Stop as stop:
        answer({"status": stop.status, "message": str(stop), "impacts": run.impacts,
                "contact_phases": run.phases, "steps": run.steps})
    doc = {"status": "ok", "pi1": pi1, "t_max": t_max, "impacts": run.impacts,
           "contact_phases": run.phases, "steps": run.steps,
           "message": f"scipy {args.method} rtol {args.rtol:g}"}
    if math.isfinite(run.min_gap):
        doc["min_gap"] = run.min_gap
    if case.get("history_samples"):
        doc["history"] = run.history(case["history_samples"])
    answer(doc)


def respond(text, args):
    global START
    START = time.monotonic()
    try:
        solve_case(text, args)
    except Answered as a:
        doc = a.doc
    doc["solve_seconds"] = time.monotonic() - START
    write(doc)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--rtol", type=float, default=1e-10, help="solve_ivp's relative tolerance")
    parser.add_argument("--method", default="DOP853", help="solve_ivp's method (an explicit one: RK45, DOP853)")
    parser.add_argument("--persistent", action="store_true",
                        help="answer a stream of cases, one line each way (poundbench --persistent)")
    args = parser.parse_args()
    if not args.persistent:
        respond(sys.stdin.read(), args)
        return
    write({"ready": True})
    for line in sys.stdin:
        respond(line, args)


if __name__ == "__main__":
    main()
