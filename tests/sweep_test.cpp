// The sweep runner (sweep/sweep.hpp) and its CSV rows (rows/row.hpp).

#include <gtest/gtest.h>
#include <time.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <mutex>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cases/case_set.hpp"
#include "cases/text.hpp"
#include "rows/row.hpp"
#include "rows/row_read.hpp"
#include "kit/solver.hpp"
#include "solvers/registry.hpp"
#include "sweep/no_contact_cache.hpp"
#include "sweep/stopwatch.hpp"
#include "studies/workprecision.hpp"
#include "sweep/sweep.hpp"
#include "kit/testing.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace sweep_tests {

std::vector<Case> smoke_cases() {
  return load_case_set(std::string(POUNDBENCH_SOURCE_DIR) + "/cases/sets/smoke.toml").cases;
}

const SolverInfo& reference_solver() {
  const SolverInfo* solver = find_solver("event-driven");
  if (!solver) throw std::logic_error("no event-driven solver in the registry");
  return *solver;
}

std::string line_without_time(Row row) {
  clear_timing(row);
  return csv_line(row);
}

TEST(Sweep, ReturnsOneRowPerCaseInPointOrder) {
  const std::vector<Case> cases = smoke_cases();
  SweepOptions options;
  options.threads = 2;
  std::vector<std::size_t> completion_order;
  options.on_row = [&](const Row& row) { completion_order.push_back(row.point); };
  const std::vector<Row> rows = run_sweep(cases, reference_solver(), Settings{}, options);

  ASSERT_EQ(rows.size(), cases.size());
  ASSERT_EQ(completion_order.size(), cases.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].point, i);
    EXPECT_EQ(rows[i].input.family, cases[i].family);
    EXPECT_EQ(rows[i].input.pi2, cases[i].pi2);
    EXPECT_EQ(rows[i].result.status, Status::ok) << rows[i].result.message;
    EXPECT_TRUE(std::isfinite(rows[i].result.pi1));
    EXPECT_TRUE(std::isfinite(rows[i].pi1_no_contact));
  }
}

// keep_rows false (a streamed spectrum): the rows go to on_row alone, the same ones, each once,
// and the progress still counts every one.
TEST(Sweep, KeepingNoRowsHandsEveryRowToOnRowAlone) {
  const std::vector<Case> cases = smoke_cases();
  SweepOptions options;
  options.threads = 2;
  const std::vector<Row> kept = run_sweep(cases, reference_solver(), Settings{}, options);
  std::vector<std::string> seen(cases.size());
  std::size_t last_done = 0;
  options.keep_rows = false;
  options.on_row = [&](const Row& row) { seen.at(row.point) += line_without_time(row); };
  options.on_progress = [&](std::size_t done, std::size_t) { last_done = done; };
  EXPECT_TRUE(run_sweep(cases, reference_solver(), Settings{}, options).empty());
  EXPECT_EQ(last_done, cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) EXPECT_EQ(seen[i], line_without_time(kept[i])) << i;
}

// on_finished (the partial file's lines, made by the workers side by side) sees every row once,
// before on_row sees it; an exception it throws stops the sweep and comes out of run_sweep as
// one from on_row does.
TEST(Sweep, OnFinishedSeesEveryRowOnceBeforeOnRowAndItsExceptionStopsTheSweep) {
  const std::vector<Case> cases = smoke_cases();
  SweepOptions options;
  options.threads = 2;
  options.keep_rows = false;
  std::mutex mutex;
  std::vector<int> finished(cases.size(), 0);
  std::size_t out_of_order = 0;
  options.on_finished = [&](const Row& row) {
    const std::lock_guard lock(mutex);
    ++finished.at(row.point);
  };
  options.on_row = [&](const Row& row) {
    const std::lock_guard lock(mutex);
    if (finished.at(row.point) != 1) ++out_of_order;
  };
  run_sweep(cases, reference_solver(), Settings{}, options);
  EXPECT_EQ(std::count(finished.begin(), finished.end(), 1), static_cast<std::ptrdiff_t>(cases.size()));
  EXPECT_EQ(out_of_order, 0u);

  std::atomic<std::size_t> rows_seen{0};
  options.on_finished = [&](const Row&) {
    if (rows_seen.fetch_add(1) == 2) throw std::runtime_error("partial file: disk full");
  };
  options.on_row = nullptr;
  EXPECT_THROW(
      {
        try {
          run_sweep(cases, reference_solver(), Settings{}, options);
        } catch (const std::runtime_error& e) {
          EXPECT_STREQ(e.what(), "partial file: disk full");
          throw;
        }
      },
      std::runtime_error);
  // Stopped: the two threads finish at most the points they were solving.
  EXPECT_LT(rows_seen.load(), cases.size());
}

