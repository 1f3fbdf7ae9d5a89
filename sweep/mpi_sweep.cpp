#include "sweep/mpi_sweep.hpp"

#include <mpi.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <list>
#include <mutex>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <thread>

#include "rows/partial_line.hpp"
#include "rows/row_read.hpp"

namespace pb::mpi {

namespace {

enum Tag : int { kRequest = 1, kTasks, kRows, kStop, kDone };

// An idle MPI loop naps this long between looks: OpenMPI's blocking calls spin, and the
// core is better left to the solving threads. Prefetching hides it from them.
constexpr auto kNap = std::chrono::milliseconds(1);

using Tasks = std::vector<std::uint64_t>;

unsigned thread_count(const SweepOptions& options) {
  return options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());
}

bool cancelled(const SweepOptions& options) { return options.cancel && options.cancel->load(); }

// The message that MPI_Iprobe found, received.
template <typename T>
std::vector<T> receive(const MPI_Status& status, MPI_Datatype type) {
  int count = 0;
  MPI_Get_count(&status, type, &count);
  std::vector<T> data(static_cast<std::size_t>(count));
  MPI_Recv(data.data(), count, type, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return data;
}

std::optional<MPI_Status> probe(int source) {
  int found = 0;
  MPI_Status status;
  MPI_Iprobe(source, MPI_ANY_TAG, MPI_COMM_WORLD, &found, &status);
  if (!found) return std::nullopt;
  return status;
}

// Rank 0's tasks still to hand out, in a fixed shuffled order of blocks of consecutive
// tasks. Shuffled, so that a chunk is a fair sample of the set rather than one costly
// family; by blocks, because neighbouring points of a spectrum run the same code paths
// and a thread solves a run of them faster (4 us of the reference's 50 us per point, by
// scripts/mpi_throughput.sh, when every task was shuffled alone). Taken from by rank 0's
// solving threads one at a time and by its main thread a chunk at a time.
class Dispenser {
 public:
  static constexpr std::size_t kBlock = 32;

  Dispenser(std::span<const std::size_t> todo, int ranks) : ranks_(ranks) {
    std::vector<std::span<const std::size_t>> blocks;
    for (std::size_t i = 0; i < todo.size(); i += kBlock)
      blocks.push_back(todo.subspan(i, std::min(kBlock, todo.size() - i)));
    std::mt19937_64 random(20090901);  // fixed, so that a rerun of the same job hands out the same chunks
    std::shuffle(blocks.begin(), blocks.end(), random);
    tasks_.reserve(todo.size());
    for (std::span<const std::size_t> block : blocks) tasks_.insert(tasks_.end(), block.begin(), block.end());
  }

  std::optional<std::size_t> take_one() {
    const std::lock_guard lock(mutex_);
    if (closed_ || next_ == tasks_.size()) return std::nullopt;
    return tasks_[next_++];
  }

  Tasks take(std::size_t wanted) {
    const std::lock_guard lock(mutex_);
    if (closed_ || wanted == 0) return {};
    const std::size_t left = tasks_.size() - next_;
    const std::size_t n = std::min(left, std::max(wanted, left / (4 * static_cast<std::size_t>(ranks_))));
    Tasks chunk(tasks_.begin() + static_cast<std::ptrdiff_t>(next_),
                tasks_.begin() + static_cast<std::ptrdiff_t>(next_ + n));
    next_ += n;
    return chunk;
  }

  void close() {
    const std::lock_guard lock(mutex_);
    closed_ = true;
  }

 private:
  std::mutex mutex_;
  int ranks_;
  std::vector<std::size_t> tasks_;
  std::size_t next_ = 0;
  bool closed_ = false;
};

// Messages on their way, sent without blocking. OpenMPI's blocking send can wait,
// spinning, until the receiver takes the message in, and the receiver looks only between
// naps: a rank's MPI thread would take the core from its solving threads, and rank 0 and a
// rank sending each other long messages at once would wait for each other for ever.
template <typename T>
class Outgoing {
 public:
  explicit Outgoing(MPI_Datatype type) : type_(type) {}
  Outgoing(const Outgoing&) = delete;
  Outgoing& operator=(const Outgoing&) = delete;
  ~Outgoing() { wait_all(); }

  void send(int to, int tag, std::vector<T> data) {
    sends_.push_back({MPI_REQUEST_NULL, std::move(data)});
    Send& s = sends_.back();
    MPI_Isend(s.data.data(), static_cast<int>(s.data.size()), type_, to, tag, MPI_COMM_WORLD, &s.request);
  }
  void forget_delivered() {
    std::erase_if(sends_, [](Send& s) {
      int delivered = 0;
      MPI_Test(&s.request, &delivered, MPI_STATUS_IGNORE);
      return delivered != 0;
    });
  }
  void wait_all() {
    for (Send& s : sends_) MPI_Wait(&s.request, MPI_STATUS_IGNORE);
    sends_.clear();
  }

 private:
  struct Send {
    MPI_Request request;
    std::vector<T> data;
  };
  MPI_Datatype type_;
  std::list<Send> sends_;  // a list: MPI holds the address of each request and buffer until it is done
};

std::vector<Row> lead(const Job& job, const CaseList& cases, std::span<const SweepRun> runs,
                      std::span<const std::size_t> todo, const SweepOptions& options) {
  const std::size_t total = cases.size() * runs.size();
  Dispenser dispenser(todo, job.size());
  std::mutex mutex;  // serialises the callbacks
  std::size_t done = 0;
  const auto report = [&](const Row& row) {
    const std::lock_guard lock(mutex);
    if (options.on_row) options.on_row(row);
    if (options.on_progress) options.on_progress(++done, total);
  };

  // Rank 0's own share, on threads of their own: the main thread stays free for MPI.
  SweepOptions local;
  local.threads = options.threads;
  local.cancel = options.cancel;
  local.pin_persistent = false;  // ranks share a node's cores (sweep/worker_cores.hpp)
  local.next_task = [&] { return dispenser.take_one(); };
  local.on_row = report;
  local.on_finished = options.on_finished;
  local.keep_rows = options.keep_rows;
  std::vector<Row> rows;  // rank 0's own, then those received
  std::atomic<bool> local_done{false};
  std::exception_ptr local_error;  // read only once local_done, which is set after it
  std::jthread solver([&] {
    try {
      rows = pb::run_sweep(cases, runs, local);
    } catch (...) {
      local_error = std::current_exception();
    }
    local_done = true;
  });

  std::vector<Row> received;
  Outgoing<std::uint64_t> outgoing(MPI_UINT64_T);
  std::vector<bool> told_no_more(static_cast<std::size_t>(job.size()), false);
  int active = job.size() - 1;  // ranks that may still send rows
  bool stopping = false;
  try {
    while ((active > 0 || !local_done) && !(local_done && local_error)) {
      if (!stopping && cancelled(options)) {
        stopping = true;
        dispenser.close();
        for (int r = 1; r < job.size(); ++r)
          if (!told_no_more[static_cast<std::size_t>(r)]) MPI_Send(nullptr, 0, MPI_INT, r, kStop, MPI_COMM_WORLD);
      }
      outgoing.forget_delivered();
      const std::optional<MPI_Status> status = probe(MPI_ANY_SOURCE);
      if (!status) {
        std::this_thread::sleep_for(kNap);
        continue;
      }
      const int from = status->MPI_SOURCE;
      if (status->MPI_TAG == kRequest) {
        const std::vector<int> wanted = receive<int>(*status, MPI_INT);
        Tasks chunk = dispenser.take(static_cast<std::size_t>(wanted.at(0)));
        if (chunk.empty()) told_no_more[static_cast<std::size_t>(from)] = true;
        outgoing.send(from, kTasks, std::move(chunk));
      } else if (status->MPI_TAG == kRows) {
        const std::vector<char> text = receive<char>(*status, MPI_CHAR);
        std::istringstream lines(std::string(text.begin(), text.end()));
        for (std::string line; read_csv_record(lines, line);) {
          Row row = parse_partial_line(line, true);
          row.input = cases[row.point];  // exactly, also in the columns the CSV leaves empty
          if (options.on_finished) options.on_finished(row);
          report(row);
          if (options.keep_rows) received.push_back(std::move(row));
        }
      } else if (status->MPI_TAG == kDone) {
        receive<int>(*status, MPI_INT);
        --active;
      }
    }
  } catch (...) {
    dispenser.close();  // so that rank 0's threads stop soon; the caller ends the job
    throw;
  }
  solver.join();
  if (local_error) std::rethrow_exception(local_error);
  rows.insert(rows.end(), std::make_move_iterator(received.begin()), std::make_move_iterator(received.end()));
  std::sort(rows.begin(), rows.end(), task_order);
  return rows;
}

void follow(const CaseList& cases, std::span<const SweepRun> runs, const SweepOptions& options) {
  const unsigned threads = thread_count(options);
  std::mutex mutex;  // guards the three below
  std::condition_variable arrived;
  std::deque<std::size_t> queue;
  bool no_more = false;  // the empty chunk came
  std::vector<std::string> outbox;

  SweepOptions local;
  local.threads = threads;
  local.cancel = options.cancel;
  local.pin_persistent = false;  // ranks share a node's cores (sweep/worker_cores.hpp)
  local.keep_rows = false;  // each row leaves as its line (the outbox below)
  local.next_task = [&]() -> std::optional<std::size_t> {
    std::unique_lock lock(mutex);
    // The cancel flag is set by a signal watcher that cannot notify: look again now and then.
    while (queue.empty() && !no_more && !cancelled(options)) arrived.wait_for(lock, std::chrono::milliseconds(50));
    if (queue.empty() || cancelled(options)) return std::nullopt;
    const std::size_t task = queue.front();
    queue.pop_front();
    return task;
  };
  local.on_row = [&](const Row& row) {
    std::string line = partial_line(row, true);
    const std::lock_guard lock(mutex);
    outbox.push_back(std::move(line));
  };
  std::atomic<bool> solving{true};
  std::exception_ptr error;
  std::jthread solver([&] {
    try {
      pb::run_sweep(cases, runs, local);
    } catch (...) {
      error = std::current_exception();
    }
    solving = false;
  });

  Outgoing<char> sent_rows(MPI_CHAR);
  bool asked = false;  // a request waits for its chunk
  bool done = false;   // the empty chunk came (the main thread's copy of no_more)
  for (;;) {
    bool busy = false;
    const bool still_solving = solving;
    if (!asked && !done) {
      const bool leaving = !still_solving || cancelled(options);
      std::size_t queued = 0;
      {
        const std::lock_guard lock(mutex);
        queued = queue.size();
      }
      if (leaving || queued <= threads) {
        const int wanted = leaving ? 0 : static_cast<int>(2 * threads);
        MPI_Send(&wanted, 1, MPI_INT, 0, kRequest, MPI_COMM_WORLD);
        asked = true;
      }
    }
    while (const std::optional<MPI_Status> status = probe(0)) {
      busy = true;
      if (status->MPI_TAG == kTasks) {
        const Tasks chunk = receive<std::uint64_t>(*status, MPI_UINT64_T);
        asked = false;
        done = chunk.empty();
        const std::lock_guard lock(mutex);
        queue.insert(queue.end(), chunk.begin(), chunk.end());
        no_more = done;
        arrived.notify_all();
      } else if (status->MPI_TAG == kStop) {
        receive<int>(*status, MPI_INT);
        const std::lock_guard lock(mutex);
        queue.clear();
      }
    }
    std::vector<std::string> lines;
    {
      const std::lock_guard lock(mutex);
      lines.swap(outbox);
    }
    sent_rows.forget_delivered();
    if (!lines.empty()) {  // the rows finished since the last look, as one message
      std::vector<char> batch;
      for (const std::string& line : lines) {
        batch.insert(batch.end(), line.begin(), line.end());
        batch.push_back('\n');
      }
      sent_rows.send(0, kRows, std::move(batch));
      busy = true;
    }
    // Every row was in the outbox before `solving` went false, and went out just above.
    if (!still_solving && done) break;
    if (!busy) std::this_thread::sleep_for(kNap);
  }
  sent_rows.wait_all();
  MPI_Send(nullptr, 0, MPI_INT, 0, kDone, MPI_COMM_WORLD);
  solver.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace

std::vector<Row> run_sweep(const Job& job, const CaseList& cases, std::span<const SweepRun> runs,
                           std::span<const std::size_t> todo, const SweepOptions& options) {
  if (job.rank() == 0) return lead(job, cases, runs, todo, options);
  follow(cases, runs, options);
  return {};
}

}  // namespace pb::mpi
