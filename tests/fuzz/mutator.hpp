#pragma once
// A small, seeded, deterministic mutator for the fuzz harness (issue 15).
//
// Deterministic on purpose: the suite runs it with a fixed seed, and every input is
// derived from (campaign seed, target, index) alone, so a failure printed as
// "seed S, input I" is rebuilt exactly by rerunning that one index, on any machine.
// That is why the random numbers come from splitmix64 and our own range reduction
// rather than <random>'s distributions, whose output the standard leaves to the library.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace pb::fuzz {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next();
  // Uniform enough for fuzzing in [0, n); n > 0.
  std::size_t below(std::size_t n) { return static_cast<std::size_t>(next() % n); }
  bool one_in(std::size_t n) { return below(n) == 0; }
  template <class T>
  const T& pick(const std::vector<T>& from) { return from[below(from.size())]; }

 private:
  std::uint64_t state_;
};

// The seed of input `index` of a campaign: independent of every other input, so that one
// input can be replayed alone.
std::uint64_t input_seed(std::uint64_t campaign_seed, std::string_view target, std::uint64_t index);

// Corpus files may hold generators instead of megabytes of text:
//   @REPEAT(text,count)@      text repeated count times
//   @SEQ(from,to,count)@      count numbers from `from` to `to`, evenly spaced, comma separated
// Anything else is copied as written.
std::string expand_generators(std::string_view text);

// The lines of a text (a last line without its newline included).
std::vector<std::string> split_lines(std::string_view text);

// One to four mutations of `lines`, each mutate(where) with `where` a place to insert a line
// at; returns whether one of them asked for the text to be cut short (as a half-written
// file is), which the caller does once the lines are text again.
template <class Mutation>
bool mutate_lines(std::vector<std::string>& lines, Rng& rng, Mutation mutate) {
  const std::size_t mutations = 1 + rng.below(4);
  bool truncate = false;
  for (std::size_t m = 0; m < mutations; ++m) {
    const std::size_t where = lines.empty() ? 0 : rng.below(lines.size() + 1);
    if (mutate(where)) truncate = true;
  }
  return truncate;
}

// The line mutations of both text mutators (mutate_toml, the record files'), `where` from
// mutate_lines: `line` put in at where; a line repeated at where; a line removed; a line of
// another of `seeds` put in at where. Each draws from rng what it needs, in that order.
void insert_line(std::vector<std::string>& lines, std::size_t where, std::string line);
void repeat_line(std::vector<std::string>& lines, std::size_t where, Rng& rng);
void remove_line(std::vector<std::string>& lines, Rng& rng);
void splice_line(std::vector<std::string>& lines, std::size_t where, const std::vector<std::string>& seeds, Rng& rng);

// TOML text (a case set or a settings list) changed by one to four mutations: a value
// replaced by an interesting one (empty, 0, -1, nan, inf, 1e308, 1e-320, 2^63-1, 2^40,
// huge strings, 3000-value lists, extreme grids), keys added (known ones and huge
// unknown ones) or duplicated or removed, lines spliced in from the other seeds, table
// headers added, bytes flipped or inserted, the text cut short (a partial file).
std::string mutate_toml(std::string_view seed, const std::vector<std::string>& all_seeds, Rng& rng);

// A command line (without the program name) changed by one to three mutations: a value
// replaced by an interesting one, a flag added with such a value, an argument removed or
// repeated, a flag renamed. `protected_flags` keep their values (the harness's own
// --time-limit, which makes a timeout mean "ignored its time limit").
std::vector<std::string> mutate_args(std::vector<std::string> args, const std::vector<std::string>& protected_flags,
                                     Rng& rng);

// The interesting values, as TOML and as command-line words.
const std::vector<std::string>& toml_values();
const std::vector<std::string>& arg_values();
const std::vector<std::string>& number_values();  // for flags that take a number

}  // namespace pb::fuzz