// The solvers are deterministic and reentrant, so the thread count must not change a
// single digit of any result; only the measured time differs.
TEST(Sweep, OneAndTwoThreadsGiveIdenticalRows) {
  const std::vector<Case> cases = smoke_cases();
  SweepOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const std::vector<Row> a = run_sweep(cases, reference_solver(), Settings{}, one);
  const std::vector<Row> b = run_sweep(cases, reference_solver(), Settings{}, two);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(line_without_time(a[i]), line_without_time(b[i]));
}

TEST(Sweep, RunsEveryRunOverEveryCaseSortedByRunThenPoint) {
  const std::vector<Case> cases = smoke_cases();
  Settings loose;
  loose.tol_scale = 100;
  const std::vector<SweepRun> runs = {{&reference_solver(), Settings{}}, {&reference_solver(), loose}};
  SweepOptions options;
  options.threads = 2;
  std::size_t last_total = 0;
  options.on_progress = [&](std::size_t, std::size_t total) { last_total = total; };
  const std::vector<Row> rows = run_sweep(cases, runs, options);
  ASSERT_EQ(rows.size(), 2 * cases.size());
  EXPECT_EQ(last_total, 2 * cases.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].run, i / cases.size());
    EXPECT_EQ(rows[i].point, i % cases.size());
    EXPECT_EQ(rows[i].settings, i < cases.size() ? R"({"tol_scale":1})" : R"({"tol_scale":100})");
  }
  // The first run is the one-run sweep of the same settings.
  const std::vector<Row> alone = run_sweep(cases, reference_solver(), Settings{}, options);
  for (std::size_t i = 0; i < cases.size(); ++i) EXPECT_EQ(line_without_time(rows[i]), line_without_time(alone[i]));
}

TEST(Sweep, ATaskSourceRunsOnlyItsTasks) {
  const std::vector<Case> cases = smoke_cases();
  const std::vector<std::size_t> tasks = {39, 3, 17};
  SweepOptions options;
  options.threads = 2;
  options.next_task = tasks_from(tasks);
  const std::vector<Row> rows = run_sweep(cases, reference_solver(), Settings{}, options);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].point, 3u);
  EXPECT_EQ(rows[1].point, 17u);
  EXPECT_EQ(rows[2].point, 39u);
}

TEST(Sweep, CancelStopsStartingNewPoints) {
  std::vector<Case> cases;
  for (int copy = 0; copy < 20; ++copy)
    for (const Case& c : smoke_cases()) cases.push_back(c);
  std::atomic<bool> cancel{false};
  std::size_t reported = 0;
  std::size_t last_progress = 0;
  SweepOptions options;
  options.threads = 2;
  options.cancel = &cancel;
  options.on_row = [&](const Row&) {
    ++reported;
    cancel = true;
  };
  options.on_progress = [&](std::size_t done, std::size_t total) {
    last_progress = done;
    EXPECT_EQ(total, cases.size());
  };
  const std::vector<Row> rows = run_sweep(cases, reference_solver(), Settings{}, options);
  // The first row cancels; each other thread can finish at most the point it was running.
  EXPECT_GE(rows.size(), 1u);
  EXPECT_LE(rows.size(), options.threads);
  EXPECT_EQ(reported, rows.size());
  EXPECT_EQ(last_progress, rows.size());
}

TEST(Sweep, AnExceptionFromOnRowStopsTheSweepAndIsRethrown) {
  const std::vector<Case> cases = smoke_cases();
  SweepOptions options;
  options.threads = 2;
  std::size_t calls = 0;
  options.on_row = [&](const Row&) {
    ++calls;
    throw std::runtime_error("disk full");
  };
  EXPECT_THROW(run_sweep(cases, reference_solver(), Settings{}, options), std::runtime_error);
  EXPECT_EQ(calls, 1u);  // later rows are not reported once a callback failed
}

// The sweep's no-contact Pi1 comes from a cache shared by its runs and threads
// (sweep/no_contact_cache.hpp): every row still has the value of its own solve, bit for bit.
TEST(Sweep, EveryRowHasTheNoContactPi1OfItsOwnSolveBitForBit) {
  const std::vector<Case> cases = smoke_cases();
  const SweepRun runs[] = {{&reference_solver(), {}}, {find_solver("moreau-jean"), {}}};
  SweepOptions options;
  options.threads = 2;
  const std::vector<Row> rows = run_sweep(cases, runs, options);
  ASSERT_EQ(rows.size(), 2 * cases.size());
  for (const Row& row : rows) {
    const double solved = no_contact_pi1(make_system(cases[row.point]), Settings{});
    EXPECT_EQ(std::bit_cast<std::uint64_t>(row.pi1_no_contact), std::bit_cast<std::uint64_t>(solved))
        << "run " << row.run << " point " << row.point;
  }
}

