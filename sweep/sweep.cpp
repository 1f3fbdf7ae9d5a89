#include "sweep/sweep.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <limits>
#include <optional>
#include <stdexcept>
#include <thread>

#include "cases/physical.hpp"
#include "kit/separation.hpp"
#include "cases/system.hpp"
#include "cases/text.hpp"
#include "programs/process.hpp"
#include "kit/verdict.hpp"
#include "sweep/stopwatch.hpp"
#include "sweep/worker_cores.hpp"
#include "solvers/registry.hpp"

namespace pb {

namespace {

std::string describe_exception(std::exception_ptr error) {
  try {
    std::rethrow_exception(error);
  } catch (const std::exception& e) {
    return e.what();
  } catch (...) {
    return "unknown exception";
  }
}

// One timed solve: the result, or the exception's message as a failed one.
struct Timed {
  Result result;
  double seconds = 0.0;
  double cpu_seconds = 0.0;
};

Timed timed_solve(const SolverInfo& solver, const System& system, const Settings& settings) {
  Timed t;
  const Stopwatch watch;
  try {
    t.result = solver.solve(system, settings);
  } catch (...) {
    t.result = Result{};
    t.result.status = Status::failed;
    t.result.message = describe_exception(std::current_exception());
  }
  const Elapsed spent = watch.elapsed();
  // A persistent program's start is the row's startup_seconds, not the solve's time.
  t.seconds = spent.wall - (std::isfinite(t.result.startup_seconds) ? t.result.startup_seconds : 0.0);
  t.cpu_seconds = spent.cpu + t.result.child_cpu_seconds;
  return t;
}

std::string status_and_pi1(const Result& r) {
  return std::string(name(r.status)) + " with Pi1 " + (std::isnan(r.pi1) ? "nan" : format_number(r.pi1));
}

// The same status and Pi1, bit for bit.
bool same(const Result& a, const Result& b) {
  return a.status == b.status && std::bit_cast<std::uint64_t>(a.pi1) == std::bit_cast<std::uint64_t>(b.pi1);
}

// The row's result replaced by a failure saying why (none of its values can be trusted).
void fail(Row& row, const std::string& why) {
  row.result = Result{};
  row.result.status = Status::failed;
  row.result.message = why;
}

double median(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  const std::size_t n = x.size();
  return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}

// A point's time limit (Settings::time_limit) is the whole point's: its timed solves, its
// monitored pass and its no-contact Pi1 share it, each given what the others left. Applied to
// each solve alone, an external program that slept 2.8 s under a 3 s limit made `run` take
// 5.8 s, `ok`.
class PointDeadline {
 public:
  explicit PointDeadline(double limit) : limit_(limit) {}
  // The time left set as the settings' limit: false, and the settings as they were, when none
  // is left. (In place: a copy of the settings and its move per solve were 1,000 instructions
  // a point.)
  bool limit(Settings& settings) const {
    if (limit_ <= 0.0) return true;
    const double rest = limit_ - std::chrono::duration<double>(Clock::now() - start_).count();
    if (!(rest > 0.0)) return false;
    settings.time_limit = rest;
    settings.point_time_limit = limit_;
    return true;
  }
  // The settings with the time left as their limit; nullopt when none is left.
  std::optional<Settings> left(Settings settings) const {
    if (!limit(settings)) return std::nullopt;
    return settings;
  }

