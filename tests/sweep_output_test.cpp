// What a sweep command does beside the sweep, in process: the partial file's batched writes
// (app/output_files.hpp, BatchedFile) and the watcher thread (app/sweep_watch.hpp), which
// ends as soon as the sweep does. The command line itself is tested as a separate process
// (tests/cli_test.cpp, tests/sweep_files_test.cpp).

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <thread>

#include "app/output_files.hpp"
#include "app/sweep_watch.hpp"
#include "tests/cli_fixture.hpp"

namespace pb::app {
namespace {

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

}  // namespace
}  // namespace pb::app
