#include "solvers/event_driven/event_driven.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <sstream>

#include "solvers/event_driven/impact.hpp"
#include "solvers/event_driven/search.hpp"
#include "solvers/event_driven/wave.hpp"

namespace pb::event_driven {

namespace {

// Every tolerance is relative to the pulse's own scales (L = a_p / w_p^2, V = a_p / w_p,
// the shortest period), so the solution is the same at any a_p, w_p (self-similarity).
struct Tolerances {
  double gap;     // a gap below this is closed (simultaneous impacts, accumulations)
  double speed;   // an approach slower than this ends an accumulation: the impact is plastic
  double lex;     // relative size below which a Taylor coefficient counts as zero
  double floor;   // the shortest window a search resolves (seconds)
  double settle;  // how long a just-opened contact may take to show a positive gap
};

Tolerances tolerances(const System& s, double scale) {
  const double eps = std::numeric_limits<double>::epsilon();
  Tolerances t;
  t.gap = 1e-10 * scale * s.length_scale();
  t.speed = 1e-7 * scale * s.a_p / s.pulse.w;
  t.lex = 1e-9 * scale;
  t.floor = std::max(1e-13 * s.t_min, 8.0 * eps * s.t_end);
  t.settle = 1e-4 * s.t_min;
  return t;
}

struct State {
  double t = 0.0;
  std::vector<double> u, v, g;
  std::vector<char> active;  // persistent contact
};

// The motion from state.t to the next event: waves of every body displacement and, per
// contact, of its gap (open) or its force (persistent contact).
struct Frame {
  std::vector<Wave> body;
  std::vector<Wave> contact;
};

std::size_t ix(int i) { return static_cast<std::size_t>(i); }

bool pulse_on(const System& s, double t) { return t < s.pulse.duration(); }

// Ground acceleration over the segment starting at t, as a wave.
Wave ground(const System& s, double t) {
  Wave a = constant(t, 0.0);
  if (pulse_on(s, t)) {
    a.f0 = s.pulse.accel(t);
    a.w = s.pulse.w;
    (s.pulse.shape == PulseShape::sine ? a.ps : a.pc) = s.pulse.amplitude;
  }
  a.prepare();
  return a;
}

// Calls f(first, last, fixed) for each run of bodies joined by the contacts flagged in
// `joined` (a run touching the wall through a joined contact is fixed).
template <class F>
void for_each_cluster(const System& s, const std::vector<char>& joined, F&& f) {
  const int wall_shift = s.wall ? 1 : 0;  // contact between bodies i and i+1 is i + wall_shift
  for (int first = 0; first < s.n_bodies();) {
    int last = first;
    while (last + 1 < s.n_bodies() && joined[ix(last + wall_shift)]) ++last;
    f(first, last, s.wall && first == 0 && joined[0]);
    first = last + 1;
  }
}

// Offset of body i from the first body of its cluster when their gaps are closed.
double offset(const System& s, int first, int i) { return -(i - first) * s.delta; }

// Bodies joined by persistent contacts move as one oscillator; its coordinate x is the
// displacement of its leftmost body, the others sit at fixed offsets (closed gaps).
void build_frame(const System& s, const State& st, Frame& fr) {
  fr.body.resize(ix(s.n_bodies()));
  fr.contact.resize(ix(s.n_contacts()));
  const Wave ag = ground(s, st.t);
  const int wall_shift = s.wall ? 1 : 0;
  for_each_cluster(s, st.active, [&](int first, int last, bool fixed) {
    double m = 0.0, c = 0.0, k = 0.0, f_const = 0.0, mx = 0.0, mv = 0.0;
    for (int i = first; i <= last; ++i) {
      const Body& b = s.bodies[ix(i)];
      m += b.m;
      c += b.c;
      k += b.k;
      f_const -= b.k * offset(s, first, i);
      mx += b.m * (st.u[ix(i)] - offset(s, first, i));
      mv += b.m * st.v[ix(i)];
    }
    Wave x;
    if (fixed) {
      x = constant(st.t, -s.delta);
    } else {
      const bool on = pulse_on(s, st.t);
      const double load = on ? -m * s.pulse.amplitude : 0.0;
      const bool sine = s.pulse.shape == PulseShape::sine;
      x = oscillator(st.t, mx / m, mv / m, m, c, k, f_const, sine ? load : 0.0, sine ? 0.0 : load, s.pulse.w);
    }
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
        mr += b.m;
        cr += b.c;
        kr += b.k;
        ko += b.k * offset(s, first, i);
        const int j = i - 1 + wall_shift;  // contact left of body i
        if (j < 0 || (i == first && !fixed)) continue;
        Wave& f = fr.contact[ix(j)];
        f = constant(st.t, ko);
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
  for (int j = 0; j < s.n_contacts(); ++j) {
    if (st.active[ix(j)]) continue;
    Wave& g = fr.contact[ix(j)];
    g = constant(st.t, 0.0);
    add_scaled(g, fr.body[ix(s.right(j))], 1.0);
    if (s.left(j) != kWall) add_scaled(g, fr.body[ix(s.left(j))], -1.0);
    g.f0 = st.g[ix(j)];
    g.prepare();
  }
}

// True when the first coefficient that is not negligible is positive.
bool lex_nonnegative(const double* c, int n, double scale, double rate, double tol) {
  double z = tol * scale;
  for (int k = 0; k < n; ++k, z *= rate) {
    if (c[k] > z) return true;
    if (c[k] < -z) return false;
  }
  return true;
}

class Solver {
 public:
  Solver(const System& s, const Settings& settings)
      : s_(s), tol_(tolerances(s, settings.tol_scale)), cap_(settings.step_cap > 0 ? settings.step_cap : 1000000) {
    const auto n = ix(s.n_bodies()), nc = ix(s.n_contacts());
    st_.u.assign(n, 0.0);
    st_.v.assign(n, 0.0);
    st_.g.assign(nc, s.delta);
    st_.active.assign(nc, 0);
    rate_ = s.pulse.w;
    for (const Body& b : s.bodies) rate_ = std::max(rate_, b.w);
    // A force is compared with the gap accelerations it makes: lambda (1/m_left + 1/m_right).
    force_scale_.resize(nc);
    for (int j = 0; j < s.n_contacts(); ++j) {
      double inv_mass = 1.0 / s.bodies[ix(s.right(j))].m;
      if (s.left(j) != kWall) inv_mass += 1.0 / s.bodies[ix(s.left(j))].m;
      force_scale_[ix(j)] = s.a_p / inv_mass;
    }
    if (settings.history_samples > 0) {
      samples_ = settings.history_samples;
      res_.history.n_bodies = s.n_bodies();
      res_.history.n_contacts = s.n_contacts();
      res_.history.data.reserve(ix(samples_ * res_.history.row_size()));
    }
  }

  Result run() {
    std::vector<int> closed;
    for (int j = 0; j < s_.n_contacts(); ++j)
      if (st_.g[ix(j)] <= tol_.gap) closed.push_back(j);
    if (!resolve(closed)) return finish();
    const double t_p = s_.pulse.duration();
    while (st_.t < s_.t_end) {
      const double seg_end = st_.t < t_p ? std::min(t_p, s_.t_end) : s_.t_end;
      double b = seg_end;
      int which = -1;
      for (int j = 0; j < s_.n_contacts(); ++j) {
        const double noise = st_.active[ix(j)] ? tol_.lex * force_scale_[ix(j)] : tol_.gap;
        const double r = first_root(fr_.contact[ix(j)], st_.t, b, tol_.floor, tol_.settle, noise);
        if (!std::isnan(r) && r <= b) {
          b = r;
          which = j;
        }
      }
      max_abs(fr_.body[ix(s_.ref)], st_.t, b, tol_.floor, peak_);
      record(b);
      advance(b);
      if (++res_.steps > cap_) {
        res_.status = Status::step_cap;
        res_.message = "more than " + std::to_string(cap_) + " events";
        break;
      }
      if (which >= 0) {
        const bool ok = st_.active[ix(which)] ? detach() : impact(which);
        if (!ok) break;
      } else if (st_.t < s_.t_end) {
        if (!detach()) break;  // end of the pulse: the load may jump, contacts re-decided
      }
    }
    return finish();
  }

 private:
  Result finish() {
    res_.pi1 = s_.pi1(peak_.value);
    res_.t_max = peak_.t;
    return std::move(res_);
  }

  void advance(double t) {
    double v[2];
    for (int i = 0; i < s_.n_bodies(); ++i) {
      fr_.body[ix(i)].eval(t, v, 2);
      st_.u[ix(i)] = v[0];
      st_.v[ix(i)] = v[1];
    }
    for (int j = 0; j < s_.n_contacts(); ++j) {
      st_.g[ix(j)] = st_.active[ix(j)] ? 0.0 : fr_.contact[ix(j)].value(t);
      res_.min_gap = std::min(res_.min_gap, st_.g[ix(j)] < 0.0 ? st_.g[ix(j)] : res_.min_gap);
    }
    st_.t = t;
  }

  // Samples of the state at equally spaced times in [state.t, t] (the first from t = 0).
  void record(double t) {
    if (samples_ <= 0) return;
    const double dt = samples_ > 1 ? s_.t_end / (samples_ - 1) : 0.0;
    auto& data = res_.history.data;
    while (next_sample_ < samples_) {
      const double ts = next_sample_ == samples_ - 1 ? s_.t_end : dt * next_sample_;
      if (ts > t) break;
      double v[2];
      data.push_back(ts);
      const std::size_t at_u = data.size();
      data.resize(data.size() + ix(2 * s_.n_bodies()));
      for (int i = 0; i < s_.n_bodies(); ++i) {
        fr_.body[ix(i)].eval(ts, v, 2);
        data[at_u + ix(i)] = v[0];
        data[at_u + ix(s_.n_bodies() + i)] = v[1];
      }
      for (int j = 0; j < s_.n_contacts(); ++j)
        data.push_back(st_.active[ix(j)] ? 0.0 : fr_.contact[ix(j)].value(ts));
      for (int j = 0; j < s_.n_contacts(); ++j)
        data.push_back(st_.active[ix(j)] ? fr_.contact[ix(j)].value(ts) : 0.0);
      ++next_sample_;
    }
  }

  // A gap closed at the current time: Poisson impact on every closed contact.
  bool impact(int j) {
    st_.g[ix(j)] = 0.0;
    std::vector<int> set;
    double approach = 0.0;
    for (int k = 0; k < s_.n_contacts(); ++k) {
      if (st_.active[ix(k)] || st_.g[ix(k)] <= tol_.gap) {
        set.push_back(k);
        approach = std::min(approach, gap_rate(s_, k, st_.v));
      }
    }
    for (int k : set)
      if (gap_rate(s_, k, st_.v) < -tol_.speed) ++res_.impacts;
    // An approach slower than the tolerance ends an accumulation of impacts: plastic.
    const double eps = -approach > tol_.speed ? s_.eps : 0.0;
    const ImpactOutcome out = poisson_impact(s_, set, st_.v, eps);
    std::vector<int> closed;
    for (std::size_t a = 0; a < set.size(); ++a) {
      if (out.gap_rate[a] <= tol_.speed) {
        closed.push_back(set[a]);
        st_.g[ix(set[a])] = 0.0;
      }
    }
    return resolve(closed);
  }

  // A persistent contact's force reached zero, or the load jumped: re-decide all of them.
  bool detach() {
    std::vector<int> closed;
    for (int k = 0; k < s_.n_contacts(); ++k)
      if (st_.active[ix(k)]) closed.push_back(k);
    return resolve(closed);
  }

  // The acceleration-level LCP (paper eq. 1) on the closed contacts with zero relative
  // velocity, solved by enumerating active sets: a set fits when every active force and
  // every inactive gap acceleration is lexicographically non-negative in its Taylor
  // coefficients at t, which decides degenerate starts (zero force, zero relative
  // acceleration) by the first derivative of the load that does not vanish.
  bool resolve(const std::vector<int>& closed) {
    const std::vector<char> before = st_.active;
    const int n = static_cast<int>(closed.size());
    close_gaps(closed);
    if (n > 16) return fail("more than 16 closed contacts at once");
    // Coefficients within round-off of zero defer to the next derivative. If round-off in
    // the higher derivatives leaves no set that fits, the plain signs decide, and failing
    // that the values alone (the LCP at t, which always has a solution).
    struct Pass {
      double tol;
      int depth;
    };
    for (const Pass pass : {Pass{tol_.lex, kMaxDerivative - 1}, Pass{0.0, kMaxDerivative - 1}, Pass{tol_.lex, 1}}) {
      for (int mask = (1 << n) - 1; mask >= 0; --mask) {
        std::fill(st_.active.begin(), st_.active.end(), 0);
        for (int a = 0; a < n; ++a)
          if (mask & (1 << a)) st_.active[ix(closed[ix(a)])] = 1;
        build_frame(s_, st_, fr_);
        if (fits(closed, pass.tol, pass.depth)) {
          for (std::size_t j = 0; j < before.size(); ++j)
            if (st_.active[j] && !before[j]) ++res_.contact_phases;
          return true;
        }
      }
    }
    std::ostringstream msg;
    msg << "no contact configuration fits the acceleration LCP at t = " << st_.t;
    return fail(msg.str());
  }

  // Closed gaps were closed to within tol_gap; move the bodies (keeping their centre of
  // mass) so that the positions agree exactly. Otherwise the springs would see a gap the
  // contact logic does not, and late in a run, when the motion itself is that small, the
  // contact LCP would be decided by it.
  void close_gaps(const std::vector<int>& closed) {
    std::vector<char> joined(ix(s_.n_contacts()), 0);
    for (int j : closed) joined[ix(j)] = 1;
    for_each_cluster(s_, joined, [&](int first, int last, bool fixed) {
      if (first == last && !fixed) return;
      double m = 0.0, mx = 0.0;
      for (int i = first; i <= last; ++i) {
        m += s_.bodies[ix(i)].m;
        mx += s_.bodies[ix(i)].m * (st_.u[ix(i)] - offset(s_, first, i));
      }
      const double x = fixed ? -s_.delta : mx / m;
      for (int i = first; i <= last; ++i) st_.u[ix(i)] = x + offset(s_, first, i);
    });
  }

  bool fits(const std::vector<int>& closed, double tol, int depth) const {
    double c[kMaxDerivative + 1];
    for (int j : closed) {
      fr_.contact[ix(j)].eval(st_.t, c, kMaxDerivative + 1);
      const bool ok = st_.active[ix(j)]
                          ? lex_nonnegative(c, std::min(depth, 4), force_scale_[ix(j)], rate_, tol)
                          : lex_nonnegative(c + 1, depth + 1, s_.a_p / rate_, rate_, tol);
      if (!ok) return false;
    }
    return true;
  }

  bool fail(std::string why) {
    res_.status = Status::failed;
    res_.message = std::move(why);
    return false;
  }

  const System& s_;
  Tolerances tol_;
  long cap_;
  State st_;
  Frame fr_;
  Peak peak_;
  Result res_;
  double rate_ = 1.0;
  std::vector<double> force_scale_;  // per contact
  int samples_ = 0, next_sample_ = 0;
};

}  // namespace

Result solve(const System& system, const Settings& settings) {
  try {
    return Solver(system, settings).run();
  } catch (const std::exception& e) {
    Result r;
    r.status = Status::failed;
    r.message = e.what();
    return r;
  }
}

std::string describe(const Settings& settings) {
  std::ostringstream out;
  out << "tol_scale=" << settings.tol_scale;
  return out.str();
}

std::string check(const Settings& settings) {
  if (!(settings.tol_scale > 0.0) || !std::isfinite(settings.tol_scale)) return "tol-scale: must be finite and > 0";
  if (settings.steps != 0) return "steps: the event-driven solver takes no step";
  return {};
}

double no_contact_pi1(const System& system) {
  System alone = system;
  alone.bodies = {system.bodies[ix(system.ref)]};
  alone.wall = false;
  alone.ref = 0;
  return solve(alone, Settings{}).pi1;
}

}  // namespace pb::event_driven
