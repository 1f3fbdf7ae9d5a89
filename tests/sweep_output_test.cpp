// What a sweep command does beside the sweep, in process: the partial file's batched writes
// (output/output_files.hpp, BatchedFile) and the watcher thread (output/sweep_watch.hpp), which
// ends as soon as the sweep does. The command line itself is tested as a separate process
// (tests/cli_test.cpp, tests/sweep_files_test.cpp).

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>

#include "output/cost_left.hpp"
#include "output/output_files.hpp"
#include "output/partial_output.hpp"
#include "output/sweep_watch.hpp"
#include "tests/cli_fixture.hpp"
#include "solvers/registry.hpp"

namespace pb::app {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace sweep_output_tests {

using namespace std::chrono_literals;

class BatchedFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = fs::temp_directory_path() / ("poundbench-batched-" + std::to_string(::getpid()) + ".csv");
    fs::remove(path_);
  }
  void TearDown() override { fs::remove(path_); }
  fs::path path_;
};

// The time left from the cost of what is left: a run not started yet costs a finished run of
// its solver scaled by their steps (N = 256 four times N = 64), not the count's rate, and the
// sum turns into seconds at the sweep's own ratio of wall time to finished cost.
TEST(CostLeft, ScalesARunNotStartedByItsStepsAndTheSweepsWallToCostRatio) {
  const SolverInfo* mj = find_solver("moreau-jean");
  Settings coarse, fine;
  coarse.steps = 64;
  fine.steps = 256;
  const std::vector<SweepRun> runs{{mj, coarse}, {mj, fine}};
  const std::vector<std::size_t> todo{0, 1, 2, 3, 4, 5};  // 3 cases, 2 runs
  CostLeft left(runs, 3, todo);
  EXPECT_FALSE(left.seconds_left(1.0).has_value());  // nothing finished: no estimate
  for (std::size_t p = 0; p < 3; ++p) {
    Row row;
    row.run = 0;
    row.point = p;
    row.cpu_seconds = 0.001;
    row.repetitions = 1;
    left.add(row);
  }
  // 3 points of 4 ms left, at 2 s of wall time per 3 ms of finished cost: 8 s. The count
  // (3 of 6 done in 2 s) would say 2 s.
  ASSERT_TRUE(left.seconds_left(2.0).has_value());
  EXPECT_NEAR(*left.seconds_left(2.0), 8.0, 1e-9);
}

// A spectrum's output from its partial file: the lines in point order whatever order they
// finished in (a quoted field holding a comma and a line break included), each row's fields
// handed over in that order, and a point missing or written twice refused.
TEST_F(BatchedFileTest, TheOutputFromThePartialFileHasItsLinesInPointOrder) {
  const std::string header = csv_header();
  const auto write = [&](const std::string& body) {
    std::ofstream out(path_, std::ios::binary);
    out << header << '\n' << body;
  };
  write("b,2,x\n\"a, \nquoted\",0,y\nc,1,z\n");
  std::ostringstream out;
  std::vector<std::string> points;
  write_from_partial(path_, 3, out, [&](const PartialRecord& r) { points.push_back(r.field("point")); });
  EXPECT_EQ(out.str(), header + "\n\"a, \nquoted\",0,y\nc,1,z\nb,2,x\n");
  EXPECT_EQ(points, (std::vector<std::string>{"0", "1", "2"}));

  std::ostringstream ignored;
  write("b,2,x\nc,1,z\n");
  EXPECT_THROW(write_from_partial(path_, 3, ignored), std::runtime_error);  // point 0 missing
  write("b,2,x\nc,1,z\nd,1,z\na,0,y\n");
  EXPECT_THROW(write_from_partial(path_, 3, ignored), std::runtime_error);  // point 1 twice
}

