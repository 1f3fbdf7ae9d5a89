#include "solvers/event_driven/event_driven.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <memory>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <utility>

#include <Eigen/Core>

#include "cases/text.hpp"
#include "kit/contact_elements/contact_law.hpp"
#include "solvers/event_driven/frame.hpp"
#include "solvers/event_driven/impact.hpp"
#include "solvers/event_driven/kelvin_voigt.hpp"
#include "solvers/event_driven/plastic.hpp"
#include "solvers/event_driven/recurrence.hpp"
#include "solvers/event_driven/search.hpp"
#include "kit/lcp/lemke.hpp"
#include "kit/named_values.hpp"
#include "kit/run_limits.hpp"
#include "kit/lex_sign.hpp"

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

// A yielding body's unloading function s u' is a velocity: its neutral level (search.hpp,
// first_root) this far below the plastic-approach speed, 1e-10 a_p / w_p at tol_scale 1, so
// that a phase that ends on a grazing stop keeps z within round-off of u_y.
constexpr double kNeutralRate = 1e-3;

// Runs of closed contacts up to this length are decided by enumerating their 2^n active
// sets; longer ones take Lemke's proposal (DERIVATION.md §4).
constexpr int kEnumerateLimit = 8;
bool known_variant(std::string_view v) { return v.empty() || v == kLemkeVariant; }
bool kelvin_voigt(const Settings& s) { return s.contact == kKelvinVoigtContact; }

// One way of deciding the contact LCP: Taylor coefficients within `tol` (relative) of zero
// defer to the next one, up to `depth` derivatives beyond a gap's rate.
struct Pass {
  double tol;
  int depth;
};

// The start state given, or rest, into out.
void start_or_rest(const std::vector<double>& start, std::size_t n, std::vector<double>& out) {
  if (start.size() == n)
    out.assign(start.begin(), start.end());
  else
    out.assign(n, 0.0);
}

// What a solve works in besides its result: the state, the frame, per-contact scratch and
// the LCP workspaces. Kept per thread between solves: a sweep solves one point after another,
// and making these twenty-odd vectors and workspaces anew for each was some 5 % of a pair
// point's instructions (callgrind). Every value a solve reads it writes first (a frame's
// waves are rebuilt in place at every event already), so a solve's results do not depend on
// what the last one left.
struct Scratch {
  State st;
  Frame fr;
  std::vector<double> force_scale;  // per contact
  std::vector<int> closed, set;
  std::vector<double> impulse, eval_u, eval_v;
  std::vector<char> joined, before, proposal;
  std::vector<char> fresh;
  std::vector<double> root, searched;
  std::vector<double> u_event, v_event;
  std::vector<char> active_event, changed;
  // Lazy events (Solver::lazy_).
  Wave side;
  std::vector<long> body_epoch, gap_epoch;
  std::vector<double> clear_until;
  std::vector<int> touched, region;
  std::vector<char> in_region;
  ImpactWork work;
  lcp::LemkeWorkspace lemke;
  Eigen::MatrixXd delassus, lex_q, lex_z;
  Plasticity plastic;
  // The recurrence (Solver::recur): per body, its oscillator's index in `recurrences` (bodies
  // of one c / m and k / m share one), and its increments and acceleration bound over the
  // sample interval at hand.
  std::vector<Recurrence> recurrences;
  std::vector<int> body_recurrence;
  std::vector<double> du, dv, acc;
  Lengths lengths;
  Wave peak_wave;  // body 0's, for a peak the bounds cannot place
  bool busy = false;
};

// The thread's Scratch, or a new one if the thread's is in use (a solve inside a solve).
class ScratchLease {
 public:
  ScratchLease() {
    thread_local Scratch kept;
    if (kept.busy) {
      own_ = std::make_unique<Scratch>();
      s_ = own_.get();
    } else {
      s_ = &kept;
    }
    s_->busy = true;
  }
  ScratchLease(const ScratchLease&) = delete;
  ScratchLease& operator=(const ScratchLease&) = delete;
  ~ScratchLease() { s_->busy = false; }
  Scratch& operator*() const { return *s_; }

 private:
  std::unique_ptr<Scratch> own_;
  Scratch* s_;
};

class Solver {
 public:
  // free: every contact removed, its gap watched (free_motion). recurrence: a record's sample
  // intervals without an event taken by the recurrence (recur, DERIVATION.md §11).
  Solver(const System& s, const Settings& settings, bool keep_searches = true, bool lazy = true, bool free = false,
         bool recurrence = true)
      : s_(s),
        tol_(tolerances(s, settings.tol_scale)),
        cap_(settings.step_cap > 0 ? settings.step_cap : 1000000),
        deadline_(settings),
        floor_(kRestitutionFloor * s.a_p / s.pulse.w),
        lemke_first_(settings.variant == kLemkeVariant),
        tol_scale_(settings.tol_scale),
        free_(free) {
    work_.lemke_only = lemke_first_;
    const auto n = ix(s.n_bodies()), nc = ix(s.n_contacts());
    st_.t = 0.0;
    start_or_rest(s.u_start, n, st_.u);
    start_or_rest(s.v_start, n, st_.v);
    st_.g.resize(nc);
    for (int j = 0; j < s.n_contacts(); ++j) st_.g[ix(j)] = s.gap(j, st_.u.data());
    st_.active.assign(nc, 0);
    fr_.body.resize(n);
    fr_.contact.resize(nc);
    plastic_.start(s, st_, fr_);
    rate_ = s.pulse.w;
    for (const Body& b : s.bodies) rate_ = std::max(rate_, b.w);
    // A force is compared with the gap accelerations it makes: lambda (1/m_left + 1/m_right).
    force_scale_.resize(nc);
    for (int j = 0; j < s.n_contacts(); ++j) {
      double inv_mass = 1.0 / s.bodies[ix(s.right(j))].m;
      if (s.left(j) != kWall) inv_mass += 1.0 / s.bodies[ix(s.left(j))].m;
      force_scale_[ix(j)] = s.a_p / inv_mass;
    }
    closed_.clear();
    set_.clear();
    closed_.reserve(nc);
    set_.reserve(nc);
    impulse_.resize(nc);
    joined_.assign(nc, 0);
    before_.resize(nc);
    proposal_.resize(nc);
    eval_u_.resize(n);
    eval_v_.resize(n);
    incremental_ = keep_searches && s.n_contacts() > 2 && !free_;
    fresh_.assign(nc, 1);
    root_.assign(nc, std::numeric_limits<double>::quiet_NaN());
    searched_.assign(nc, 0.0);
    changed_.resize(n);
    lazy_ = lazy && incremental_ && !plastic_.on();
    fr_.motion.assign(lazy_ ? n : 0, 0);  // kept by the lazy events alone (sync_cluster)
    if (lazy_) {
      body_epoch_.assign(n, -1);
      gap_epoch_.assign(nc, -1);
      clear_until_.assign(nc, -std::numeric_limits<double>::infinity());
      in_region_.assign(n, 0);
      u_event_.resize(n);
      v_event_.resize(n);
    }
    if (free_) {
      body_peak_.assign(n, Peak{});
      closing_.assign(nc, Peak{});
      opening_.assign(nc, Peak{});
    }
    start_recurrence(recurrence);
    if (settings.history_samples > 0) {
      samples_ = settings.history_samples;
      res_.history.n_bodies = s.n_bodies();
      res_.history.n_contacts = s.n_contacts();
      res_.history.data.reserve(ix(samples_ * res_.history.row_size()));
    }
  }