// The paper set's Fig. 10 family (820 points, of 20 no-contact problems: its points differ
// in the contact's Pi terms): a point that shares body 0, the pulse and the durations with an
// earlier one gets its value from the cache, and that value is the one its own solve gives.
TEST(NoContactCache, GivesEveryPointItsOwnSolvesValueAndSolvesSharedProblemsOnce) {
  const std::vector<Case> all = load_case_set(std::string(POUNDBENCH_SOURCE_DIR) + "/cases/sets/paper.toml").cases;
  NoContactCache cache;
  std::size_t points = 0;
  for (const Case& c : all) {
    if (c.family != "fig10") continue;
    ++points;
    const System s = make_system(c);
    const double cached = cache.pi1(s, Settings{});
    const double solved = no_contact_pi1(s, Settings{});
    ASSERT_EQ(std::bit_cast<std::uint64_t>(cached), std::bit_cast<std::uint64_t>(solved)) << "point " << points;
  }
  EXPECT_EQ(points, 820u);
  EXPECT_EQ(cache.size(), cache.solves());
  EXPECT_EQ(cache.solves(), 20u);
}

// The key holds every value of the one-body system the no-contact solve reads, and nothing
// of the other bodies.
TEST(NoContactKey, ChangesWithEveryValueOfBodyZerosProblemAndWithNoOtherBody) {
  Case c = test::make_case(Scene::row3, PulseShape::cosine, 0.8, 0.5, 0.5);
  c.pi7 = 2.0;
  const System s = make_system(c);
  const NoContactKey key = no_contact_key(s);
  const auto changed = [&](auto&& change) {
    System other = s;
    change(other);
    return !(no_contact_key(other) == key);
  };
  Body& (*body0)(System&) = [](System& x) -> Body& { return x.bodies[static_cast<std::size_t>(x.ref)]; };
  EXPECT_TRUE(changed([&](System& x) { body0(x).m *= 2; }));
  EXPECT_TRUE(changed([&](System& x) { body0(x).w *= 2; }));
  EXPECT_TRUE(changed([&](System& x) { body0(x).k *= 2; }));
  EXPECT_TRUE(changed([&](System& x) { body0(x).c *= 2; }));
  EXPECT_TRUE(changed([](System& x) { x.pulse.shape = PulseShape::sine; }));
  EXPECT_TRUE(changed([](System& x) { x.pulse.amplitude = -x.pulse.amplitude; }));
  EXPECT_TRUE(changed([](System& x) { x.pulse.w *= 2; }));
  EXPECT_TRUE(changed([](System& x) { x.a_p *= 2; }));
  EXPECT_TRUE(changed([](System& x) { x.t_end *= 2; }));
  EXPECT_TRUE(changed([](System& x) { x.t_min *= 2; }));
  EXPECT_TRUE(changed([](System& x) { x.delta *= 2; }));
  EXPECT_TRUE(changed([](System& x) { x.eps *= 2; }));
  EXPECT_TRUE(changed([](System& x) { x.xi *= 2; }));
  EXPECT_TRUE(changed([](System& x) { x.u_start.assign(3, 0.25); }));
  EXPECT_TRUE(changed([](System& x) { x.v_start.assign(3, 0.25); }));
  EXPECT_FALSE(changed([](System& x) { x.bodies[0].m *= 2; }));  // body 1, left of body 0
  EXPECT_FALSE(changed([](System& x) { x.bodies[2].w *= 2; }));  // body 2
  EXPECT_FALSE(changed([](System& x) { x.u_start.assign(3, 0.0); }));  // rest, said explicitly
}

// A solve cut short (a sweep being stopped: NaN) is not kept; the next point solves again.
TEST(NoContactCache, KeepsNoValueOfASolveCutShort) {
  const System s = make_system(smoke_cases().front());
  NoContactCache cache;
  const std::atomic<bool> stop{true};
  Settings stopped;
  stopped.stop = &stop;
  EXPECT_TRUE(std::isnan(cache.pi1(s, stopped)));
  EXPECT_EQ(cache.size(), 0u);
  EXPECT_TRUE(std::isfinite(cache.pi1(s, Settings{})));
  EXPECT_EQ(cache.solves(), 2u);
  EXPECT_EQ(cache.size(), 1u);
}

