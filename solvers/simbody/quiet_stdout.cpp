#include "solvers/simbody/quiet_stdout.hpp"

#include <cstdio>
#include <iostream>
#include <streambuf>

namespace pb::simbody {

namespace {

thread_local int t_quiet = 0;  // QuietScopes open on this thread
thread_local const std::function<void()>* t_watch = nullptr;  // the innermost scope's watch

// A write dropped: the watch sees it first.
void dropped() {
  if (t_watch) (*t_watch)();
}

// What std::cout wrote to before: every write outside a QuietScope goes on to it.
class FilterBuffer : public std::streambuf {
 public:
  explicit FilterBuffer(std::streambuf* next) : next_(next) {}
  std::streambuf* next() const { return next_; }

 protected:
  int_type overflow(int_type c) override {
    if (t_quiet) dropped();
    if (t_quiet || traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    return next_->sputc(traits_type::to_char_type(c));
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    if (!t_quiet) return next_->sputn(s, n);
    dropped();
    return n;
  }
  int sync() override { return t_quiet ? 0 : next_->pubsync(); }

 private:
  std::streambuf* next_;
};

ssize_t write_on(void* original, const char* data, size_t size) {
  if (t_quiet) {
    dropped();
    return static_cast<ssize_t>(size);
  }
  // Into the original FILE's own buffer, unflushed: a program's output keeps the buffering
  // it had (a write per printf made `solve_case | head -1` die of SIGPIPE, and every CSV line
  // a system call).
  const size_t written = std::fwrite(data, 1, size, static_cast<FILE*>(original));
  return written == 0 && size > 0 ? -1 : static_cast<ssize_t>(written);
}

// Installs both filters; puts the originals back at exit, before the standard streams'
// last flush, which would otherwise reach a destroyed buffer.
class Filters {
 public:
  Filters() : buffer_(std::cout.rdbuf()), original_(stdout) {
    cookie_io_functions_t io{};
    io.write = &write_on;
    filtered_ = fopencookie(original_, "w", io);
    if (!filtered_) return;
    std::setvbuf(filtered_, nullptr, _IONBF, 0);
    std::fflush(original_);
    stdout = filtered_;
    std::cout.rdbuf(&buffer_);
  }
  ~Filters() {
    if (!filtered_) return;
    std::cout.rdbuf(buffer_.next());
    stdout = original_;
    std::fclose(filtered_);
  }
  Filters(const Filters&) = delete;
  Filters& operator=(const Filters&) = delete;
  bool installed() const { return filtered_ != nullptr; }

 private:
  FilterBuffer buffer_;
  FILE* original_;
  FILE* filtered_ = nullptr;
};

const Filters g_filters;  // before main, after <iostream> made std::cout (this file includes it)

}  // namespace

QuietScope::QuietScope(const std::function<void()>* watch) : outer_(t_watch) {
  ++t_quiet;
  if (watch) t_watch = watch;
}
QuietScope::~QuietScope() {
  --t_quiet;
  t_watch = outer_;
}

bool stdout_filtered() { return g_filters.installed(); }

}  // namespace pb::simbody