  Result run() {
    try {
      events();
    } catch (const OutOfTime&) {
      res_.status = Status::time_limit;
      std::ostringstream msg;
      msg << deadline_.reason() << " (t = " << st_.t << " of " << s_.t_end << ")";
      res_.message = msg.str();
    } catch (const NonFinite&) {
      res_.status = Status::nan;
      std::ostringstream msg;
      msg << "the closed-form motion is not finite at t = " << st_.t;
      res_.message = msg.str();
    }
    return finish();
  }

  // run() of a free Solver: its peaks, and its gaps' extremes (each gap is u_right - u_left
  // there: free_motion sets delta to 0).
  FreeMotion free_run() {
    Result r = run();
    FreeMotion out;
    out.status = r.status;
    out.message = std::move(r.message);
    if (r.status != Status::ok) return out;
    for (const Peak& p : body_peak_) out.peak.push_back(p.value);
    for (const Peak& p : closing_) out.closing.push_back(p.value);
    for (const Peak& p : opening_) out.opening.push_back(p.value);
    return out;
  }

 private:
  void events() {
    if (!start()) return;
    const double t_p = s_.pulse.duration();
    const bool paper = s_.pulse.paper();
    while (st_.t < s_.t_end) {
      if (recurrence_) {
        const int taken = recur();
        if (taken > 0) continue;
        if (taken < 0) break;
      }
      // The segment ends where the load's closed form does: the paper's pulse at T_p, any
      // other load at its next breakpoint (a record's next sample), each an event.
      const double seg_end = paper ? (st_.t < t_p ? std::min(t_p, s_.t_end) : s_.t_end)
                                   : std::min(s_.pulse.next_break(st_.t), s_.t_end);
      double b = seg_end;
      int which = -1;
      for (int j = 0; j < (free_ ? 0 : s_.n_contacts()); ++j) {
        const double r = next_root(j, b);
        if (!std::isnan(r) && r <= b) {
          b = r;
          which = j;
        }
      }
      // A yield or unloading (DERIVATION.md §10) before it; at the same time the contact's
      // event goes first, and the impact's settling of the branches sees the yield.
      YieldEvent yield{std::numeric_limits<double>::quiet_NaN()};
      if (plastic_.on()) {
        yield = plastic_.next(s_, st_, fr_, b, tol_.floor, tol_.settle, tol_.gap, kNeutralRate * tol_.speed,
                              deadline_);
        if (!std::isnan(yield.t)) {
          b = yield.t;
          which = -1;
        }
      }
      if (free_)
        watch(b);  // body 0's peak among the others'
      else
        max_abs(fr_.body[ix(s_.ref)], st_.t, b, tol_.floor, peak_, deadline_);
      record(b);
      if (plastic_.on()) plastic_.integrate(s_, fr_, st_.t, b);
      // A contact's event within the load's piece touches only the bodies it reaches; at a
      // breakpoint (or the end) every motion changes, and the whole frame is rebuilt.
      const bool lazy_event = lazy_ && which >= 0 && b < seg_end;
      if (lazy_event)
        begin_event(b);
      else
        advance(b);
      if (incremental_ && !lazy_) {
        u_event_ = st_.u;
        v_event_ = st_.v;
        active_event_ = st_.active;
      }
      if (++res_.steps > cap_) {
        res_.status = Status::step_cap;
        res_.message = "more than " + std::to_string(cap_) + " events";
        break;
      }
      if (deadline_.tick()) throw OutOfTime{};  // one counter with the searches' looks
      if (which < 0 && st_.t >= s_.t_end) break;
      if (free_) {
        // No contact: a breakpoint of the load or a yield changes the motion of every body.
        if (!std::isnan(yield.t)) plastic_.change(s_, st_, yield);
        build_frame(s_, st_, 0, s_.n_bodies() - 1, fr_);
        continue;
      }
      if (lazy_event) {
        if (!(st_.active[ix(which)] ? detach_lazily(which) : impact_lazily(which))) break;
        continue;
      }
      const double e_before = energy(st_.u.data(), st_.v.data());
      bool ok;
      if (which >= 0 && !st_.active[ix(which)]) {
        st_.g[ix(which)] = 0.0;
        ok = impact();
      } else {
        // A force reached zero, the load reached a breakpoint (it may jump), or a body
        // yielded or unloaded (its stiffness changed): the persistent contacts anew. A
        // yield found an ulp before a contact's closure (a yield displacement equal to the
        // gap) leaves that contact closed and approaching: its impact is now.
        if (!std::isnan(yield.t)) plastic_.change(s_, st_, yield);
        ok = !std::isnan(yield.t) && closing() ? impact() : detach();
      }
      if (!ok) break;
      account(e_before);
      // At a load's breakpoint (and a yield) every motion changes; a contact's event
      // changes those of the bodies it reaches.
      if (which < 0 || b >= seg_end || !incremental_)
        std::fill(fresh_.begin(), fresh_.end(), 1);
      else
        mark_changed(which);
      if (lazy_) note_all_gaps();
    }
  }

  // The recurrence (DERIVATION.md §11): on a record, between samples, every body that no
  // persistent contact holds is a damped oscillator under a linear load, whose state at the
  // sample's end is a few products from its state at the start. recur() takes a sample
  // interval so where bounds prove that the full event loop would find nothing in it: no gap
  // closes, no |u| reaches the peak so far (in a free run: no body's |u| and no gap's either
  // way). Yielding bodies keep the full path (their branch changes the motion), and so do the
  // paper's pulses and the pulse models (a sinusoidal load: no sample intervals).
  void start_recurrence(bool wanted) {
    recurrence_ = wanted && s_.pulse.record && !s_.pulse.paper() && !plastic_.on() && s_.pulse.record->t.size() >= 2;
    if (!recurrence_) return;
    auto& recs = scratch_.recurrences;
    auto& of = scratch_.body_recurrence;
    recs.clear();
    of.assign(ix(s_.n_bodies()), -1);
    for (int i = 0; i < s_.n_bodies(); ++i) {
      const Body& b = s_.bodies[ix(i)];
      int at = -1;  // bodies of one c / m and k / m share their transitions
      for (std::size_t q = 0; q < recs.size() && at < 0; ++q)
        if (recs[q].two_sigma() == b.c / b.m && recs[q].w2() == b.k / b.m) at = static_cast<int>(q);
      if (at < 0) {
        at = static_cast<int>(recs.size());
        recs.emplace_back(b.m, b.c, b.k);
        if (!recs.back().valid()) {
          recurrence_ = false;
          return;
        }
      }
      of[ix(i)] = at;
    }
    scratch_.du.resize(ix(s_.n_bodies()));
    scratch_.dv.resize(ix(s_.n_bodies()));
    scratch_.acc.resize(ix(s_.n_bodies()));
    scratch_.lengths.clear();
    sample_ = 0;
    stale_ = false;
  }

