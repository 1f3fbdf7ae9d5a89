#include "app/partial_writer.hpp"

#include <algorithm>
#include <stdexcept>
#include <thread>

#include "sweep/partial_rows.hpp"

namespace pb::app {

PartialWriter::PartialWriter(const std::string& partial, bool with_run, std::size_t cases,
                             std::vector<std::string>* lines, unsigned threads, std::size_t expected)
    : file_(partial, BatchedFile::Mode::append, Clock::duration::max()),
      with_run_(with_run),
      cases_(cases),
      lines_(lines),
      threads_(std::max(threads, 1u)),
      to_come_(expected) {
  // Grown row by row, the queue was copied as it doubled, under the sweep's lock; with room
  // for every row to come, a million-point sweep reserved 1.5 GB up front.
  queued_.reserve(room());
}

void PartialWriter::queue(const Row& row) {
  bool full = false;
  {
    const std::lock_guard hold(mutex_);
    if (!error_.empty()) throw std::runtime_error(error_);
    if (queued_.empty()) oldest_ = Clock::now();
    queued_.push_back(row);
    peak_ = std::max(peak_, queued_.size());
    full = queued_.size() >= kMaxQueued;
  }
  if (full) write(true);
}

void PartialWriter::write_due() {
  try {
    write(false);
  } catch (const std::exception&) {
    // Kept in error_ for the next row's worker.
  }
}

void PartialWriter::close() {
  const std::lock_guard writing(writing_);
  file_.close();
}

std::size_t PartialWriter::peak_queued() const {
  const std::lock_guard hold(mutex_);
  return peak_;
}

void PartialWriter::write(bool all) {
  const std::lock_guard writing(writing_);
  std::vector<Row> rows;
  {
    const std::lock_guard hold(mutex_);
    if (!error_.empty()) throw std::runtime_error(error_);
    if (queued_.empty() || (!all && Clock::now() - oldest_ < kPartialDelay && queued_.size() < kBatchRows)) return;
    rows.swap(queued_);
    to_come_ -= std::min(to_come_, rows.size());
    queued_.reserve(room());
  }
  try {
    std::vector<std::string> text = format(rows);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      file_.add_line(text[i]);
      if (lines_) (*lines_)[rows[i].run * cases_ + rows[i].point] = std::move(text[i]);
    }
    file_.flush();
  } catch (const std::exception& e) {
    const std::lock_guard hold(mutex_);
    error_ = e.what();
    throw;
  }
}

// The rows' lines, on the sweep's threads when there are many: a sweep shorter than
// kPartialDelay (the paper set through the reference, 0.3 s) leaves every row to the last
// batch, written after the workers have stopped, and its 23 820 lines took 0.1 s on one.
std::vector<std::string> PartialWriter::format(const std::vector<Row>& rows) const {
  std::vector<std::string> text(rows.size());
  const std::size_t n = rows.size(), ways = n < 1024 ? 1 : threads_;
  const auto part = [&](std::size_t first) {
    for (std::size_t i = first; i < n; i += ways) text[i] = partial_line(rows[i], with_run_);
  };
  {
    std::vector<std::jthread> pool;
    for (std::size_t w = 1; w < ways; ++w) pool.emplace_back(part, w);
    part(0);
  }  // the jthreads join here, before text is returned
  return text;
}

}  // namespace pb::app