// A pulse model's waves are not in the key: two Mavroeidis-Papageorgiou pulses that differ
// only in their phase have the same key, and each gets its own solve's value.
TEST(NoContactCache, SolvesEveryPointOfAPulseModel) {
  NoContactCache cache;
  for (double nu : {0.0, 90.0}) {
    Case c = smoke_cases().front();
    c.pulse = PulseShape::mp;
    c.mp_gamma = 2.5;
    c.mp_nu = nu;
    const System s = make_system(c);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(cache.pi1(s, Settings{})),
              std::bit_cast<std::uint64_t>(no_contact_pi1(s, Settings{})))
        << "nu " << nu;
  }
  EXPECT_EQ(cache.size(), 0u);
}

Result throwing_solve(const System&, const Settings&) { throw std::runtime_error("matrix is singular"); }
std::string no_settings(const Settings&) { return R"({"x":1})"; }
std::string accept(const Settings&) { return {}; }

TEST(RunPoint, TurnsASolverExceptionIntoAFailedRow) {
  const SolverInfo thrower{"thrower", "throws", &throwing_solve, &no_settings, &accept};
  const Row row = run_point(smoke_cases().front(), 7, thrower, Settings{});
  EXPECT_EQ(row.point, 7u);
  EXPECT_EQ(row.solver, "thrower");
  EXPECT_EQ(row.settings, R"({"x":1})");
  EXPECT_EQ(row.result.status, Status::failed);
  EXPECT_EQ(row.result.message, "matrix is singular");
  EXPECT_TRUE(std::isnan(row.result.pi1));
  // The no-contact response does not depend on the solver under test.
  EXPECT_TRUE(std::isfinite(row.pi1_no_contact));
}

Result ok_without_pi1(const System&, const Settings&) {
  Result r;
  r.status = Status::ok;
  r.impacts = 3;
  return r;  // pi1 left NaN
}

Result negative_count(const System&, const Settings&) {
  Result r;
  r.status = Status::diverged;
  r.impacts = -5;
  return r;
}

// A solver's result that a row read back could not be (rows/row.hpp row_problem) is
// written as a failed row saying why, never as the result.
TEST(RunPoint, TurnsAnInconsistentResultIntoAFailedRow) {
  for (auto* solve : {&ok_without_pi1, &negative_count}) {
    const SolverInfo liar{"liar", "returns what no row may hold", solve, &no_settings, &accept};
    const Row row = run_point(smoke_cases().front(), 0, liar, Settings{});
    EXPECT_EQ(row.result.status, Status::failed);
    EXPECT_EQ(row.result.message.rfind("the solver returned an inconsistent result: ", 0), 0u) << row.result.message;
    EXPECT_EQ(row.result.impacts, 0);
    EXPECT_EQ(row_problem(row), "");
  }
}

TEST(RunPoint, TurnsAnInvalidCaseIntoAFailedRow) {
  Case c = smoke_cases().front();
  c.eps = 1.5;
  const Row row = run_point(c, 0, reference_solver(), Settings{});
  EXPECT_EQ(row.result.status, Status::failed);
  EXPECT_EQ(row.result.message.rfind("eps:", 0), 0u) << row.result.message;
}

// ---------------------------------------------------------------- timing

double thread_cpu() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Spends `seconds` of this thread's CPU time.
void burn(double seconds) {
  const double end = thread_cpu() + seconds;
  while (thread_cpu() < end) {
  }
}

// The clocks' own cost is taken off an interval: around nothing it measures about zero, where
// the thread's CPU clock, a system call, made it some 0.37 us (sweep/stopwatch.hpp); and a
// known amount of work is still measured whole.
TEST(Stopwatch, TakesTheClocksOwnCostOffAnInterval) {
  const Elapsed& cost = Stopwatch::clock_cost();
  EXPECT_GT(cost.cpu, 0.0);
  EXPECT_GE(cost.wall, 0.0);
  std::vector<double> cpu;
  for (int i = 0; i < 101; ++i) {
    const Elapsed e = Stopwatch().elapsed();
    EXPECT_GE(e.cpu, 0.0);
    EXPECT_GE(e.wall, 0.0);
    cpu.push_back(e.cpu);
  }
  std::nth_element(cpu.begin(), cpu.begin() + 50, cpu.end());
  EXPECT_LT(cpu[50], cost.cpu) << "the median empty interval, the clocks' cost taken off";
  const Stopwatch watch;
  burn(1e-3);
  const Elapsed e = watch.elapsed();
  EXPECT_GE(e.cpu, 1e-3);
  EXPECT_GE(e.wall, e.cpu * 0.99);
}

// What the local solvers below saw: the calls, by whether the monitor was on. Tests run
// one at a time, and run_point calls a solver on its caller's thread.
int g_monitored = 0, g_unmonitored = 0;
std::vector<double> g_costs;  // CPU seconds the k-th unmonitored call spends (the last repeats)