  // 1: the sample interval from st_.t was taken by the recurrence; 0: the event loop takes
  // it (the frame is then current); -1: the run ends (the event cap).
  int recur() {
    const Record& rec = *s_.pulse.record;
    const std::vector<double>& ts = rec.t;
    std::size_t i = sample_;
    while (i + 1 < ts.size() && ts[i + 1] <= st_.t) ++i;
    sample_ = i;
    // From a sample to the next, both within the run, no history sample on the way.
    if (!(i + 1 < ts.size() && ts[i] == st_.t && ts[i + 1] <= s_.t_end)) return by_events();
    const double b = ts[i + 1];
    if (samples_ > 0 && next_sample_ < samples_ && history_time(next_sample_) <= b) return by_events();
    const double h = b - st_.t;
    const int slot = scratch_.lengths.slot(h);
    if (slot < 0) {  // an unevenly sampled record: a transition per interval would cost more
      recurrence_ = false;
      return by_events();
    }
    // The piece's load as Pulse::piece_at writes it, per unit mass: q = -a_g.
    const std::vector<double>& as = rec.a;
    const double amplitude = s_.pulse.amplitude;
    const double q0 = -(amplitude * as[i]), q1 = -(amplitude * ((as[i + 1] - as[i]) / (ts[i + 1] - ts[i])));
    const std::size_t n = ix(s_.n_bodies());
    Recurrence* recs = scratch_.recurrences.data();
    const int* of = scratch_.body_recurrence.data();
    double *du = scratch_.du.data(), *dv = scratch_.dv.data(), *acc = scratch_.acc.data();
    const double *u = st_.u.data(), *v = st_.v.data();
    for (std::size_t k = 0; k < n; ++k) {
      Recurrence& r = recs[of[k]];
      const Recurrence::Step step = r.step(r.over(slot, h), u[k], v[k], q0, q1);
      du[k] = step.dx;
      dv[k] = step.dv;
      acc[k] = step.acc;
    }
    const auto jerk = [&](std::size_t k) { return recs[of[k]].w() * acc[k]; };
    // Each contact: no gap may close (come within twice the closure tolerance) before b.
    for (int j = 0; j < s_.n_contacts(); ++j) {
      const auto k = ix(j);
      if (st_.active[k]) return by_events();
      const auto r = ix(s_.right(j));
      const bool wall = s_.left(j) == kWall;
      const auto l = wall ? r : ix(s_.left(j));
      const double ga = st_.g[k], gb = ga + (wall ? du[r] : du[r] - du[l]);
      if (free_) {
        const Ends g{ga,
                     gb,
                     v[r] - (wall ? 0.0 : v[l]),
                     v[r] + dv[r] - (wall ? 0.0 : v[l] + dv[l]),
                     acc[r] + (wall ? 0.0 : acc[l]),
                     jerk(r) + (wall ? 0.0 : jerk(l))};
        if (!watch_ends(g, b, opening_[k]) || !watch_ends(g.flip(), b, closing_[k])) return by_events();
      } else if (!(std::min(ga, gb) - (acc[r] + (wall ? 0.0 : acc[l])) * reach(h) > 2.0 * tol_.gap)) {
        return by_events();
      }
    }
    // The peaks: body 0's |u| (every body's in a free run).
    const auto ends = [&](std::size_t k) { return Ends{u[k], u[k] + du[k], v[k], v[k] + dv[k], acc[k], jerk(k)}; };
    if (free_) {
      for (std::size_t k = 0; k < n; ++k)
        if (!watch_abs(ends(k), b, body_peak_[k])) return by_events();
    } else if (!watch_abs(ends(ix(s_.ref)), b, peak_)) {
      // A new peak inside the interval: the full search on that body's wave alone, from the
      // state at st_.t as build_frame would make it (body_motion).
      Wave& wave = scratch_.peak_wave;
      body_motion(s_, st_, s_.ref, s_.ref, s_.ref, wave);
      max_abs(wave, st_.t, b, tol_.floor, peak_, deadline_);
    }
    for (std::size_t k = 0; k < n; ++k) {
      st_.u[k] += du[k];
      st_.v[k] += dv[k];
    }
    for (int j = 0; j < s_.n_contacts(); ++j) {
      const auto r = ix(s_.right(j));
      st_.g[ix(j)] += s_.left(j) == kWall ? du[r] : du[r] - du[ix(s_.left(j))];
    }
    st_.t = b;
    stale_ = true;
    if (++res_.steps > cap_) {  // an event each, as the event loop counts them
      res_.status = Status::step_cap;
      res_.message = "more than " + std::to_string(cap_) + " events";
      return -1;
    }
    if (deadline_.tick()) throw OutOfTime{};
    return 1;
  }

  // A watched function over the sample interval [st_.t, b]: its values and rates at both
  // ends, and bounds of its second and third derivatives' sizes over it.
  struct Ends {
    double fa, fb, ra, rb, bend, twist;
    Ends flip() const { return {-fa, -fb, -ra, -rb, bend, twist}; }
  };
  // A second derivative within M of zero on [0, h] keeps f within M s (h - s) / 2 <= M h^2 / 8
  // of its chord.
  static double reach(double h) { return 0.125 * h * h; }

  // What max_both does for the largest value of f over [st_.t, b] with `peak` (its `up`),
  // without a search where it can: f stays below the peak (1e-12 below it: the round-off of
  // the recurrence's state against the waves' a search would build), or f is monotone there
  // (its rate, within twist h^2 / 8 of the chord of its end rates, keeps one sign), its
  // largest value at an end. False: a search is needed.
  bool watch_ends(const Ends& f, double b, Peak& peak) const {
    const double h = b - st_.t;
    if (std::max(f.fa, f.fb) + f.bend * reach(h) < peak.value * (1.0 - 1e-12)) return true;
    if (!monotone(f, h)) return false;
    raise(peak, f.fa, st_.t);
    raise(peak, f.fb, b);
    return true;
  }
  // The same for |f| (max_abs).
  bool watch_abs(const Ends& f, double b, Peak& peak) const {
    const double h = b - st_.t;
    if (std::max(std::abs(f.fa), std::abs(f.fb)) + f.bend * reach(h) < peak.value * (1.0 - 1e-12)) return true;
    if (!monotone(f, h)) return false;
    raise(peak, std::abs(f.fa), st_.t);
    raise(peak, std::abs(f.fb), b);
    return true;
  }
  static bool monotone(const Ends& f, double h) {
    const double slack = f.twist * reach(h);
    return std::min(f.ra, f.rb) > slack || std::max(f.ra, f.rb) < -slack;
  }
  static void raise(Peak& peak, double value, double t) {
    if (value > peak.value) peak = {value, t};
  }

  // The event loop takes the interval from st_.t: the frame as a breakpoint leaves it, rebuilt
  // from the state the recurrence left (if it took the last interval).
  int by_events() {
    if (!stale_) return 0;
    stale_ = false;
    build_frame(s_, st_, 0, s_.n_bodies() - 1, fr_);
    std::fill(fresh_.begin(), fresh_.end(), 1);
    if (lazy_) note_all_gaps();
    return 0;
  }

  // Lazy events (DERIVATION.md §9): a body's state at the event is taken from its wave only
  // where the event needs it (sync), a gap's only where it may be closed (gap); the frame is
  // rebuilt for the clusters whose motion the event changed, and every other wave, search
  // and state is kept. epoch_ numbers the events: body_epoch_, gap_epoch_ say which event a
  // body's u, v (and u_event_, v_event_: before the event was handled) or a gap's g are of.
  void begin_event(double t) {
    st_.t = t;
    ++epoch_;
    touched_.clear();
    trig_ = TrigCache{};
  }

  void sync(int i) {
    const auto k = ix(i);
    if (body_epoch_[k] == epoch_) return;
    body_epoch_[k] = epoch_;
    double v[2];
    fr_.body[k].eval(st_.t, v, 2, trig_);
    st_.u[k] = u_event_[k] = v[0];
    st_.v[k] = v_event_[k] = v[1];
    touched_.push_back(i);
  }

  // sync() of bodies lo..hi, a cluster's: their waves are one motion plus each body's offset
  // (Frame::motion), so one evaluation serves them all, bit for bit; a 1000-body touching
  // chain synced some 500 bodies an event, one evaluation each.
  void sync_cluster(int lo, int hi) {
    std::uint64_t shared = 0;
    for (int i = lo; i <= hi; ++i) {
      const auto k = ix(i);
      if (body_epoch_[k] == epoch_) continue;
      const Wave& w = fr_.body[k];
      if (shared == 0 || fr_.motion[k] != shared) {
        w.eval_at(st_.t, at_, trig_);
        shared = fr_.motion[k];
      }
      body_epoch_[k] = epoch_;
      st_.u[k] = u_event_[k] = at_.value(w.f0);
      st_.v[k] = v_event_[k] = at_.rate;
      touched_.push_back(i);
    }
  }