// Lines wait in memory until the batch is due, then reach the file together.
TEST_F(BatchedFileTest, KeepsLinesUntilTheOldestHasWaitedItsDelay) {
  BatchedFile file(path_, BatchedFile::Mode::truncate, 200ms);
  file.add_line("a");
  file.add_line("b");
  file.write_due();
  EXPECT_EQ(read_text(path_), "");
  std::this_thread::sleep_for(250ms);
  file.write_due();
  EXPECT_EQ(read_text(path_), "a\nb\n");
  file.add_line("c");  // a new batch, its own delay
  EXPECT_EQ(read_text(path_), "a\nb\n");
  file.close();
  EXPECT_EQ(read_text(path_), "a\nb\nc\n");
}

// A batch past kMaxBatchBytes is written at once, whatever its age.
TEST_F(BatchedFileTest, WritesABatchThatReachesItsSizeLimitAtOnce) {
  BatchedFile file(path_, BatchedFile::Mode::truncate, std::chrono::hours(1));
  const std::string line(1000, 'x');
  std::size_t lines = 0;
  while (read_text(path_).empty()) {
    file.add_line(line);
    ASSERT_LE(++lines, BatchedFile::kMaxBatchBytes / line.size() + 1);
  }
  EXPECT_EQ(line_count(read_text(path_)), lines);
}

// A file destroyed with lines kept (an exception unwinding the sweep) writes them.
TEST_F(BatchedFileTest, WritesTheLinesItKeepsWhenDestroyed) {
  {
    BatchedFile file(path_, BatchedFile::Mode::truncate, std::chrono::hours(1));
    file.add_line("kept");
  }
  EXPECT_EQ(read_text(path_), "kept\n");
}

// Append mode keeps what the file had (a resumed sweep's earlier rows).
TEST_F(BatchedFileTest, AppendsToWhatTheFileHad) {
  {
    BatchedFile file(path_, BatchedFile::Mode::truncate, 0ms);
    file.add_line("header");
  }
  BatchedFile file(path_, BatchedFile::Mode::append, 0ms);
  file.add_line("row");
  EXPECT_EQ(read_text(path_), "header\nrow\n");
}

// A failed write names the file and the reason, and every later call says so again.
TEST(BatchedFile, AFailedWriteIsReportedByThatCallAndEveryLaterOne) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  BatchedFile file("/dev/full", BatchedFile::Mode::append, 0ms);
  try {
    file.add_line("row");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "/dev/full: write failed: No space left on device");
  }
  EXPECT_THROW(file.add_line("next"), std::runtime_error);
  EXPECT_THROW(file.write_due(), std::runtime_error);
  EXPECT_THROW(file.close(), std::runtime_error);
}

// finish() wakes the watcher: it used to wait for its 100 ms tick to end, so that every sweep
// command ended up to 100 ms after its last point. Run on a thread of its own, since the
// watcher blocks SIGINT and SIGTERM in the thread that makes it.
TEST(SweepWatch, FinishEndsTheWatcherWithoutWaitingForItsTick) {
  double fastest = 1.0;
  std::thread([&] {
    for (int i = 0; i < 5; ++i) {
      const auto start = std::chrono::steady_clock::now();
      SweepWatch watch("test", "points", 1, 0, Progress::none, [] {});
      std::this_thread::sleep_for(1ms);
      watch.finish();
      fastest = std::min(fastest, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
  }).join();
  EXPECT_LT(fastest, 0.05) << "seconds from start to finish";
}

// on_tick runs on the watcher's thread at every tick while the sweep runs.
TEST(SweepWatch, RunsOnTickAtEveryTick) {
  std::atomic<int> ticks{0};
  std::thread([&] {
    SweepWatch watch("test", "points", 1, 0, Progress::none, [] {}, [&] { ++ticks; });
    std::this_thread::sleep_for(450ms);
    watch.finish();
  }).join();
  EXPECT_GE(ticks.load(), 2);
  EXPECT_LE(ticks.load(), 5);
}

}  // namespace sweep_output_tests
}  // namespace pb::app