Result costly_solve(const System&, const Settings& settings) {
  Result r;
  r.pi1 = 1.5;
  if (settings.monitor) {
    ++g_monitored;
    r.energy_excess = -0.25;  // what only the monitor measures
    r.isolated_impacts = 2;
    r.restitution_low = r.restitution_high = 0.5;
    return r;
  }
  burn(g_costs[std::min<std::size_t>(static_cast<std::size_t>(g_unmonitored), g_costs.size() - 1)]);
  ++g_unmonitored;
  return r;
}

const SolverInfo kCostly{"costly", "spends a given CPU time", &costly_solve, &no_settings, &accept};

Row timed_row(std::vector<double> costs, int repetitions, bool monitor = false) {
  g_monitored = g_unmonitored = 0;
  g_costs = std::move(costs);
  Settings settings;
  settings.monitor = monitor;
  return run_point(smoke_cases().front(), 0, kCostly, settings, repetitions);
}

// Five repetitions costing 1.6, 0.4, 1.2, 0.8 and 2.0 ms (each a little more: the clock is
// read after the work): the row's CPU time is the median, with the fastest and slowest. The
// costs are 0.4 ms apart and 6 ms in all (under the point's budget): the clocks' own cost,
// microseconds even on a loaded machine, cannot move one into its neighbour's range.
TEST(RunPoint, TimesTheSolveRepeatedlyAndKeepsTheMedianAndTheRange) {
  const Row row = timed_row({1.6e-3, 0.4e-3, 1.2e-3, 0.8e-3, 2.0e-3}, 5);
  ASSERT_EQ(row.result.status, Status::ok) << row.result.message;
  EXPECT_EQ(row.repetitions, 5);
  EXPECT_EQ(g_unmonitored, 5);
  EXPECT_EQ(g_monitored, 0);
  EXPECT_GE(row.cpu_seconds, 1.2e-3);
  EXPECT_LT(row.cpu_seconds, 1.6e-3);
  EXPECT_GE(row.cpu_seconds_low, 0.4e-3);
  EXPECT_LT(row.cpu_seconds_low, 0.8e-3);
  EXPECT_GE(row.cpu_seconds_high, 2.0e-3);
  EXPECT_LT(row.cpu_seconds_high, 4.0e-3);
  EXPECT_GE(row.seconds, row.cpu_seconds * 0.99);  // wall time: the median too, never less than CPU
  EXPECT_EQ(row.result.pi1, 1.5);

  const Row once = timed_row({2e-4}, 1);
  EXPECT_EQ(once.repetitions, 1);
  EXPECT_EQ(once.cpu_seconds_low, once.cpu_seconds);
  EXPECT_EQ(once.cpu_seconds_high, once.cpu_seconds);
}

// A point stops repeating once its solves have spent kRepetitionBudget together: 6 ms solves
// are timed twice (6 ms is under the 10 ms budget, 12 ms is over), never fewer than once.
TEST(RunPoint, StopsRepeatingOnceThePointsBudgetIsSpent) {
  ASSERT_EQ(kRepetitionBudget, 0.01);
  EXPECT_EQ(timed_row({6e-3}, 5).repetitions, 2);
  EXPECT_EQ(timed_row({0.02}, 5).repetitions, 1);
  EXPECT_EQ(timed_row({1e-4}, 3).repetitions, 3);
}

// The timed solves run with the monitor off; what the monitor measures comes from one more,
// untimed solve with it on, when the run asks for it (and only then).
TEST(RunPoint, TimesTheSolveWithoutTheMonitorAndTakesItsMeasurementsFromOneMorePass) {
  const Row row = timed_row({1e-4}, 3, true);
  ASSERT_EQ(row.result.status, Status::ok) << row.result.message;
  EXPECT_EQ(g_unmonitored, 3);
  EXPECT_EQ(g_monitored, 1);
  EXPECT_EQ(row.result.energy_excess, -0.25);
  EXPECT_EQ(row.result.isolated_impacts, 2);
  EXPECT_EQ(row.result.restitution_high, 0.5);
  EXPECT_LT(row.cpu_seconds_high, 2e-3);  // the monitored pass is not timed

  const Row without = timed_row({1e-4}, 3, false);
  EXPECT_EQ(g_monitored, 0);
  EXPECT_TRUE(std::isnan(without.result.energy_excess));
}