  void sync_bodies(int j) {
    sync(s_.right(j));
    if (s_.left(j) != kWall) sync(s_.left(j));
  }

  // Contact j's gap at st_.t (0 for a persistent contact).
  double gap(int j) {
    const auto k = ix(j);
    if (gap_epoch_[k] == epoch_) return st_.g[k];
    gap_epoch_[k] = epoch_;
    if (st_.active[k]) return st_.g[k] = 0.0;
    double v[2];
    fr_.contact[k].eval(st_.t, v, 2, trig_);
    st_.g[k] = v[0];
    res_.min_gap = std::min(res_.min_gap, v[0] < 0.0 ? v[0] : res_.min_gap);
    clear_until_[k] = clear_time(fr_.contact[k], st_.t, v[0], v[1]);
    return v[0];
  }

  // Whether contact j is closed (persistent, or its gap within tol_gap), looking at its gap
  // only where clear_until_ does not already prove it open.
  bool maybe_closed(int j) {
    const auto k = ix(j);
    if (st_.active[k]) return true;
    if (gap_epoch_[k] != epoch_ && clear_until_[k] > st_.t) return false;
    return gap(j) <= tol_.gap;
  }

  // Until when gap f, of value g and rate d at t, stays above 2 tol_gap for certain: the
  // quadratic lower bound g + d s - bound(f'') s^2 / 2 (t itself where it is not above).
  double clear_time(const Wave& f, double t, double g, double d) const {
    const double room = g - 2.0 * tol_.gap;
    if (!(room > 0.0)) return t;
    const double b2 = f.bound(t, 2);
    if (!(b2 > 0.0)) return d >= 0.0 ? std::numeric_limits<double>::infinity() : t + room / -d;
    const double s = (d + std::sqrt(d * d + 2.0 * b2 * room)) / b2;
    return std::isfinite(s) ? t + s : t;
  }

  // After the whole frame was rebuilt: every gap's clearance from its new wave.
  void note_all_gaps() {
    for (int j = 0; j < s_.n_contacts(); ++j) note_gap(j);
  }
  void note_gap(int j) {
    const auto k = ix(j);
    if (st_.active[k]) return;
    double v[2];
    fr_.contact[k].eval(st_.t, v, 2, trig_);
    clear_until_[k] = clear_time(fr_.contact[k], st_.t, v[0], v[1]);
  }

  // A closure: Poisson's impact on the runs of closed contacts that hold an open one (a run
  // of persistent contacts alone is a cluster whose motion the event did not reach), then
  // the contact LCP on those left at rest relative to each other.
  bool impact_lazily(int which) {
    st_.g[ix(which)] = 0.0;
    gap_epoch_[ix(which)] = epoch_;
    closed_.clear();
    for (int k = 0; k < s_.n_contacts(); ++k)
      if (maybe_closed(k)) closed_.push_back(k);
    set_.clear();
    for_each_run(s_, std::span<const int>(closed_), [&](std::size_t begin, std::size_t end) {
      bool open = false;
      for (std::size_t a = begin; a < end; ++a) open = open || !st_.active[ix(closed_[a])];
      if (open) set_.insert(set_.end(), closed_.begin() + static_cast<std::ptrdiff_t>(begin),
                            closed_.begin() + static_cast<std::ptrdiff_t>(end));
    });
    for (int k : set_) {
      sync_bodies(k);
      if (st_.active[ix(k)]) {  // a persistent contact's gap is 0, as advance() writes it
        st_.g[ix(k)] = 0.0;
        gap_epoch_[ix(k)] = epoch_;
      }
    }
    return impact_set() && resolve_lazily(which);
  }

  // A persistent contact's force reached zero: its cluster's contacts anew.
  bool detach_lazily(int which) {
    int lo = which, hi = which;
    while (lo > 0 && st_.active[ix(lo - 1)]) --lo;
    while (hi + 1 < s_.n_contacts() && st_.active[ix(hi + 1)]) ++hi;
    closed_.clear();
    for (int k = lo; k <= hi; ++k) {
      closed_.push_back(k);
      sync_bodies(k);
    }
    return resolve_lazily(which);
  }