 private:
  using Clock = std::chrono::steady_clock;
  double limit_;
  Clock::time_point start_ = Clock::now();
};

// The timed solves of run_point (sweep.hpp says how): row.result is the first's, the
// timing columns the repetitions'.
void time_solves(Row& row, const SolverInfo& solver, const System& system, Settings settings, int repetitions,
                 const PointDeadline& deadline, bool monitor_timed) {
  // One pass (the external programs): the timed solve is the monitored one when asked.
  settings.monitor = settings.monitor && (monitor_timed || solver.one_pass);
  std::vector<double> wall, cpu;
  double spent = 0.0;
  for (int j = 0; j < repetitions && (j == 0 || spent < kRepetitionBudget); ++j) {
    // Where none is left the first solve still runs, on the limit as given.
    if (!deadline.limit(settings) && j > 0) break;  // the limit is spent: the repetitions end here
    Timed t = timed_solve(solver, system, settings);
    if (j == 0) {
      row.result = std::move(t.result);
    } else if (t.result.status == Status::time_limit && row.result.status != Status::time_limit) {
      break;  // cut short: not a timing of the same run
    } else if (!same(row.result, t.result)) {
      fail(row, "repetition " + std::to_string(j + 1) + " gave " + status_and_pi1(t.result) + " and the first " +
                    status_and_pi1(row.result) + ": the solver is not deterministic");
      break;
    }
    wall.push_back(t.seconds);
    cpu.push_back(t.cpu_seconds);
    spent += t.cpu_seconds;
  }
  row.seconds = median(wall);
  row.cpu_seconds = median(cpu);
  row.cpu_seconds_low = *std::min_element(cpu.begin(), cpu.end());
  row.cpu_seconds_high = *std::max_element(cpu.begin(), cpu.end());
  row.repetitions = static_cast<int>(cpu.size());
}

// The monitored pass of run_point: the monitor's measurements copied into the row.
void add_monitor(Row& row, const SolverInfo& solver, const System& system, Settings settings,
                 const PointDeadline& deadline) {
  settings.monitor = true;
  const std::optional<Settings> now = deadline.left(settings);
  Result monitored;
  if (now)
    monitored = timed_solve(solver, system, *now).result;
  else
    monitored.status = Status::time_limit;
  if (monitored.status == Status::time_limit && row.result.status != Status::time_limit) {
    // Cut short (the machine busier than when it was timed): the answer stands, unmeasured.
    row.result.message += std::string(row.result.message.empty() ? "" : "; ") +
                          "the monitored solve passed the time limit: no energy, gap or restitution measurement";
    return;
  }
  if (!same(row.result, monitored)) {
    fail(row, "the monitored run gave " + status_and_pi1(monitored) + " and the timed runs " +
                  status_and_pi1(row.result) + ": the monitor must not change the result");
    return;
  }
  Result& r = row.result;
  r.energy_excess = monitored.energy_excess;
  r.isolated_impacts = monitored.isolated_impacts;
  r.restitution_low = monitored.restitution_low;
  r.restitution_high = monitored.restitution_high;
  r.gap_rate_max = monitored.gap_rate_max;
}

// x(h) against x(2h) at order p, relative to x(h) (ErrorEstimate); 0 where both are 0.
double richardson(double at_h, double at_2h, double order) {
  const double difference = std::abs(at_h - at_2h);
  if (difference == 0.0) return 0.0;
  return difference / (std::exp2(order) - 1.0) / std::abs(at_h);
}

// The settings of ErrorEstimate's companion solve at twice the run's step; nullopt where there
// is none: a run without a fixed step, a solver of no known order, or a variant whose check
// refuses a step of ours (it chooses its own: Simbody's Runge-Kutta-Merson reports a step but
// takes none of --steps or --wh), which is then judged as the solvers without a fixed step.
std::optional<Settings> companion_settings(const SolverInfo& solver, const System& system, const Result& r,
                                           const Settings& run) {
  if (!(solver.step_order > 0.0) || !std::isfinite(r.step) || r.status != Status::ok) return std::nullopt;
  Settings settings = run;
  settings.steps = 0;
  settings.steps_per_sample = 0;
  settings.h_s = 0.0;
  settings.wh = step_pi_term(system, 2.0 * r.step);
  settings.monitor = false;
  settings.history_samples = 0;
  if (!solver.check(settings).empty()) return std::nullopt;
  return settings;
}

// The companion solve of ErrorEstimate (its settings: companion_settings), and the estimates from it.
void add_estimate(Row& row, const SolverInfo& solver, const System& system, const Settings& settings,
                  const PointDeadline& deadline) {
  Result& r = row.result;
  const std::optional<Settings> now = deadline.left(settings);
  const Result companion = now ? timed_solve(solver, system, *now).result : Result{};
  if (!now || companion.status == Status::time_limit) {
    r.message += std::string(r.message.empty() ? "" : "; ") +
                 "the companion solve at 2h passed the time limit: no error estimate";
    return;
  }
  if (companion.status != Status::ok) {
    r.doubt += std::string(r.doubt.empty() ? "" : "; ") + "its companion solve at twice the step ended " +
               std::string(name(companion.status)) + " (so nothing to estimate its error by)";
    return;
  }
  r.error_estimate = richardson(r.pi1, companion.pi1, solver.step_order);
  // No impact is an approach of 0: an impact at one step and none at the other is as far apart
  // as the impact (100 % at p = 1, or infinite where the run itself had none); none at either, no estimate.
  const auto approach = [](double v) { return std::isnan(v) ? 0.0 : v; };
  if (!std::isnan(r.impact_velocity_max) || !std::isnan(companion.impact_velocity_max))
    r.error_estimate_velocity =
        richardson(approach(r.impact_velocity_max), approach(companion.impact_velocity_max), solver.step_order);
}

// Whether the run took every measurement the verdict could ask of it (run_point says which);
// estimable: it has a companion (companion_settings).
bool measured_all(const Result& r, const SolverInfo& solver, const Settings& settings, bool estimable) {
  if (!settings.monitor && !solver.reference) return false;
  return !estimable || !std::isnan(r.error_estimate);
}

// The no-contact motion's separations and peaks (kit/separation.hpp), over a_p / w_p^2: one
// free solve; a yielding system's motion under the reversed load is not the mirror of it, and
// is solved again. Not for a chain (a kicked row of many bodies, not a pair of neighbours).
void add_separation(Row& row, const Case& c, const System& system, const Settings& limits, NoContactCache* cache) {
  if (c.scene == Scene::chain) return;
  const FreeMotion given = cache ? cache->free(system, limits) : free_motion(system, limits);
  if (given.status != Status::ok) throw std::runtime_error(given.message);
  std::optional<FreeMotion> reversed;
  if (system.yields()) {
    Case flipped = c;
    flipped.directivity = c.directivity == Directivity::normal ? Directivity::reverse : Directivity::normal;
    const System other = make_system(flipped);
    reversed = cache ? cache->free(other, limits) : free_motion(other, limits);
    if (reversed->status != Status::ok) throw std::runtime_error(reversed->message);
  }
  const Separation sep = separation(system, given, reversed ? &*reversed : nullptr);
  const double unit = system.length_scale();
  row.separation = sep.required / unit;
  row.separation_reversed = sep.reversed / unit;
  row.separation_abs = sep.rules.abs / unit;
  row.separation_srss = sep.rules.srss / unit;
  row.separation_ddc = sep.rules.ddc / unit;
  row.peaks_no_contact.clear();
  // Body 0 first, then the others left to right (its neighbours 1 and 2 of pair and row3).
  row.peaks_no_contact.push_back(given.peak[ix(system.ref)] / unit);
  for (int i = 0; i < system.n_bodies(); ++i)
    if (i != system.ref) row.peaks_no_contact.push_back(given.peak[ix(i)] / unit);
}

// The settings a case runs with: a stiffness given in N/m (Settings::k_contact) is the case's own
// Pi term (its unit of mass is the case's m0, a Hertz element's length its a_p / w_p^2), so that
// one stiffness holds across the cases of a study. Empty with the reason where it cannot be.
std::optional<Settings> case_settings(const Case& c, const SolverInfo& solver, const Settings& settings,
                                      std::string& why) {
  if (!(settings.k_contact > 0.0)) return settings;
  if (!physical(c)) {
    why = "k_contact: a stiffness in N/m needs a case in physical units (its unit of mass is m0's)";
    return std::nullopt;
  }
  Settings mapped = settings;
  mapped.stiffness = stiffness_pi_term(c, settings.k_contact, solver.hertz_contact && solver.hertz_contact(settings));
  return mapped;
}

}  // namespace

void add_body_peaks(Row& row, const SolverInfo& solver, const Settings& given) {
  const Case& c = row.input;
  if (row.result.status != Status::ok || c.scene == Scene::chain || c.scene == Scene::wall) return;
  // A program run once a point (the external solver) is not run again; nor is a solve under a
  // time limit, which is the whole run's (run_point's) and would be passed.
  if (solver.one_pass || given.time_limit > 0.0) return;
  std::string why;
  std::optional<Settings> settings = case_settings(c, solver, given, why);
  if (!settings) return;
  settings->monitor = false;
  settings->history_samples = 0;
  System system = make_system(c);
  const int ref = system.ref;
  row.peaks = {row.result.pi1};
  for (int i = 0; i < system.n_bodies(); ++i) {
    if (i == ref) continue;
    system.ref = i;
    const Result r = solver.solve(system, *settings);
    row.peaks.push_back(r.status == Status::ok ? r.pi1 : std::numeric_limits<double>::quiet_NaN());
  }
}

Row run_point(const Case& c, std::size_t point, const SolverInfo& solver, const Settings& given,
              int repetitions, NoContactCache* no_contact, bool monitor_timed, const ErrorEstimate& estimate,
              const std::string* described) {
  Row row;
  row.input = c;
  row.point = point;
  row.solver = std::string(solver.name);
  row.variant = given.variant;
  row.result.status = Status::failed;
  if (repetitions < 1 || repetitions > kMaxRepetitions) {
    row.result.message = "repetitions: must be from 1 to " + std::to_string(kMaxRepetitions) + " (it is " +
                         std::to_string(repetitions) + ")";
    return row;
  }
  std::string why;
  const std::optional<Settings> own = case_settings(c, solver, given, why);
  if (!own) {
    row.result.message = why;
    return row;
  }
  const Settings& settings = *own;
  try {
    row.settings = described ? *described : solver.describe(given);
  } catch (...) {
    row.result.message = "describe: " + describe_exception(std::current_exception());
    return row;
  }
  if (auto bad = validate(c)) {
    row.result.message = *bad;
    return row;
  }

  System system;
  try {
    system = make_system(c);
  } catch (...) {
    row.result.message = "make_system: " + describe_exception(std::current_exception());
    return row;
  }
  row.length_scale = system.length_scale();

  const PointDeadline deadline(settings.time_limit);
  time_solves(row, solver, system, settings, repetitions, deadline, monitor_timed);
  if (settings.monitor && !monitor_timed && !solver.one_pass && !solver.reference &&
      row.result.status != Status::time_limit)
    add_monitor(row, solver, system, settings, deadline);

  // The companion's settings (and the solver's check of them) only where the estimate is made or
  // the verdict may be judged (measured_all): a sweep that asks neither does without.
  std::optional<Settings> companion;
  if (estimate.on || settings.monitor || solver.reference)
    companion = companion_settings(solver, system, row.result, settings);
  if (estimate.on && companion) add_estimate(row, solver, system, *companion, deadline);
  judge(system, row.result, {estimate.target_error, measured_all(row.result, solver, settings, companion.has_value())});
  row.wh = step_pi_term(system, row.result.step);
  row.penetration_steps = penetration_steps(row.result);

  try {
    Settings limits = settings;
    if (!deadline.limit(limits)) throw std::runtime_error("not computed: the run's time limit was spent");
    row.pi1_no_contact = no_contact ? no_contact->pi1(system, limits) : no_contact_pi1(system, limits);
    add_separation(row, c, system, limits, no_contact);
  } catch (...) {
    // The solver's own result stands; only the comparison value is missing.
    if (!row.result.message.empty()) row.result.message += "; ";
    row.result.message += "no-contact pi1: " + describe_exception(std::current_exception());
  }
  // A result the row check refuses (an ok with no Pi1) would be written and then refused
  // on resume; it is a solver's failure, so the row says so.
  if (std::string bad = row_problem(row); !bad.empty()) {
    const std::string message = row.result.message;
    fail(row, "the solver returned an inconsistent result: " + bad + (message.empty() ? "" : "; " + message));
  }
  return row;
}

bool task_order(const Row& a, const Row& b) { return a.run != b.run ? a.run < b.run : a.point < b.point; }

TaskSource tasks_from(std::span<const std::size_t> tasks) {
  auto next = std::make_shared<std::atomic<std::size_t>>(0);
  return [tasks, next]() -> std::optional<std::size_t> {
    const std::size_t i = next->fetch_add(1);
    if (i >= tasks.size()) return std::nullopt;
    return tasks[i];
  };
}

std::vector<Row> run_sweep(const CaseList& cases, std::span<const SweepRun> runs,
                           const SweepOptions& options) {
  const std::size_t n = cases.size();
  const std::size_t total = n * runs.size();
  std::atomic<std::size_t> next{0};
  const TaskSource next_task = options.next_task ? options.next_task : [&]() -> std::optional<std::size_t> {
    const std::size_t t = next.fetch_add(1);
    if (t >= total) return std::nullopt;
    return t;
  };
  std::atomic<bool> stop{false};  // a callback threw
  NoContactCache no_contact;      // one per sweep: every run's points share it

  std::mutex mutex;  // guards everything below and serialises the callbacks
  std::vector<Row> rows;
  if (options.keep_rows) rows.reserve(total);
  std::size_t done = 0;
  std::exception_ptr error;

  // What each run's points are solved with: its settings, the sweep's stop flag and, where
  // the run sets none, the sweep's time limit per point.
  std::vector<Settings> settings;
  settings.reserve(runs.size());
  for (const SweepRun& run : runs) {
    settings.push_back(run.settings);
    settings.back().stop = options.cancel;
    if (settings.back().time_limit == 0.0) settings.back().time_limit = options.point_time_limit;
  }
  // Each run's settings described once, not once a point (as run_point would); a run whose
  // describe throws is described by each point, whose row then says so.
  std::vector<std::optional<std::string>> described(runs.size());
  for (std::size_t r = 0; r < runs.size(); ++r) {
    try {
      described[r] = runs[r].solver->describe(settings[r]);
    } catch (...) {
    }
  }
  const auto cancelled = [&] { return options.cancel && options.cancel->load(); };
  const auto stopped = [&] { return stop.load(std::memory_order_relaxed) || cancelled(); };
  unsigned threads = options.threads ? options.threads : std::thread::hardware_concurrency();
  threads = static_cast<unsigned>(std::clamp<std::size_t>(threads, 1, std::max<std::size_t>(total, 1)));
  const std::vector<int> cores = worker_cores(runs, threads, options.pin_persistent);
  std::atomic<unsigned> workers{0};
  const auto work = [&] {
    const unsigned worker = workers.fetch_add(1);
    const PinnedThread pinned(worker < cores.size() ? cores[worker] : -1);
    // A worker's persistent programs (the external solver's) end with it: started once per worker.
    const programs::ThreadSessionsEnd sessions_end;
    while (!stopped()) {
      const std::optional<std::size_t> task = next_task();
      if (!task || *task >= total) return;
      const std::size_t r = *task / n;
      Row row =
          run_point(cases[*task % n], *task % n, *runs[r].solver, settings[r], runs[r].repetitions, &no_contact,
                    runs[r].monitor_timed, runs[r].estimate, described[r] ? &*described[r] : nullptr);
      row.run = r;
      if (cancelled()) return;  // the run may have been cut short by the stop: not a result
      std::exception_ptr finished_error;
      try {
        if (options.on_finished) options.on_finished(row);
      } catch (...) {
        finished_error = std::current_exception();
      }

      const std::lock_guard lock(mutex);
      if (error) return;
      if (finished_error) {
        error = finished_error;
        stop = true;
        return;
      }
      try {
        if (options.on_row) options.on_row(row);
        if (options.keep_rows) rows.push_back(std::move(row));
        if (options.on_progress) options.on_progress(++done, total);
      } catch (...) {
        error = std::current_exception();
        stop = true;
        return;
      }
    }
  };

  if (threads == 1) {
    work();
  } else {
    std::vector<std::jthread> pool;
    pool.reserve(threads);
    for (unsigned t = 0; t < threads; ++t) pool.emplace_back(work);
  }  // the jthreads join here

  if (error) std::rethrow_exception(error);
  std::sort(rows.begin(), rows.end(), task_order);
  return rows;
}

std::vector<Row> run_sweep(const CaseList& cases, const SolverInfo& solver, const Settings& settings,
                           const SweepOptions& options) {
  const SweepRun run{&solver, settings};
  return run_sweep(cases, std::span(&run, 1), options);
}

}  // namespace pb