// A study that judges the monitor (stress) times the monitored solves themselves: each point is
// solved once per repetition, never once more, and its rows carry the monitor's measurements.
TEST(RunSweep, AStudyThatJudgesTheMonitorTimesTheMonitoredSolvesAlone) {
  Settings monitored;
  monitored.monitor = true;
  SettingsList list;
  list.runs = {{&kCostly, monitored, 1}};
  const std::vector<SweepRun> runs = study_runs(list, {.repetitions = 2, .monitor = true});
  ASSERT_EQ(runs.size(), 2u);  // the truth, then the list's run
  EXPECT_TRUE(runs[1].monitor_timed);
  EXPECT_FALSE(study_runs(list, {.repetitions = 2}).back().monitor_timed);

  g_monitored = g_unmonitored = 0;
  const std::vector<Case> cases = smoke_cases();
  SweepOptions one_thread;
  one_thread.threads = 1;
  const std::vector<Row> rows = run_sweep(CaseList(std::span(cases).first(3)), std::span(runs).subspan(1), one_thread);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(g_monitored, 6);
  EXPECT_EQ(g_unmonitored, 0);
  for (const Row& row : rows) {
    EXPECT_EQ(row.repetitions, 2);
    EXPECT_EQ(row.result.energy_excess, -0.25);
  }
}

std::atomic<int> g_calls{0};

Result monitor_moves_pi1(const System&, const Settings& settings) {
  Result r;
  r.pi1 = settings.monitor ? std::nextafter(1.0, 2.0) : 1.0;
  return r;
}

Result monitor_runs_out_of_time(const System&, const Settings& settings) {
  Result r;
  r.pi1 = 1.0;
  if (settings.monitor) {
    r.status = Status::time_limit;
    r.pi1 = std::numeric_limits<double>::quiet_NaN();
  }
  return r;
}

Result drifts(const System&, const Settings&) {
  Result r;
  r.pi1 = g_calls++ == 0 ? 1.0 : std::nextafter(1.0, 2.0);  // one ulp from the second call on
  return r;
}

// The monitor must not change the result, nor may a repetition: a row whose monitored pass
// or second repetition differs by one ulp fails, saying so, and holds none of its values.
TEST(RunPoint, FailsARowWhoseMonitorOrRepetitionChangesPi1) {
  Settings monitored;
  const SolverInfo moved{"moved", "the monitor moves Pi1", &monitor_moves_pi1, &no_settings, &accept};
  Row row = run_point(smoke_cases().front(), 0, moved, monitored, 2);
  EXPECT_EQ(row.result.status, Status::failed);
  EXPECT_NE(row.result.message.find("the monitor must not change the result"), std::string::npos)
      << row.result.message;
  EXPECT_TRUE(std::isnan(row.result.pi1));

  // A monitored solve cut short by its time limit (a busier machine) changed nothing: the
  // timed answer stands, without the monitor's measurements, and says why.
  const SolverInfo slow{"slow", "its monitored solve runs out of time", &monitor_runs_out_of_time, &no_settings,
                        &accept};
  row = run_point(smoke_cases().front(), 0, slow, monitored, 2);
  EXPECT_EQ(row.result.status, Status::ok) << row.result.message;
  EXPECT_EQ(row.result.pi1, 1.0);
  EXPECT_NE(row.result.message.find("the monitored solve passed the time limit"), std::string::npos);

  Settings plain;
  plain.monitor = false;
  const SolverInfo drifting{"drifting", "not deterministic", &drifts, &no_settings, &accept};
  g_calls = 0;
  row = run_point(smoke_cases().front(), 0, drifting, plain, 3);
  EXPECT_EQ(row.result.status, Status::failed);
  const std::string says = "repetition 2 gave ok with Pi1 1.0000000000000002 and the first ok with Pi1 1:";
  EXPECT_EQ(row.result.message.rfind(says, 0), 0u) << row.result.message;
  // One repetition has nothing to differ from.
  g_calls = 0;
  EXPECT_EQ(run_point(smoke_cases().front(), 0, drifting, plain, 1).result.status, Status::ok);
}

TEST(RunPoint, RefusesRepetitionsOutsideOneToTheLimit) {
  for (int r : {0, -1, kMaxRepetitions + 1}) {
    const Row row = run_point(smoke_cases().front(), 0, reference_solver(), Settings{}, r);
    EXPECT_EQ(row.result.status, Status::failed);
    EXPECT_EQ(row.result.message.rfind("repetitions: must be from 1 to 1000", 0), 0u) << row.result.message;
  }
}