  // resolve() on the contacts closed_ alone, then the frame rebuilt for the clusters the
  // event changed (a body whose state moved in any bit, the bodies of closed_ and of the
  // event's contact, each with its whole cluster), and the energy balance over them.
  bool resolve_lazily(int which) {
    for (int j : closed_) {  // a persistent contact's gap is 0, as advance() writes it
      before_[ix(j)] = st_.active[ix(j)];
      joined_[ix(j)] = 1;
      st_.g[ix(j)] = 0.0;
      gap_epoch_[ix(j)] = epoch_;
    }
    // The bodies of closed_ alone (ascending): the clusters of the other bodies have no
    // contact in joined_, and a pass over every body was O(N) per event.
    if (!closed_.empty())
      close_gaps(s_, joined_, st_.u, first_body(s_, closed_.front()), last_body(s_, closed_.back()));
    for (int j : closed_) {
      joined_[ix(j)] = 0;
      st_.active[ix(j)] = 0;
    }
    bool ok = true;
    for_each_run(s_, std::span<const int>(closed_), [&](std::size_t begin, std::size_t end) {
      if (ok) ok = decide(std::span<const int>(closed_).subspan(begin, end - begin));
    });
    if (!ok) return false;
    const auto same = [](double x, double y) {
      return std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y);
    };
    region_.clear();
    for (std::size_t a = 0; a < touched_.size(); ++a) {  // add_cluster may lengthen touched_
      const auto k = ix(touched_[a]);
      if (!same(st_.u[k], u_event_[k]) || !same(st_.v[k], v_event_[k])) add_cluster(touched_[a]);
    }
    const auto add_contact = [&](int j) {
      add_cluster(s_.right(j));
      if (s_.left(j) != kWall) add_cluster(s_.left(j));
    };
    add_contact(which);
    for (int j : closed_) add_contact(j);
    std::sort(region_.begin(), region_.end());
    for (std::size_t begin = 0; begin < region_.size();) {
      std::size_t end = begin + 1;
      while (end < region_.size() && region_[end] == region_[end - 1] + 1) ++end;
      rebuild(region_[begin], region_[end - 1]);
      begin = end;
    }
    for (int j : closed_)
      if (st_.active[ix(j)] && !before_[ix(j)]) ++res_.contact_phases;
    double after = 0.0, before = 0.0, v[2];
    for (int i : region_) {
      const auto k = ix(i);
      const Body& body = s_.bodies[k];
      fr_.body[k].eval(st_.t, v, 2);
      after += body.m * v[1] * v[1] + body.k * v[0] * v[0];
      before += body.m * v_event_[k] * v_event_[k] + body.k * u_event_[k] * u_event_[k];
      in_region_[k] = 0;
    }
    balance_ += 0.5 * after - 0.5 * before;
    excess_ = std::max(excess_, balance_);
    return true;
  }

  // Adds body i's cluster (its run of persistent contacts) to region_, its bodies synced.
  void add_cluster(int i) {
    if (in_region_[ix(i)]) return;
    const auto [lo, hi] = cluster_of(i);
    for (int b = lo; b <= hi; ++b) {
      in_region_[ix(b)] = 1;
      region_.push_back(b);
    }
    sync_cluster(lo, hi);
  }

  // The bodies of body i's cluster.
  std::pair<int, int> cluster_of(int i) const {
    const int shift = s_.wall ? 1 : 0;  // the contact left of body i is i - 1 + shift
    int lo = i, hi = i;
    while (lo > 0 && st_.active[ix(lo - 1 + shift)]) --lo;
    while (hi + 1 < s_.n_bodies() && st_.active[ix(hi + shift)]) ++hi;
    return {lo, hi};
  }

  // The frame of bodies first..last (whole clusters, their states synced), the contacts
  // among them, and the open contacts at either end, whose other body keeps its wave: for
  // the gap that body's cluster is built afresh at st_.t, aside.
  void rebuild(int first, int last) {
    const int shift = s_.wall ? 1 : 0;
    const int lo = std::max(first - 1 + shift, 0), hi = std::min(last + shift, s_.n_contacts() - 1);
    for (int j = lo; j <= hi; ++j) gap(j);
    build_frame(s_, st_, first, last, fr_);
    if (const int j = first - 1 + shift; j >= 0 && s_.left(j) != kWall)
      build_gap(st_, j, fr_.body[ix(first)], &aside(s_.left(j)), fr_.contact[ix(j)]);
    if (const int j = last + shift; j < s_.n_contacts())
      build_gap(st_, j, aside(s_.right(j)), &fr_.body[ix(last)], fr_.contact[ix(j)]);
    for (int j = lo; j <= hi; ++j) {
      fresh_[ix(j)] = 1;
      note_gap(j);
    }
  }

  const Wave& aside(int i) {
    const auto [lo, hi] = cluster_of(i);
    sync_cluster(lo, hi);
    body_motion(s_, st_, lo, hi, i, side_);
    return side_;
  }

  // The first root of contact j's wave after st_.t, searched no further than b (NaN if there
  // is none by then). A contact whose motion the events since its last search did not
  // change keeps that search's answer: its root, or its having none up to where it looked,
  // from where the search goes on if b is now further (DERIVATION.md §9). Its wave is
  // rebuilt at every event all the same, from a state on the same motion: the same function
  // to round-off, so the answer holds to round-off.
  double next_root(int j, double b) {
    const auto k = ix(j);
    double from = searched_[k];
    if (fresh_[k] || (!std::isnan(root_[k]) && !(root_[k] > st_.t))) {
      fresh_[k] = 0;
      from = st_.t;
    } else if (!std::isnan(root_[k]) || !(from < b)) {
      return root_[k];
    }
    const double noise = st_.active[k] ? tol_.lex * force_scale_[k] : tol_.gap;
    const Wave& f = fr_.contact[k];
    // In a chain, a force that stays within its noise of zero is a neutral one (bodies of
    // one frequency and damping ratio moving as one carry none): first_root would find the
    // first sign change of its rounding (1e-14 m a_p), where the LCP keeps the contact as it
    // was; a Newton's cradle of 1000 bodies had 381 events for 7 impacts, each as dear as the run.
    if (lazy_ && st_.active[k] && std::abs(f.mean()) + f.swing(from) < noise) {
      searched_[k] = b;
      return root_[k] = std::numeric_limits<double>::quiet_NaN();
    }
    root_[k] = first_root(f, from, b, tol_.floor, tol_.settle, noise, deadline_);
    searched_[k] = b;
    return root_[k];
  }

  // After contact `which`'s event: marks for a new search every contact whose bodies' state
  // (position or velocity, to the bit) the event changed, whose persistent-contact flag it
  // changed, or which it found closed (its gap within tol_gap, or the event's own), with
  // every body of a cluster (a run of persistent contacts) that holds a changed one.
  void mark_changed(int which) {
    const auto same = [](double x, double y) {
      return std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y);
    };
    const int nc = s_.n_contacts();
    for (int i = 0; i < s_.n_bodies(); ++i)
      changed_[ix(i)] = !same(st_.u[ix(i)], u_event_[ix(i)]) || !same(st_.v[ix(i)], v_event_[ix(i)]);
    const auto mark = [&](int j) {
      changed_[ix(s_.right(j))] = 1;
      if (s_.left(j) != kWall) changed_[ix(s_.left(j))] = 1;
    };
    mark(which);
    for (int j = 0; j < nc; ++j)
      if (st_.active[ix(j)] != active_event_[ix(j)] || (!active_event_[ix(j)] && st_.g[ix(j)] <= tol_.gap)) mark(j);
    // A cluster moves as one: spread along its persistent contacts, rightwards then leftwards.
    const auto spread = [&](int j) {
      if (!st_.active[ix(j)] || s_.left(j) == kWall) return;
      const auto l = ix(s_.left(j)), r = ix(s_.right(j));
      changed_[l] = changed_[r] = changed_[l] || changed_[r];
    };
    for (int j = 0; j < nc; ++j) spread(j);
    for (int j = nc - 1; j >= 0; --j) spread(j);
    for (int j = 0; j < nc; ++j)
      if ((s_.left(j) != kWall && changed_[ix(s_.left(j))]) || changed_[ix(s_.right(j))]) fresh_[ix(j)] = 1;
  }

  // t = 0: a closed contact that approaches (a Newton's-cradle kick) is an impact first;
  // otherwise the contact LCP decides the closed contacts at rest relative to each other.
  bool start() {
    if (free_) {
      build_frame(s_, st_, 0, s_.n_bodies() - 1, fr_);
      return true;
    }
    const double e_before = energy(st_.u.data(), st_.v.data());
    bool approach = false;
    closed_.clear();
    for (int j = 0; j < s_.n_contacts(); ++j) {
      if (st_.g[ix(j)] > tol_.gap) continue;
      const double rate = gap_rate(s_, j, st_.v);
      approach = approach || rate < -tol_.speed;
      if (rate <= tol_.speed) closed_.push_back(j);
    }
    if (!(approach ? impact() : resolve())) return false;
    account(e_before);
    std::fill(fresh_.begin(), fresh_.end(), 1);
    if (lazy_) note_all_gaps();
    return true;
  }

  Result finish() {
    if (plastic_.on() && res_.status == Status::ok) plastic_.finish(s_, st_, -balance_, res_);
    res_.pi1 = s_.pi1(peak_.value);
    res_.t_max = peak_.t;
    res_.energy_excess = excess_ / s_.energy_scale();
    res_.isolated_impacts = isolated_;
    res_.restitution_low = isolated_ > 0 ? e_low_ : std::numeric_limits<double>::quiet_NaN();
    res_.restitution_high = isolated_ > 0 ? e_high_ : std::numeric_limits<double>::quiet_NaN();
    check_result(s_, tol_scale_, res_);
    // As every solver: a run that did not end ok has no Pi1 (the largest |u0| of a run cut
    // short, or of a run that failed its own checks, is not an answer to report).
    if (res_.status != Status::ok) {
      res_.pi1 = res_.t_max = res_.residual = res_.hysteretic = std::numeric_limits<double>::quiet_NaN();
      res_.energies = {};
    }
    return std::move(res_);
  }

  // System::energy, with the hysteretic variables of the state's branches where bodies yield.
  double energy(const double* u, const double* v) {
    return plastic_.on() ? plastic_.energy(s_, st_, u, v) : s_.energy(u, v);
  }

  // The energy balance E + D - E0 - W moves only at events (DERIVATION.md §5): adds the jump
  // from e_before to the energy of the new frame at st.t.
  void account(double e_before) {
    double v[2];
    for (int i = 0; i < s_.n_bodies(); ++i) {
      fr_.body[ix(i)].eval(st_.t, v, 2);
      eval_u_[ix(i)] = v[0];
      eval_v_[ix(i)] = v[1];
    }
    balance_ += energy(eval_u_.data(), eval_v_.data()) - e_before;
    excess_ = std::max(excess_, balance_);
  }

  // Every wave is evaluated at one t, most of them on the same few frequencies and decay
  // rates (every wave starts at the last event): they share libm's values (TrigCache).
  void advance(double t) {
    double v[2];
    TrigCache trig;
    for (int i = 0; i < s_.n_bodies(); ++i) {
      fr_.body[ix(i)].eval(t, v, 2, trig);
      st_.u[ix(i)] = v[0];
      st_.v[ix(i)] = v[1];
    }
    for (int j = 0; j < s_.n_contacts(); ++j) {
      if (!st_.active[ix(j)]) fr_.contact[ix(j)].eval(t, v, 1, trig);
      st_.g[ix(j)] = st_.active[ix(j)] ? 0.0 : v[0];
      if (!free_) res_.min_gap = std::min(res_.min_gap, st_.g[ix(j)] < 0.0 ? st_.g[ix(j)] : res_.min_gap);
    }
    st_.t = t;
  }

  // A free run's peaks over [st.t, b]: every body's |u|, every gap's farthest either way.
  void watch(double b) {
    for (int i = 0; i < s_.n_bodies(); ++i) max_abs(fr_.body[ix(i)], st_.t, b, tol_.floor, body_peak_[ix(i)], deadline_);
    for (int j = 0; j < s_.n_contacts(); ++j) {
      max_both(fr_.contact[ix(j)], st_.t, b, tol_.floor, opening_[ix(j)], closing_[ix(j)], deadline_);
    }
  }

  // The time of history sample n: equally spaced from 0 to t_end.
  double history_time(int n) const {
    const double dt = samples_ > 1 ? s_.t_end / (samples_ - 1) : 0.0;
    return n == samples_ - 1 ? s_.t_end : dt * n;
  }

  // Samples of the state at equally spaced times in [state.t, t] (the first from t = 0).
  void record(double t) {
    if (samples_ <= 0) return;
    auto& data = res_.history.data;
    while (next_sample_ < samples_) {
      const double ts = history_time(next_sample_);
      if (ts > t) break;
      double v[2];
      TrigCache trig;
      data.push_back(ts);
      const std::size_t at_u = data.size();
      data.resize(data.size() + ix(2 * s_.n_bodies()));
      for (int i = 0; i < s_.n_bodies(); ++i) {
        fr_.body[ix(i)].eval(ts, v, 2, trig);
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

  // Poisson impact on every closed contact (persistent, or a gap within tol_gap), run by
  // run; then the contact LCP on those left at rest relative to each other.
  bool impact() {
    set_.clear();
    for (int k = 0; k < s_.n_contacts(); ++k)
      if (st_.active[ix(k)] || st_.g[ix(k)] <= tol_.gap) set_.push_back(k);
    return impact_set() && resolve();
  }

  // The impacts on the contacts set_, run by run; closed_: those of them left at rest
  // relative to each other (gap 0), the others separate and are no longer persistent.
  bool impact_set() {
    for (int k : set_)
      if (const double rate = gap_rate(s_, k, st_.v); rate < -tol_.speed) {
        ++res_.impacts;
        note_impact(res_, st_.t, rate);
      }
    bool ok = true;
    for_each_run(s_, std::span<const int>(set_), [&](std::size_t begin, std::size_t end) {
      if (ok) ok = impact_run(std::span<const int>(set_).subspan(begin, end - begin));
    });
    if (!ok) return false;
    closed_.clear();
    for (int k : set_) {
      if (gap_rate(s_, k, st_.v) <= tol_.speed) {
        closed_.push_back(k);
        st_.g[ix(k)] = 0.0;
      } else {
        st_.active[ix(k)] = 0;
      }
    }
    return true;
  }

  bool impact_run(std::span<const int> run) {
    double approach = 0.0;
    for (int k : run) approach = std::min(approach, gap_rate(s_, k, st_.v));
    if (!(approach < 0.0)) return true;  // nothing approaches: no impulse
    // An approach slower than the tolerance ends an accumulation of impacts: plastic.
    const double eps = -approach > tol_.speed ? s_.eps : 0.0;
    try {
      poisson_run(s_, run, st_.v, eps, work_, std::span<double>(impulse_).first(run.size()));
    } catch (const std::runtime_error& e) {
      return fail(e.what());
    }
    if (run.size() == 1 && approach < -floor_) {
      const double e = -gap_rate(s_, run[0], st_.v) / approach;
      ++isolated_;
      e_low_ = isolated_ == 1 ? e : std::min(e_low_, e);
      e_high_ = isolated_ == 1 ? e : std::max(e_high_, e);
    }
    return true;
  }

  // Whether an open contact is closed (within tol_gap) and approaching.
  bool closing() const {
    for (int k = 0; k < s_.n_contacts(); ++k)
      if (!st_.active[ix(k)] && st_.g[ix(k)] <= tol_.gap && gap_rate(s_, k, st_.v) < -tol_.speed) return true;
    return false;
  }

  // A persistent contact's force reached zero, or the load jumped: re-decide all of them.
  bool detach() {
    closed_.clear();
    for (int k = 0; k < s_.n_contacts(); ++k)
      if (st_.active[ix(k)]) closed_.push_back(k);
    return resolve();
  }

  // The acceleration-level LCP (paper eq. 1) on the closed contacts closed_ (ascending, zero
  // relative velocity). Runs of consecutive contacts share no body with each other, so
  // each run is decided alone, on a frame of its own bodies; then the whole frame is built.
  bool resolve() {
    // Velocities may have jumped (an impact): bodies at their yield limit take the branch
    // their motion says.
    if (plastic_.on()) plastic_.settle(s_, st_, tol_.gap, tol_.speed);
    before_ = st_.active;
    for (int j : closed_) joined_[ix(j)] = 1;
    close_gaps(s_, joined_, st_.u, 0, s_.n_bodies() - 1);
    for (int j : closed_) joined_[ix(j)] = 0;  // all zero between events: the lazy ones clear only their own
    std::fill(st_.active.begin(), st_.active.end(), 0);
    bool ok = true;
    for_each_run(s_, std::span<const int>(closed_), [&](std::size_t begin, std::size_t end) {
      if (ok) ok = decide(std::span<const int>(closed_).subspan(begin, end - begin));
    });
    if (!ok) return false;
    build_frame(s_, st_, 0, s_.n_bodies() - 1, fr_);
    for (std::size_t j = 0; j < before_.size(); ++j)
      if (st_.active[j] && !before_[j]) ++res_.contact_phases;
    return true;
  }

  // A set fits when every active force and every inactive gap acceleration is
  // lexicographically non-negative in its Taylor coefficients at t, which decides
  // degenerate starts (zero force, zero relative acceleration) by the first derivative of
  // the load that does not vanish. Coefficients within round-off of zero defer to the next
  // derivative; if round-off in the higher derivatives leaves no set that fits, the plain
  // signs decide, and failing that the values alone (the LCP at t, which always has a
  // solution for this P-matrix).
  bool decide(std::span<const int> run) {
    const int n = static_cast<int>(run.size());
    const int from = first_body(s_, run.front()), to = last_body(s_, run.back());
    for (const Pass pass : {Pass{tol_.lex, kMaxDerivative - 1}, Pass{0.0, kMaxDerivative - 1}, Pass{tol_.lex, 1}}) {
      if (n <= kEnumerateLimit) {
        for (int mask = (1 << n) - 1; mask >= 0; --mask) {
          for (int a = 0; a < n; ++a) st_.active[ix(run[ix(a)])] = (mask & (1 << a)) ? 1 : 0;
          if (try_set(run, from, to, pass)) return true;
        }
      } else if (propose(run, from, to, pass)) {
        return true;
      }
    }
    std::ostringstream msg;
    msg << "no contact configuration fits the acceleration LCP at t = " << st_.t << " (contacts " << run.front()
        << ".." << run.back() << ")";
    return fail(msg.str());
  }

  // A long run. Candidates, each confirmed by the exact test:
  //  1. every contact active (a chain locked together; the enumeration's first set too);
  //  2. Chandrasekaran's growth: from no active contact, make active every inactive one
  //     whose gap would go negative, until none does. For an M-matrix (G = W^T M^-1 W of a
  //     row is one) this reaches the solution of the LCP, and never has to drop a contact;
  //     each step costs one frame of the run, O(n);
  //  3. Lemke's method on the Delassus matrix G with the Taylor coefficients of the free
  //     gap motion (rate, acceleration, ...) as lexicographic right-hand side, O(n^2) per
  //     pivot; then that proposal with one contact flipped.
  // The variant "lemke" proposes by Lemke's method first (then all active, then flips).
  bool propose(std::span<const int> run, int from, int to, const Pass& pass) {
    auto try_all_active = [&] {
      for (int j : run) st_.active[ix(j)] = 1;
      return try_set(run, from, to, pass);
    };
    auto try_proposal = [&] {
      for (std::size_t a = 0; a < run.size(); ++a) st_.active[ix(run[a])] = proposal_[a];
      return try_set(run, from, to, pass);
    };
    if (!lemke_first_ && try_all_active()) return true;
    if (!lemke_first_ && grow(run, from, to, pass)) return promote_neutral(run, from, to, pass);
    lemke_proposal(run, from, to, pass);
    if (try_proposal()) return promote_neutral(run, from, to, pass);
    if (lemke_first_ && try_all_active()) return true;
    for (std::size_t a = 0; a < run.size(); ++a) {
      proposal_[a] = !proposal_[a];
      if (try_proposal()) return promote_neutral(run, from, to, pass);
      proposal_[a] = !proposal_[a];
    }
    return false;
  }

  // After a set that fits: a closed contact left inactive whose gap motion vanishes in every
  // coefficient the test reads (bodies side by side moving alike) fits either way. Taken
  // inactive, it would be caught only once its gap reached -tol_gap, arriving at about
  // sqrt(2 a tol_gap) (1e-5 a_p / w_p), above tol_speed: with eps = 1 it would bounce
  // for ever instead of settling, and the run would depend on that. So such contacts are
  // made active, as the enumeration's order (all active first) does, if the set still
  // fits; otherwise the set is kept as it was. Always true (the set fitted).
  bool promote_neutral(std::span<const int> run, int from, int to, const Pass& pass) {
    bool any = false;
    for (std::size_t a = 0; a < run.size(); ++a) {
      proposal_[a] = st_.active[ix(run[a])];
      if (!st_.active[ix(run[a])] && neutral(run[a], pass)) {
        st_.active[ix(run[a])] = 1;
        any = true;
      }
    }
    if (any && !try_set(run, from, to, pass))
      for (std::size_t a = 0; a < run.size(); ++a) st_.active[ix(run[a])] = proposal_[a];
    return true;
  }

  // Whether the gap of inactive contact j (in the frame built last) has rate and
  // derivatives that the test takes as zero, to the pass's depth.
  bool neutral(int j, const Pass& pass) const {
    double c[kMaxDerivative + 1];
    fr_.contact[ix(j)].eval(st_.t, c, kMaxDerivative + 1);
    double z = pass.tol * s_.a_p / rate_;
    for (int k = 0; k <= pass.depth; ++k, z *= rate_)
      if (std::abs(c[1 + k]) > z) return false;
    return true;
  }

  bool grow(std::span<const int> run, int from, int to, const Pass& pass) {
    for (int j : run) st_.active[ix(j)] = 0;
    for (std::size_t step = 0; step <= run.size(); ++step) {
      build_frame(s_, st_, from, to, fr_);
      bool added = false;
      for (std::size_t a = 0; a < run.size(); ++a) {
        const int j = run[a];
        proposal_[a] = 0;
        if (fits_one(j, pass.tol, pass.depth)) continue;
        if (st_.active[ix(j)]) return false;  // a force went negative: not this way
        proposal_[a] = 1;
        added = true;
      }
      if (!added) return true;
      for (std::size_t a = 0; a < run.size(); ++a)
        if (proposal_[a]) st_.active[ix(run[a])] = 1;
    }
    return false;
  }

  // Writes Lemke's active set for the run into proposal_ (none if Lemke fails).
  void lemke_proposal(std::span<const int> run, int from, int to, const Pass& pass) {
    const auto n = static_cast<Eigen::Index>(run.size());
    const int cols = pass.depth + 1;
    for (int j : run) st_.active[ix(j)] = 0;
    build_frame(s_, st_, from, to, fr_);
    lex_q_.resize(n, cols);
    lex_z_.resize(n, cols);
    delassus_.setZero(n, n);
    double c[kMaxDerivative + 1];
    for (Eigen::Index a = 0; a < n; ++a) {
      const int j = run[static_cast<std::size_t>(a)];
      fr_.contact[ix(j)].eval(st_.t, c, kMaxDerivative + 1);
      // The coefficients fits() takes as zero are zero here too, so both see one problem.
      double z = pass.tol * s_.a_p / rate_;
      for (int k = 0; k < cols; ++k, z *= rate_) lex_q_(a, k) = std::abs(c[1 + k]) > z ? c[1 + k] : 0.0;
      const int l = s_.left(j), r = s_.right(j);
      delassus_(a, a) = 1.0 / s_.bodies[ix(r)].m + (l == kWall ? 0.0 : 1.0 / s_.bodies[ix(l)].m);
      if (a > 0) delassus_(a - 1, a) = delassus_(a, a - 1) = -1.0 / s_.bodies[ix(l)].m;
    }
    std::fill(proposal_.begin(), proposal_.begin() + n, 0);
    if (lcp::lemke_lex(delassus_, lex_q_, lex_z_, lemke_).status != lcp::Status::solved) return;
    for (Eigen::Index r = 0; r < n; ++r)
      if (lemke_.basic(r) >= n) proposal_[static_cast<std::size_t>(lemke_.basic(r) - n)] = 1;
  }

  // Builds the run's frame for the active flags set in st_ and tests them.
  bool try_set(std::span<const int> run, int from, int to, const Pass& pass) {
    build_frame(s_, st_, from, to, fr_);
    return fits(run, pass.tol, pass.depth);
  }

  bool fits(std::span<const int> run, double tol, int depth) const {
    for (int j : run)
      if (!fits_one(j, tol, depth)) return false;
    return true;
  }

  bool fits_one(int j, double tol, int depth) const {
    double c[kMaxDerivative + 1];
    fr_.contact[ix(j)].eval(st_.t, c, kMaxDerivative + 1);
    return st_.active[ix(j)] ? lex_nonnegative(c, std::min(depth, 4), force_scale_[ix(j)], rate_, tol)
                             : lex_nonnegative(c + 1, depth + 1, s_.a_p / rate_, rate_, tol);
  }

  bool fail(std::string why) {
    res_.status = Status::failed;
    res_.message = std::move(why);
    return false;
  }

  ScratchLease lease_;  // first: the references below are into it
  Scratch& scratch_ = *lease_;
  const System& s_;
  Tolerances tol_;
  long cap_;
  Deadline deadline_;
  double floor_;  // kRestitutionFloor a_p / w_p
  bool lemke_first_;
  double tol_scale_;
  State& st_ = scratch_.st;
  Frame& fr_ = scratch_.fr;
  Peak peak_;
  Result res_;
  bool free_ = false;
  std::vector<Peak> body_peak_, closing_, opening_;  // a free run's (watch)
  double rate_ = 1.0;
  // The recurrence (recur): on; the record's sample at or before st_.t; whether the frame
  // is older than the state (the recurrence took the last interval).
  bool recurrence_ = false;
  std::size_t sample_ = 0;
  bool stale_ = false;
  std::vector<double>& force_scale_ = scratch_.force_scale;  // per contact
  int samples_ = 0, next_sample_ = 0;
  // Energy balance and restitution (Result).
  double balance_ = 0.0, excess_ = 0.0;
  long isolated_ = 0;
  double e_low_ = 0.0, e_high_ = 0.0;
  // Scratch kept across events so that handling one allocates nothing.
  std::vector<int>&closed_ = scratch_.closed, &set_ = scratch_.set;
  std::vector<double>&impulse_ = scratch_.impulse, &eval_u_ = scratch_.eval_u, &eval_v_ = scratch_.eval_v;
  std::vector<char>&joined_ = scratch_.joined, &before_ = scratch_.before, &proposal_ = scratch_.proposal;
  // Per contact, what its last search found (next_root): a root, or none up to searched_;
  // fresh_: its motion changed since, search again from the last event. Not with two
  // contacts or fewer: they share a body, which an event at either moves.
  bool incremental_ = false;
  std::vector<char>& fresh_ = scratch_.fresh;
  std::vector<double>&root_ = scratch_.root, &searched_ = scratch_.searched;
  // The state where the last event was found, before it was handled (mark_changed).
  std::vector<double>&u_event_ = scratch_.u_event, &v_event_ = scratch_.v_event;
  std::vector<char>&active_event_ = scratch_.active_event, &changed_ = scratch_.changed;
  // Chains without yielding bodies: a contact's event rebuilds only the clusters it
  // changes (DERIVATION.md §9); the events above.
  bool lazy_ = false;
  long epoch_ = 0;
  TrigCache trig_;
  WaveAt at_;  // sync_cluster's shared evaluation
  Wave& side_ = scratch_.side;
  std::vector<long>&body_epoch_ = scratch_.body_epoch, &gap_epoch_ = scratch_.gap_epoch;
  std::vector<double>& clear_until_ = scratch_.clear_until;
  std::vector<int>&touched_ = scratch_.touched, &region_ = scratch_.region;
  std::vector<char>& in_region_ = scratch_.in_region;
  ImpactWork& work_ = scratch_.work;
  Plasticity& plastic_ = scratch_.plastic;
  lcp::LemkeWorkspace& lemke_ = scratch_.lemke;
  Eigen::MatrixXd &delassus_ = scratch_.delassus, &lex_q_ = scratch_.lex_q, &lex_z_ = scratch_.lex_z;
};

}  // namespace

namespace {

Result solve_rigid(const System& system, const Settings& settings, bool keep_searches, bool lazy,
                   bool recurrence = true) {
  // A variant it does not have fails the run, as every solver's does (the contract).
  if (!known_variant(settings.variant)) return failed("variant: unknown '" + clip(settings.variant) + "'");
  if (kelvin_voigt(settings)) {
    if (!system.yields()) return solve_kelvin_voigt(system, settings);
    return yielding_refused("the Kelvin-Voigt reference's motion is one linear system; "
                            "yielding is solved with rigid contact");
  }
  try {
    return Solver(system, settings, keep_searches, lazy, false, recurrence).run();
  } catch (const std::exception& e) {
    return failed(e.what());
  }
}

}  // namespace

Result solve(const System& system, const Settings& settings) { return solve_rigid(system, settings, true, true); }

Result detail::solve_searching_every_contact(const System& system, const Settings& settings) {
  return solve_rigid(system, settings, false, false);
}

Result detail::solve_rebuilding_every_body(const System& system, const Settings& settings) {
  return solve_rigid(system, settings, true, false);
}

Result detail::solve_searching_every_sample(const System& system, const Settings& settings) {
  return solve_rigid(system, settings, true, true, false);
}

void check_result(const System& s, double tol_scale, Result& r) {
  if (r.status != Status::ok) return;
  std::ostringstream msg;
  const double gap = tolerances(s, tol_scale).gap, energy = kEnergyCheck * std::max(1.0, tol_scale);
  if (!std::isfinite(r.pi1)) {
    r.status = Status::nan;
    msg << "Pi1 is not finite";
  } else if (r.min_gap < -kPenetrationCheck * gap) {
    r.status = Status::penetration;
    msg << "a gap reached " << r.min_gap / s.length_scale() << " a_p/w_p^2, beyond " << kPenetrationCheck
        << " closure tolerances";
  } else if (r.energy_excess > energy) {
    r.status = Status::energy;
    msg << "the run made " << r.energy_excess << " of the energy scale, beyond " << energy;
  } else {
    return;
  }
  r.message = msg.str();
}

std::string describe(const Settings& settings) {
  NamedValues out;
  out.add("tol_scale", settings.tol_scale);
  // Rigid contact, the default, by either name keeps the rows' settings as they were.
  if (!settings.contact.empty() && settings.contact != "rigid") out.add("contact", settings.contact);
  if (kelvin_voigt(settings))
    add_stiffness(out, settings, settings.stiffness > 0.0 ? settings.stiffness : compliant::kDefaultStiffness);
  return out.json();
}

std::vector<VariantInfo> variant_list() {
  return {{"", "a long run of closed contacts: all active, else grown contact by contact, else Lemke's proposal"},
          {kLemkeVariant, "a long run of closed contacts: Lemke's proposal first (slower; checks the default)"}};
}

std::string check(const Settings& settings) {
  if (!(settings.tol_scale >= kMinTolScale && settings.tol_scale <= kMaxTolScale)) {
    std::ostringstream msg;
    msg << "tol-scale: must be in [" << kMinTolScale << ", " << kMaxTolScale
        << "]: below, its tolerances fall under double precision's round-off; above, the plastic-approach "
           "speed passes the restitution floor";
    return msg.str();
  }
  if (settings.steps != 0) return "steps: the event-driven solver takes no step";
  if (settings.wh != 0.0) return "wh: the event-driven solver takes no step";
  if (!known_variant(settings.variant))
    return "variant: the event-driven solver has the default (empty) and \"lemke\"";
  if (!settings.contact.empty() && settings.contact != "rigid" && !kelvin_voigt(settings))
    return "contact: unknown '" + clip(settings.contact) + "' (known: rigid, kelvin-voigt)";
  if (!(settings.stiffness >= 0.0) || !std::isfinite(settings.stiffness))
    return "stiffness: must be finite and > 0 (0: the default)";
  if (!kelvin_voigt(settings) && settings.stiffness != 0.0)
    return "stiffness: only with --contact kelvin-voigt (rigid contact has none)";
  if (kelvin_voigt(settings) && !settings.variant.empty())
    return "variant: the Kelvin-Voigt reference has none (its contacts need no LCP)";
  return {};
}

namespace {

FreeMotion free_motion(const System& system, const Settings& limits, bool recurrence) {
  System apart = system;
  apart.delta = 0.0;  // each gap is then u_right - u_left, what the separation measures
  Settings settings;
  settings.time_limit = limits.time_limit;
  settings.stop = limits.stop;
  try {
    return Solver(apart, settings, false, false, true, recurrence).free_run();
  } catch (const std::exception& e) {
    FreeMotion out;
    out.status = Status::failed;
    out.message = e.what();
    return out;
  }
}

}  // namespace

FreeMotion free_motion(const System& system, const Settings& limits) { return free_motion(system, limits, true); }

FreeMotion detail::free_motion_searching_every_sample(const System& system, const Settings& limits) {
  return free_motion(system, limits, false);
}

double no_contact_pi1(const System& system, const Settings& limits) {
  System alone = system;
  alone.bodies = {system.bodies[ix(system.ref)]};
  alone.wall = false;
  alone.ref = 0;
  alone.u_start = {system.u_start.empty() ? 0.0 : system.u_start[ix(system.ref)]};
  alone.v_start = {system.v_start.empty() ? 0.0 : system.v_start[ix(system.ref)]};
  Settings settings;
  settings.time_limit = limits.time_limit;
  settings.stop = limits.stop;
  return solve(alone, settings).pi1;
}

}  // namespace pb::event_driven
