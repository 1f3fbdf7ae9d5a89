#include "output/partial_writer.hpp"

#include <algorithm>
#include <stdexcept>

#include "rows/partial_line.hpp"

namespace pb::app {

PartialWriter::PartialWriter(const std::string& partial, bool with_run, std::size_t cases,
                             std::vector<std::string>* lines, std::size_t expected)
    : file_(partial, BatchedFile::Mode::append, Clock::duration::max()),
      with_run_(with_run),
      cases_(cases),
      lines_(lines),
      to_come_(expected) {
  // Grown line by line, the queue was copied as it doubled, under its lock; with room for
  // every line to come, a million-point sweep would reserve its whole file up front.
  queued_.reserve(room());
}

void PartialWriter::queue(const Row& row) {
  Line line{partial_line(row, with_run_), row.run * cases_ + row.point};  // outside the lock
  for (;;) {
    {
      const std::lock_guard hold(mutex_);
      if (!error_.empty()) throw std::runtime_error(error_);
      if (queued_.size() < kMaxQueued) {
        if (queued_.empty()) oldest_ = Clock::now();
        queued_.push_back(std::move(line));
        peak_ = std::max(peak_, queued_.size());
        return;
      }
    }
    write(true);  // full: this worker writes the queue before its line goes in
  }
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
  std::vector<Line> batch;
  {
    const std::lock_guard hold(mutex_);
    if (!error_.empty()) throw std::runtime_error(error_);
    if (queued_.empty() || (!all && Clock::now() - oldest_ < kPartialDelay && queued_.size() < kBatchRows)) return;
    batch.swap(queued_);
    to_come_ -= std::min(to_come_, batch.size());
    queued_.reserve(room());
  }
  try {
    for (Line& line : batch) {
      file_.add_line(line.text);
      if (lines_) (*lines_)[line.task] = std::move(line.text);
    }
    file_.flush();
  } catch (const std::exception& e) {
    const std::lock_guard hold(mutex_);
    error_ = e.what();
    throw;
  }
}

}  // namespace pb::app
