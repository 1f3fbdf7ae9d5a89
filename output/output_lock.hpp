#pragma once
// One sweep at a time per output. Two sweeps on one --out would both append to its partial
// file and rewrite it, and rows of one would be lost in the other's rename. The leader
// takes an exclusive flock on "<out>.lock" ("poundbench-<command>.lock" in the current
// directory when the output is stdout) while it checks its inputs, before it reads the
// partial file, and keeps it until the outputs are written and the partial file is
// removed. A second sweep is refused as a bad input naming the holder's pid, which the
// lock file holds.
//
// The lock file is removed when the lock is released (destructor, or release() before
// _Exit). The kernel releases the flock itself on any exit, a crash or SIGKILL included;
// the file such an exit leaves is taken over by the next sweep, and the next release
// removes it. A sweep that opened the file just before its holder removed it finds it
// gone once it holds the lock, and starts again on a new file, so two sweeps never hold
// locks on two files of one name.

#include <string>
#include <string_view>

namespace pb::app {

// Where the lock of a sweep's output is: "<out>.lock", or "poundbench-<command>.lock"
// when the output is stdout (empty `out`).
std::string lock_file_name(const std::string& out, std::string_view command);

class OutputLock {
 public:
  OutputLock() = default;  // holds nothing: a process that writes no output
  // Takes the lock or throws BadInput ("<what>: another sweep (pid N) ..."); `what` names
  // the output for the message. Throws BadInput too when the file cannot be created.
  OutputLock(std::string lock_file, std::string_view what);
  OutputLock(OutputLock&& other) noexcept;
  OutputLock& operator=(OutputLock&& other) noexcept;
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;
  ~OutputLock();

  bool held() const { return fd_ >= 0; }
  // Removes the lock file and releases the lock; safe to call twice, and before _Exit.
  void release() noexcept;

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace pb::app
