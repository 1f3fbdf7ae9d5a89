#include "solvers/event_driven/frame.hpp"

#include <algorithm>
#include <limits>

namespace pb::event_driven {

namespace {

bool pulse_on(const System& s, double t) { return t < s.pulse.duration(); }

// Ground acceleration over the load's piece from t (DERIVATION.md §1), as a wave: the
// paper's pulse as it always was; any other load from its piece, a polynomial of degree 1
// plus sinusoids.
Wave ground(const System& s, double t, const LoadPiece& piece) {
  Wave a = constant(t, 0.0);
  if (s.pulse.paper()) {
    if (pulse_on(s, t)) {
      a.f0 = s.pulse.accel(t);
      a.n_sines = 1;
      a.sine[0].w = s.pulse.w;
      (s.pulse.shape == PulseShape::sine ? a.sine[0].ps : a.sine[0].pc) = s.pulse.amplitude;
    }
  } else {
    a.f0 = piece.accel(t);
    a.lin = piece.slope;
    a.horizon = piece.end;
    a.n_sines = piece.n_waves;
    for (std::size_t j = 0; j < static_cast<std::size_t>(piece.n_waves); ++j)
      a.sine[j] = {piece.waves[j].w, piece.waves[j].s, piece.waves[j].c};
  }
  a.prepare();
  return a;
}

// The load on a cluster of mass m (-m a_g) plus f_const, from t over the piece.
Forcing cluster_load(double t, double m, double f_const, const LoadPiece& piece) {
  Forcing f;
  f.f0 = f_const - m * (piece.value + piece.slope * (t - piece.start));
  f.f1 = -m * piece.slope;
  f.n = piece.n_waves;
  for (std::size_t j = 0; j < static_cast<std::size_t>(piece.n_waves); ++j) {
    f.w[j] = piece.waves[j].w;
    f.fs[j] = -m * piece.waves[j].s;
    f.fc[j] = -m * piece.waves[j].c;
  }
  return f;
}

// Calls f(first, last, fixed) for each run of bodies from..to joined by the contacts flagged
// in `joined` (a run touching the wall through a joined contact is fixed).
template <class F>
void for_each_cluster(const System& s, const std::vector<char>& joined, int from, int to, F&& f) {
  const int wall_shift = s.wall ? 1 : 0;  // contact between bodies i and i+1 is i + wall_shift
  for (int first = from; first <= to;) {
    int last = first;
    while (last + 1 <= to && joined[ix(last + wall_shift)]) ++last;
    f(first, last, s.wall && first == 0 && joined[0]);
    first = last + 1;
  }
}

// Offset of body i from the first body of its cluster when their gaps are closed.
double offset(const System& s, int first, int i) { return -(i - first) * s.delta; }

// The load as a Forcing for a softened cluster's general oscillator: the paper's pulse as its
// one sinusoid, any other load from its piece.
Forcing load_of(const System& s, double t, double m, double f_const, const LoadPiece& piece) {
  if (!s.pulse.paper()) return cluster_load(t, m, f_const, piece);
  Forcing f;
  f.f0 = f_const;
  if (pulse_on(s, t)) {
    f.n = 1;
    f.w[0] = s.pulse.w;
    (s.pulse.shape == PulseShape::sine ? f.fs[0] : f.fc[0]) = -m * s.pulse.amplitude;
  }
  return f;
}

// Writes the yield functions of body i from its wave (Frame::yield).
void yield_functions(const System& s, const State& st, int i, Frame& fr) {
  const Body& b = s.bodies[ix(i)];
  const Wave& u = fr.body[ix(i)];
  Wave& up = fr.yield[ix(2 * i)];
  Wave& down = fr.yield[ix(2 * i + 1)];
  const int branch = st.branch[ix(i)];
  if (branch == 0) {
    reset(up, st.t, b.u_y + st.e[ix(i)]);  // u_y - z = u_y + e - u
    add_scaled(up, u, -1.0);
    up.prepare();
    reset(down, st.t, b.u_y - st.e[ix(i)]);  // u_y + z
    add_scaled(down, u, 1.0);
    down.prepare();
  } else {
    reset(up, st.t, 0.0);  // s u'
    add_scaled(up, derivative(u), branch);
    up.prepare();
  }
}

}  // namespace

Spring spring(const System& s, const State& st, int i) {
  const Body& b = s.bodies[ix(i)];
  if (st.branch.empty() || !b.yields()) return {b.k, 0.0};
  const int branch = st.branch[ix(i)];
  if (branch == 0) return {b.k, -(1.0 - s.alpha) * b.k * st.e[ix(i)]};
  return {s.alpha * b.k, branch * (1.0 - s.alpha) * b.k * b.u_y};
}

double hysteretic_z(const System& s, const State& st, int i) {
  const Body& b = s.bodies[ix(i)];
  if (st.branch.empty() || !b.yields()) return st.u[ix(i)];
  const int branch = st.branch[ix(i)];
  return branch == 0 ? st.u[ix(i)] - st.e[ix(i)] : branch * b.u_y;
}

namespace {

// The motion x of the cluster of bodies first..last (fixed: held at the wall), the
// displacement of its leftmost body (the others sit at fixed offsets: closed gaps), from st
// at st.t over the load's piece.
void cluster_motion(const System& s, const State& st, int first, int last, bool fixed, const LoadPiece& piece,
                    Wave& x) {
  if (fixed) {
    x = constant(st.t, -s.delta);
    return;
  }
  double m = 0.0, c = 0.0, k = 0.0, f_const = 0.0, mx = 0.0, mv = 0.0;
  bool soft = false;  // a body of it yields: its stiffness is alpha k
  for (int i = first; i <= last; ++i) {
    const Body& b = s.bodies[ix(i)];
    const Spring sp = spring(s, st, i);
    m += b.m;
    c += b.c;
    k += sp.k;
    f_const -= sp.k * offset(s, first, i);
    if (sp.r0 != 0.0) f_const -= sp.r0;  // (x - 0.0 would turn a -0.0 into 0.0: no bit moves for elastic bodies)
    soft = soft || (!st.branch.empty() && st.branch[ix(i)] != 0);
    mx += b.m * (st.u[ix(i)] - offset(s, first, i));
    mv += b.m * st.v[ix(i)];
  }
  if (soft) {
    // A softened cluster may be critically or overdamped, or have no stiffness: the
    // general mode (underdamped near a sinusoid's resonance, the forms below), whose
    // growth without stiffness needs a finite horizon: t_end at most.
    const Forcing load = load_of(s, st.t, m, f_const, piece);
    if (!near_resonance(m, c, k, load)) {
      const double end = s.pulse.paper() ? (pulse_on(s, st.t) ? s.pulse.duration() : s.t_end) : piece.end;
      general_oscillator_into(x, st.t, mx / m, mv / m, m, c, k, load, std::min(end, s.t_end));
      return;
    }
  }
  if (!s.pulse.paper()) {
    oscillator_into(x, st.t, mx / m, mv / m, m, c, k, cluster_load(st.t, m, f_const, piece), piece.end);
  } else {
    const bool on = pulse_on(s, st.t);
    const double load = on ? -m * s.pulse.amplitude : 0.0;
    const bool sine = s.pulse.shape == PulseShape::sine;
    const double horizon = on ? s.pulse.duration() : std::numeric_limits<double>::infinity();
    oscillator_into(x, st.t, mx / m, mv / m, m, c, k, f_const, sine ? load : 0.0, sine ? 0.0 : load, s.pulse.w,
                    horizon);
  }
}

}  // namespace

// A cluster's coordinate x is the displacement of its leftmost body; the others sit at
// fixed offsets (closed gaps).
void build_frame(const System& s, const State& st, int from, int to, Frame& fr) {
  const LoadPiece piece = s.pulse.paper() ? LoadPiece{} : s.pulse.piece(st.t);
  const Wave ag = ground(s, st.t, piece);
  const int wall_shift = s.wall ? 1 : 0;
  for_each_cluster(s, st.active, from, to, [&](int first, int last, bool fixed) {
    // The cluster's motion, written where it goes: a chain rebuilds every body at every
    // event, and clearing a Wave (some 650 bytes) and copying it cost as much as the maths.
    const auto motion = [&](Wave& x) { cluster_motion(s, st, first, last, fixed, piece, x); };
    if (!fr.motion.empty()) std::fill(fr.motion.begin() + first, fr.motion.begin() + last + 1, ++fr.motions);
    if (first == last && !fixed) {  // a free body: no force to build from x
      Wave& body = fr.body[ix(first)];
      motion(body);
      body.f0 += offset(s, first, first);
      return;
    }
    Wave x;
    motion(x);
    for (int i = first; i <= last; ++i) {
      fr.body[ix(i)] = x;
      fr.body[ix(i)].f0 += offset(s, first, i);
    }
    // Force of a persistent contact: what the bodies right of it need to follow the cluster,
    // lambda = sum over them of m x'' + c x' + k u + m a_g.
    if (last > first || fixed) {
      const Wave dx = derivative(x), ddx = derivative(dx);
      double mr = 0.0, cr = 0.0, kr = 0.0, ko = 0.0;
      for (int i = last; i >= first; --i) {
        const Body& b = s.bodies[ix(i)];
        const Spring sp = spring(s, st, i);
        mr += b.m;
        cr += b.c;
        kr += sp.k;
        ko += sp.k * offset(s, first, i);
        if (sp.r0 != 0.0) ko += sp.r0;
        const int j = i - 1 + wall_shift;  // contact left of body i
        if (j < 0 || (i == first && !fixed)) continue;
        Wave& f = fr.contact[ix(j)];
        reset(f, st.t, ko);
        add_scaled(f, x, kr);
        if (!fixed) {
          add_scaled(f, dx, cr);
          add_scaled(f, ddx, mr);
        }
        add_scaled(f, ag, mr);
        f.prepare();
      }
    }
  });
  if (!fr.yield.empty())
    for (int i = from; i <= to; ++i)
      if (s.bodies[ix(i)].yields()) yield_functions(s, st, i, fr);
  for (int j = first_contact(s, from); j <= last_contact(s, to); ++j) {
    if (st.active[ix(j)]) continue;
    build_gap(st, j, fr.body[ix(s.right(j))], s.left(j) != kWall ? &fr.body[ix(s.left(j))] : nullptr,
              fr.contact[ix(j)]);
  }
}

void body_motion(const System& s, const State& st, int first, int last, int i, Wave& u) {
  const bool fixed = s.wall && first == 0 && st.active[0];
  cluster_motion(s, st, first, last, fixed, s.pulse.paper() ? LoadPiece{} : s.pulse.piece(st.t), u);
  u.f0 += offset(s, first, i);
}

void build_gap(const State& st, int j, const Wave& right, const Wave* left, Wave& g) {
  reset(g, st.t, 0.0);
  add_scaled(g, right, 1.0);
  if (left) add_scaled(g, *left, -1.0);
  g.f0 = st.g[ix(j)];
  g.prepare();
}

void close_gaps(const System& s, const std::vector<char>& joined, std::vector<double>& u, int from, int to) {
  for_each_cluster(s, joined, from, to, [&](int first, int last, bool fixed) {
    if (first == last && !fixed) return;
    double m = 0.0, mx = 0.0;
    for (int i = first; i <= last; ++i) {
      m += s.bodies[ix(i)].m;
      mx += s.bodies[ix(i)].m * (u[ix(i)] - offset(s, first, i));
    }
    const double x = fixed ? -s.delta : mx / m;
    for (int i = first; i <= last; ++i) u[ix(i)] = x + offset(s, first, i);
  });
}

}  // namespace pb::event_driven