TEST(Csv, QuotesOnlyFieldsThatNeedIt) {
  EXPECT_EQ(csv_field("pair-stiff"), "pair-stiff");
  EXPECT_EQ(csv_field("tol_scale=1;steps=4"), "tol_scale=1;steps=4");
  EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csv_field("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(csv_field(""), "");
}

// Exact equality: the text must carry every bit of the double.
TEST(Csv, NumbersReadBackToTheSameDouble) {
  for (double x : {0.1, 1.0 / 3.0, 2.0 / 3.0 * 1e-300, 5e-324, 1e22, 123456789.123456789, -0.75, 0.0,
                   std::numbers::pi, std::nextafter(1.0, 2.0)}) {
    const std::string text = format_number(x);
    EXPECT_EQ(std::strtod(text.c_str(), nullptr), x) << text;
  }
  EXPECT_EQ(format_number(0.1), "0.1");  // shortest, not %.17g's 0.10000000000000001
  EXPECT_EQ(format_number(std::numeric_limits<double>::quiet_NaN()), "");
}

TEST(Csv, LineHasOneFieldPerHeaderColumnAndReadsBack) {
  const std::vector<std::string> header = split_csv(csv_header());
  // 47, the yielding, the physical, the own timings, h_over_dt, the estimates, the separations
  // (residual_m, five _pi/_m pairs, peaks_m, peaks_no_contact_m), a record's scaling
  ASSERT_EQ(header.size(), 95u);
  EXPECT_EQ(header.front(), "family");
  EXPECT_EQ(header[28], "message");  // the columns after it were appended later
  EXPECT_EQ(header[37], "penetration_steps");
  EXPECT_EQ(header[40], "repetitions");
  EXPECT_EQ(header[44], "record");  // the loads' columns (issue 21)
  EXPECT_EQ(header[46], "unresolved");  // then the verdict's (issue 32)
  EXPECT_EQ(header[47], "pi_y0");  // yielding's fields and responses (issue 39)
  EXPECT_EQ(header[55], "t0");     // the physical values and results (issue 35)
  EXPECT_EQ(header[74], "startup_seconds");  // the external solver's own timings (issue 37)
  EXPECT_EQ(header[75], "h_over_dt");        // a record's step over its sampling interval (issue 34)
  EXPECT_EQ(header[76], "error_estimate");   // the error estimates (issue 48)
  EXPECT_EQ(header[78], "residual_m");       // the separations (issue 51)
  EXPECT_EQ(header[91], "record_scale");     // and a record's scaling, last (issue 51)
  EXPECT_EQ(header.back(), "sa_period");

  Row row;
  row.input.family = "odd, \"name\"";
  row.input.scene = Scene::pair;
  row.input.pi2 = 1.0 / 3.0;
  row.point = 12;
  row.solver = "event-driven";
  row.settings = R"({"tol_scale":1})";
  row.result.pi1 = 2.0 / 7.0;
  row.result.impacts = 5;
  row.result.message = "stopped, \"early\"\nsee log";
  row.length_scale = 1.0;
  const std::vector<std::string> fields = split_csv(csv_line(row));
  ASSERT_EQ(fields.size(), header.size());
  const auto field = [&](const std::string& column) {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == column) return fields[i];
    throw std::logic_error("no column " + column);
  };
  EXPECT_EQ(field("family"), row.input.family);
  EXPECT_EQ(field("message"), row.result.message);
  EXPECT_EQ(field("point"), "12");
  EXPECT_EQ(field("scene"), "pair");
  EXPECT_EQ(std::strtod(field("pi2").c_str(), nullptr), row.input.pi2);
  EXPECT_EQ(std::strtod(field("pi1").c_str(), nullptr), row.result.pi1);
  EXPECT_EQ(field("impacts"), "5");
  EXPECT_EQ(field("pi5"), "1");   // pair has body 1
  EXPECT_EQ(field("pi7"), "");    // but no body 2
  EXPECT_EQ(field("min_gap"), "");  // no contact closed: infinite gap
  EXPECT_EQ(field("pi1_no_contact"), "");  // NaN
  EXPECT_EQ(field("pi_y0"), "");  // an elastic case: no yield fields, no yield responses
  EXPECT_EQ(field("alpha"), "");
  EXPECT_EQ(field("mu"), "");
  EXPECT_EQ(field("error_estimate"), "");  // not estimated
  row.result.error_estimate = 1.0 / 3.0;
  row.result.error_estimate_velocity = 0.125;
  row.input.pi_y0 = 0.5;
  row.input.alpha = 0.05;
  row.result.residual = 0.25;
  const std::vector<std::string> yielding = split_csv(csv_line(row));
  const Row back = parse_row(yielding);
  EXPECT_EQ(back.input.pi_y0, 0.5);
  EXPECT_EQ(back.input.alpha, 0.05);
  EXPECT_TRUE(std::isinf(back.input.pi_y1));  // not given: elastic
  EXPECT_EQ(back.result.residual, 0.25);
  EXPECT_EQ(back.result.error_estimate, 1.0 / 3.0);
  EXPECT_EQ(back.result.error_estimate_velocity, 0.125);
  EXPECT_EQ(ductility(back), row.result.pi1 / 0.5);
  EXPECT_EQ(case_key(back.input), case_key(row.input));
}

// The verdict (kit/verdict.hpp) goes out and comes back as it was: true, false with its
// reasons (a comma and a quote in them), and not judged; and a file written before its two
// columns reads, its rows not judged.
TEST(Csv, TheVerdictReadsBackAndAFileFromBeforeItStillReads) {
  Row row;
  row.input.scene = Scene::wall;
  row.solver = "compliant";
  row.settings = "{}";
  row.result.pi1 = 1.5;
  row.length_scale = 1.0;
  for (std::optional<bool> resolved : {std::optional<bool>(true), std::optional<bool>(false), std::optional<bool>()}) {
    row.result.resolved = resolved;
    row.result.unresolved = resolved == false ? "a contact lasted 1 step, \"short\"" : "";
    const Row back = parse_row(split_csv(csv_line(row)));
    EXPECT_EQ(back.result.resolved, resolved);
    EXPECT_EQ(back.result.unresolved, row.result.unresolved);
    EXPECT_EQ(csv_line(back), csv_line(row));
  }
  // A file from before the verdict: its columns end before `resolved` (and the physical ones after it).
  std::string header = csv_header();
  header.erase(header.rfind(",resolved"));
  const std::vector<std::string> fields = split_csv(csv_line(row));
  const auto joined = [](const std::vector<std::string>& f) {
    std::string text;
    for (std::size_t i = 0; i < f.size(); ++i) (text += i ? "," : "") += csv_field(f[i]);
    return text;
  };
  const std::vector<std::string> before(fields.begin(), fields.begin() + static_cast<long>(split_csv(header).size()));
  std::istringstream old(header + "\n" + joined(before) + "\n");
  const RowFile file = read_csv(old, "old.csv");
  ASSERT_EQ(file.rows.size(), 1u);
  EXPECT_FALSE(file.rows[0].result.resolved.has_value());
  std::vector<std::string> maybe = fields;
  maybe[split_csv(header).size()] = "maybe";  // the resolved column
  std::istringstream bad(csv_header() + "\n" + joined(maybe) + "\n");
  EXPECT_THROW(read_csv(bad, "bad.csv"), RowReadError);
}

TEST(Csv, MinGapIsDividedByTheLengthScale) {
  Row row;
  row.result.min_gap = -0.002;
  row.length_scale = 0.5;
  EXPECT_DOUBLE_EQ(min_gap_ratio(row), -0.004);
  const std::vector<std::string> fields = split_csv(csv_line(row));
  EXPECT_EQ(fields[25], "-0.004");
}

TEST(Csv, ChainRowsCarryBodiesAndKickAndTimeSteppersTheirWh) {
  const std::vector<std::string> header = split_csv(csv_header());
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  Row chain;
  chain.input.scene = Scene::chain;
  chain.input.bodies = 5;
  chain.input.kick = 1.5;
  const std::vector<std::string> fields = split_csv(csv_line(chain));
  ASSERT_EQ(fields.size(), header.size());
  EXPECT_EQ(fields[column("bodies")], "5");
  EXPECT_EQ(fields[column("kick")], "1.5");

  Case c;  // a pair
  Settings wh;
  wh.wh = 2.0;
  const Row stepper = run_point(c, 0, *find_solver("moreau-jean"), wh);
  ASSERT_EQ(stepper.result.status, Status::ok) << stepper.result.message;
  const std::vector<std::string> pair = split_csv(csv_line(stepper));
  EXPECT_EQ(pair[column("bodies")], "");
  EXPECT_EQ(pair[column("kick")], "");
  // Recovered from the step the solver took: 2 up to the rounding of h and back.
  EXPECT_NEAR(std::strtod(pair[column("wh")].c_str(), nullptr), 2.0, 1e-12);
  // Measured by the stepper's monitor; within one step of travel (its proven bound).
  ASSERT_FALSE(pair[column("penetration_steps")].empty());
  EXPECT_LE(std::strtod(pair[column("penetration_steps")].c_str(), nullptr), 1.0);
  const std::vector<std::string> reference = split_csv(csv_line(run_point(c, 0, reference_solver(), Settings{})));
  EXPECT_EQ(reference[column("wh")], "");
  EXPECT_EQ(reference[column("penetration_steps")], "");  // no step
}

TEST(Csv, WriteCsvWritesHeaderAndOneLinePerRow) {
  std::vector<Row> rows(3);
  std::ostringstream out;
  write_csv(out, rows);
  const std::string text = out.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 4);
  EXPECT_EQ(text.substr(0, text.find('\n')), csv_header());
}

}  // namespace sweep_tests
}  // namespace pb
