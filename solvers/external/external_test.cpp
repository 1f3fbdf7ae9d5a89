// The external solver (solvers/external/, docs/external.md): the command's quoting rules,
// the protocol carrying a case and an answer without loss, and every way a program can go
// wrong turned into a row: it cannot start, it exits non-zero or on a signal, its answer is
// not one, it passes the time limit, it is stopped, it does not read its input. The shared
// checks (statuses, threads, monitor, smoke set) are the solver contract's, with
// `poundbench adapter --solver moreau-jean` as the program (solver_contract_test.cpp).

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "cases/case_set.hpp"
#include "cases/system.hpp"
#include "programs/command_words.hpp"
#include "solvers/external/external.hpp"
#include "programs/process.hpp"
#include "programs/protocol.hpp"
#include "solvers/moreau_jean/moreau_jean.hpp"
#include "sweep/sweep.hpp"
#include "kit/testing.hpp"
#include "solvers/registry.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace external_tests {

using test::make_case;

constexpr const char* kAdapter = POUNDBENCH_EXE " adapter --solver moreau-jean";

System pair_case() { return make_system(make_case(Scene::pair, PulseShape::sine, 1.0, 0.5, 0.5)); }

Settings with_command(const std::string& command) {
  Settings s;
  s.command = command;
  return s;
}

// A program that answers `answer` (one line of JSON, no single quotes) whatever it is asked.
std::string answering(const std::string& answer) { return "sh -c 'cat > /dev/null; echo \"$0\"' '" + answer + "'"; }

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// ---------------------------------------------------------------- the command

TEST(ExternalCommand, WordsFollowTheQuotingRules) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"python3 adapter.py", {"python3", "adapter.py"}},
      {"  a \t b\nc  ", {"a", "b", "c"}},
      {"prog 'two words' \"and \\\"quoted\\\"\"", {"prog", "two words", "and \"quoted\""}},
      {"prog 'it''s' a'b c'\"d\"", {"prog", "its", "ab cd"}},
      {"prog '' \"\"", {"prog", "", ""}},
      {"prog a\\ b \\'c", {"prog", "a b", "'c"}},
      {"prog \"back\\\\slash \\n\"", {"prog", "back\\slash \\n"}},
      {"prog $HOME *.py | wc > out ; rm", {"prog", "$HOME", "*.py", "|", "wc", ">", "out", ";", "rm"}},
  };
  for (const auto& [text, words] : cases) {
    const programs::CommandWords split = programs::split_command(text);
    EXPECT_EQ(split.error, "") << text;
    EXPECT_EQ(split.words, words) << text;
  }
  for (const auto& [text, error] : std::vector<std::pair<std::string, std::string>>{
           {"prog 'open", "command: a single quote (') is not closed"},
           {"prog \"open", "command: a double quote (\") is not closed"},
           {"prog end\\", "command: ends in a backslash (\\ escapes the next character)"},
           {"   ", "command: no program (give the program and its arguments, e.g. \"python3 adapter.py\")"},
           {"'' arg", "command: the program's name is empty"}}) {
    const programs::CommandWords split = programs::split_command(text);
    EXPECT_EQ(split.error, error) << text;
    EXPECT_TRUE(split.words.empty()) << text;
  }
}

TEST(ExternalCommand, CheckRefusesAMissingOrUnknownProgramAndBadQuoting) {
  EXPECT_EQ(external::check(Settings{}).rfind("command: required by solver external", 0), 0u);
  EXPECT_EQ(external::check(with_command("no-such-program-xyz --flag")),
            "command: program 'no-such-program-xyz' not found in PATH");
  EXPECT_EQ(external::check(with_command("/no/such/file")), "command: '/no/such/file' is not an executable file");
  EXPECT_EQ(external::check(with_command("sh -c 'x")), "command: a single quote (') is not closed");
  EXPECT_EQ(external::check(with_command(kAdapter)), "");
  Settings both = with_command(kAdapter);
  both.steps = 8;
  both.wh = 1.0;
  EXPECT_EQ(external::check(both), "wh: give steps or wh, not both");
}

// ---------------------------------------------------------------- the protocol

// poundbench answering as an external program gives the in-process answer bit for bit: the
// documents carry every number exactly (the smoke set through moreau-jean at N = 64, and the
// reference on its wall cases).
TEST(ExternalProtocol, AdapterGivesTheInProcessAnswerBitForBit) {
  const CaseSet set = load_case_set(std::string(POUNDBENCH_SOURCE_DIR) + "/cases/sets/smoke.toml");
  Settings st = with_command(kAdapter);
  st.steps = 64;
  Settings direct;
  direct.steps = 64;
  int compared = 0;
  for (std::size_t i = 0; i < set.cases.size(); i += 4) {
    const System s = make_system(set.cases[i]);
    const Result a = moreau_jean::solve(s, direct), b = external::solve(s, st);
    ASSERT_EQ(b.status, a.status) << i << ": " << b.message;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(b.pi1), std::bit_cast<std::uint64_t>(a.pi1)) << i;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(b.t_max), std::bit_cast<std::uint64_t>(a.t_max)) << i;
    EXPECT_EQ(b.impacts, a.impacts) << i;
    EXPECT_EQ(b.contact_phases, a.contact_phases) << i;
    EXPECT_EQ(b.steps, a.steps) << i;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(b.min_gap), std::bit_cast<std::uint64_t>(a.min_gap)) << i;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(b.step), std::bit_cast<std::uint64_t>(a.step)) << i;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(b.energy_excess), std::bit_cast<std::uint64_t>(a.energy_excess)) << i;
    ++compared;
  }
  EXPECT_EQ(compared, 10);
}

TEST(ExternalProtocol, CaseDocumentReadsBackToTheSameSystem) {
  Case c = make_case(Scene::chain, PulseShape::cosine, 0.7, 1.3, 0.25);
  c.bodies = 5;
  c.kick = 0.5;
  c.directivity = Directivity::reverse;
  const System s = make_system(c);
  Settings st;
  st.steps = 32;
  st.step_cap = 1000;
  st.time_limit = 2.5;
  st.history_samples = 10;
  const programs::CaseRead back = programs::read_case(programs::case_document(s, st).text);
  EXPECT_EQ(case_key(case_of(back.system)), case_key(case_of(s)));
  EXPECT_EQ(back.system.u_start, s.u_start);
  EXPECT_EQ(back.system.v_start, s.v_start);
  EXPECT_EQ(back.system.t_end, s.t_end);
  EXPECT_EQ(back.system.t_min, s.t_min);
  EXPECT_EQ(back.settings.steps, 32);
  EXPECT_EQ(back.settings.step_cap, 1000);
  EXPECT_EQ(back.settings.time_limit, 2.5);
  EXPECT_EQ(back.settings.history_samples, 10);
}

// A program may answer with the history of u0 alone: Pi1 and its time are taken from it
// (Pi1 = max |u0| over a_p / w_p^2; here a_p = 1, w_p = 1), and `run --history` gets its u0.
TEST(ExternalProtocol, Pi1IsTakenFromAHistoryOfU0) {
  Settings st = with_command(answering(R"({"version":1,"status":"ok","history":{"t":[0,1,2,3],"u0":[0,0.5,-1.25,0.75]}})"));
  st.history_samples = 4;
  const System s = pair_case();
  const Result r = external::solve(s, st);
  ASSERT_EQ(r.status, Status::ok) << r.message;
  EXPECT_DOUBLE_EQ(r.pi1, 1.25);
  EXPECT_DOUBLE_EQ(r.t_max, 2.0);
  ASSERT_EQ(r.history.rows(), 4u);
  EXPECT_EQ(r.history.data[static_cast<std::size_t>(2 * r.history.row_size() + 1 + s.ref)], -1.25);
  EXPECT_TRUE(std::isnan(r.history.data[static_cast<std::size_t>(2 * r.history.row_size() + 1 + 1 - s.ref)]))
      << "u of the other body: not in a version 1 answer";
}

// ---------------------------------------------------------------- a program gone wrong

TEST(ExternalFailures, BadAnswersAreFailedRowsNamingTheField) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"", "answer: stdout: empty (one JSON document is expected)"},
      {"not json", "answer: stdout: not one JSON document"},
      {"[1, 2]", "answer: stdout: must be a JSON object"},
      {R"({"status":"ok","pi1":1})", "answer: version: missing"},
      {R"({"version":2,"status":"ok","pi1":1})", "answer: version: must be 1 (it is 2)"},
      {R"({"version":1,"pi1":1})", "answer: status: missing"},
      {R"({"version":1,"status":"great"})", "answer: status: must be one of ok, diverged, nan, step_cap, time-limit, failed"},
      {R"({"version":1,"status":"ok"})", "answer: pi1: status ok needs pi1 >= 0, or a history of u0 to take it from"},
      {R"({"version":1,"status":"ok","pi1":-1})", "answer: pi1: status ok needs pi1 >= 0"},
      {R"({"version":1,"status":"ok","pi1":"2"})", "answer: pi1: must be a number"},
      {R"({"version":1,"status":"ok","pi1":1,"impacts":2.5})", "answer: impacts: must be a whole number >= 0"},
      {R"({"version":1,"status":"ok","pi_1":1})", "answer: pi_1: unknown key"},
      {R"({"version":1,"status":"ok","history":{"t":[0,1],"u0":[1]}})", "answer: history: t and u0 must have the same length"},
  };
  for (const auto& [answer, message] : cases) {
    const Result r = external::solve(pair_case(), with_command(answering(answer)));
    EXPECT_EQ(r.status, Status::failed) << answer;
    EXPECT_EQ(r.message.rfind(message, 0), 0u) << answer << " gave: " << r.message;
    EXPECT_TRUE(std::isnan(r.pi1)) << answer;
  }
}

TEST(ExternalFailures, NonZeroExitIsAFailedRowWithStderrsLastLines) {
  const Result r = external::solve(
      pair_case(), with_command("sh -c 'cat > /dev/null; for i in 1 2 3 4 5 6 7; do echo line $i >&2; done; exit 3'"));
  EXPECT_EQ(r.status, Status::failed);
  EXPECT_EQ(r.message, "the program exited with code 3; stderr: line 3 | line 4 | line 5 | line 6 | line 7");
}

TEST(ExternalFailures, ASignalIsAFailedRowNamingIt) {
  const Result r = external::solve(pair_case(), with_command("sh -c 'echo dying >&2; kill -SEGV $$'"));
  EXPECT_EQ(r.status, Status::failed);
  EXPECT_EQ(r.message, "the program was ended by signal 11 (SIGSEGV); stderr: dying");
}

TEST(ExternalFailures, AProgramThatCannotStartIsAFailedRow) {
  const Result r = external::solve(pair_case(), with_command("/no/such/program"));
  EXPECT_EQ(r.status, Status::failed);
  EXPECT_EQ(r.message, "command: cannot start /no/such/program: No such file or directory");
}

// Ended at the time limit plus its grace (kGraceSeconds), whatever the program does: one
// that sleeps, and a script whose child sleeps with the pipes open (its group is ended).
TEST(ExternalFailures, APastTheTimeLimitProgramIsEndedWithItsGroup) {
  for (const char* command : {"sleep 30", "sh -c 'sleep 30 & sleep 40'"}) {
    Settings st = with_command(command);
    st.time_limit = 0.1;
    const auto start = std::chrono::steady_clock::now();
    const Result r = external::solve(pair_case(), st);
    const double elapsed = seconds_since(start);
    EXPECT_EQ(r.status, Status::time_limit) << command;
    EXPECT_EQ(r.message.rfind("more than 0.1 s of wall time: the program had not answered 0.5 s after it", 0), 0u)
        << r.message;
    EXPECT_GT(elapsed, 0.6) << command;
    EXPECT_LT(elapsed, 10.0) << command;  // 0.6 s here; 30 s if the group outlived its limit
  }
}

TEST(ExternalFailures, StopFlagEndsAProgramWithinMilliseconds) {
  std::atomic<bool> stop{false};
  Settings st = with_command("sleep 30");
  st.stop = &stop;
  std::jthread stopper([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    stop = true;
  });
  const auto start = std::chrono::steady_clock::now();
  const Result r = external::solve(pair_case(), st);
  const double elapsed = seconds_since(start);
  EXPECT_EQ(r.status, Status::time_limit);
  EXPECT_NE(r.message.find("stopped"), std::string::npos) << r.message;
  EXPECT_LT(elapsed, 10.0);  // the flag is looked at every 10 ms; 30 s if it were not
}

// A program that closes its stdin unread while poundbench is still writing (a 1000-body
// chain's case is 85 kB, more than a pipe holds): the write fails with EPIPE and no
// SIGPIPE reaches poundbench; the program's answer stands.
TEST(ExternalFailures, AProgramThatDoesNotReadItsInputDoesNotKillPoundbench) {
  Case c = make_case(Scene::chain, PulseShape::sine, 1.0, 1.0, 0.5);
  c.bodies = 1000;
  const System s = make_system(c);
  ASSERT_GT(programs::case_document(s, Settings{}).text.size(), 65'536u);  // Linux's pipe buffer
  const Result r = external::solve(s, with_command("sh -c 'exec 0<&-; echo \"{\\\"version\\\":1,\\\"status\\\":\\\"ok\\\",\\\"pi1\\\":2}\"'"));
  EXPECT_EQ(r.status, Status::ok) << r.message;
  EXPECT_EQ(r.pi1, 2.0);
}

// ---------------------------------------------------------------- issue 46

// A program that writes `answer` (one line, no single quotes) whatever it is asked, with
// printf: no shell's echo reads its backslashes.
std::string printing(const std::string& answer) {
  return "sh -c 'cat > /dev/null; printf \"%s\\n\" \"$0\"' '" + answer + "'";
}

bool printable_utf8(const std::string& text) { return programs::printable_line(text) == text; }

TEST(ExternalProtocol, PrintableLineReplacesWhatIsNotUtf8AndEveryControlCharacter) {
  using programs::printable_line;
  EXPECT_EQ(printable_line("plain ascii, \xC3\xA9t\xC3\xA9, \xE2\x82\xAC, \xF0\x9F\x98\x80"),
            "plain ascii, \xC3\xA9t\xC3\xA9, \xE2\x82\xAC, \xF0\x9F\x98\x80");
  EXPECT_EQ(printable_line("a\nb\rc\td\x1b[31me\x7f"), "a?b?c?d?[31me?");
  EXPECT_EQ(printable_line(std::string("nul\0end", 7)), "nul?end");
  const std::string fffd = "\xEF\xBF\xBD";
  EXPECT_EQ(printable_line("\xff\xfe"), fffd + fffd);
  EXPECT_EQ(printable_line("\xC3("), fffd + "(");          // a lead byte without its continuation
  EXPECT_EQ(printable_line("cut \xE2\x82"), "cut " + fffd + fffd);  // a sequence cut short
  EXPECT_EQ(printable_line("\xC0\xAF"), fffd + fffd);     // an overlong '/'
  EXPECT_EQ(printable_line("\xED\xA0\x80"), fffd + fffd + fffd);  // a surrogate
  EXPECT_EQ(printable_line("\xF4\x90\x80\x80"), fffd + fffd + fffd + fffd);  // past U+10FFFF
  // C1 (U+0085, a line end to some readers), U+2028, U+2029, a right-to-left override, U+FEFF.
  EXPECT_EQ(printable_line("\xC2\x85|\xE2\x80\xA8|\xE2\x80\xA9|\xE2\x80\xAE|\xEF\xBB\xBF"), "?|?|?|?|?");
}

// Issue 46: an answer's message and a program's stderr reached the rows as they were, and
// `report` then refused poundbench's own output.
TEST(ExternalFailures, WhatAProgramWritesReachesTheRowAsOnePrintableLine) {
  const Result answered = external::solve(
      pair_case(), with_command(printing(R"({"version":1,"status":"failed","message":"a\u001b[31mb\u0000c\u2028d\u0085e\nf"})")));
  EXPECT_EQ(answered.status, Status::failed);
  EXPECT_EQ(answered.message, "a?[31mb?c?d?e?f");
  const Result failed = external::solve(
      pair_case(), with_command("sh -c 'cat > /dev/null; printf \"not utf-8: \\377\\376 \\033[2J\\n\" >&2; exit 3'"));
  EXPECT_EQ(failed.status, Status::failed);
  EXPECT_EQ(failed.message, "the program exited with code 3; stderr: not utf-8: \xEF\xBF\xBD\xEF\xBF\xBD ?[2J");
  // A line that is no answer is quoted in the message: its bytes too.
  const Result quoted = external::solve(pair_case(), with_command("sh -c 'cat > /dev/null; printf \"\\377\\033\"'"));
  EXPECT_EQ(quoted.status, Status::failed);
  EXPECT_TRUE(printable_utf8(quoted.message)) << quoted.message;
}

TEST(ExternalProtocol, AReadyLineIsParsedAndItsReadyMustBeTrue) {
  EXPECT_EQ(programs::ready_line_problem(R"({"version": 1, "ready": true})"), "");
  EXPECT_EQ(programs::ready_line_problem(R"({"ready":true,"version":1,"program":"mine"})"), "");
  for (const char* line : {R"({"version": 1, "ready": false})", R"("ready")", R"({"version": 1, "ready": "true"})",
                           R"({"version": 1, "ready": 1})", R"({"ready": true})", R"({"version": 2, "ready": true})",
                           R"({"version": 1, "ready": true, "ready": false})", "ready", "", "{\"ready\": true\x1b"}) {
    const std::string why = programs::ready_line_problem(line);
    EXPECT_EQ(why.rfind(R"(its first line must be {"version": 1, "ready": true} (persistent mode), not ')", 0), 0u)
        << line << " gave: " << why;
    EXPECT_TRUE(why.find('\n') == std::string::npos) << why;
  }
}

// The duplicate-key check was quadratic: 120,000 keys took 11.9 s to check. 400,000 (quadratic:
// about 130 s) are refused for their first unknown key, long before a 60 s deadline (linear: well
// under a second), and a key given twice among them is still found.
TEST(ExternalProtocol, DuplicateKeysAreFoundInLinearTime) {
  std::string many = R"({"version":1,"status":"ok","pi1":1)";
  for (int i = 0; i < 400'000; ++i) many += ",\"k" + std::to_string(i) + "\":0";
  const auto in_a_minute = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  Result r;
  EXPECT_EQ(programs::read_answer(many + "}", pair_case(), Settings{}, r, in_a_minute),
            "answer: k0: unknown key (docs/external.md lists an answer's keys)");
  EXPECT_EQ(programs::read_answer(many + ",\"k399999\":1}", pair_case(), Settings{}, r, in_a_minute),
            "answer: stdout: key \"k399999\" given twice in one object");
}

// `--time-limit 1` was quoted as "more than 0.999999 s": a sweep gives each solve of a point what is
// left of the point's limit, and the messages quoted that.
TEST(ExternalFailures, TimeLimitMessagesQuoteTheLimitAsGiven) {
  const Case c = make_case(Scene::pair, PulseShape::sine, 1.0, 0.5, 0.5);
  Settings program = with_command("sleep 30");
  program.time_limit = 0.3000001;  // more digits than a stream prints by default
  const Row ended = run_point(c, 0, *find_solver("external"), program);
  EXPECT_EQ(ended.result.status, Status::time_limit);
  EXPECT_EQ(ended.result.message.rfind("more than 0.3000001 s of wall time: the program had not answered", 0), 0u)
      << ended.result.message;
  Settings stepper;
  stepper.steps = 10'000'000;  // 8e7 steps: seconds, under the step cap
  stepper.time_limit = 0.3000001;
  const Row stepped = run_point(c, 0, *find_solver("moreau-jean"), stepper);
  EXPECT_EQ(stepped.result.status, Status::time_limit);
  EXPECT_EQ(stepped.result.message.rfind("more than 0.3000001 s of wall time at t = ", 0), 0u) << stepped.result.message;
}

// A line already waiting on a persistent program's stdout when a case is to be sent (here the
// second of two lines it wrote to the first case, there before the second case is sent) is not
// that case's answer: the point fails saying why, and the next point starts the program again.
TEST(ExternalPersistent, ALineWaitingBeforeTheCaseIsSentIsNoAnswer) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("pb-persistent-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string marker = (dir / "second-line-written").string();
  const std::string script = (dir / "twice.sh").string();
  std::ofstream(script) << "echo '{\"version\": 1, \"ready\": true}'\n"
                           "while read -r line; do\n"
                           "  echo '{\"version\": 1, \"status\": \"ok\", \"pi1\": 1}'\n"
                           "  echo '{\"version\": 1, \"status\": \"ok\", \"pi1\": 99}'\n"
                           "  touch " + marker + "\n"
                           "done\n";
  Settings st = with_command("sh " + script);
  st.variant = std::string(external::kPersistent);
  st.time_limit = 60;
  const Result first = external::solve(pair_case(), st);
  EXPECT_EQ(first.status, Status::ok) << first.message;
  EXPECT_EQ(first.pi1, 1.0);
  for (int waited = 0; !std::filesystem::exists(marker) && waited < 6000; ++waited)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  const Result second = external::solve(pair_case(), st);
  EXPECT_EQ(second.status, Status::failed);
  EXPECT_EQ(second.message, R"(the program wrote '{"version": 1, "status": "ok", "pi1": 99}' to stdout before this )"
                            "case was sent (persistent mode: one answer line per case line); it was ended (the next "
                            "point starts it again)");
  const Result third = external::solve(pair_case(), st);
  EXPECT_EQ(third.status, Status::ok) << third.message;
  EXPECT_EQ(third.pi1, 1.0);
  programs::end_thread_sessions();
  std::filesystem::remove_all(dir);
}

// ---------------------------------------------------------------- processes and descriptors

int open_descriptors() {
  int n = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator("/proc/self/fd")) ++n;
  return n;
}

// The program starts with its three standard streams and nothing else, even a descriptor
// this process opened without close-on-exec; after a sweep of 16 runs on 4 threads, this
// process holds the descriptors it held before and has no child left, zombie or not.
TEST(ExternalProcesses, NoDescriptorLeaksAndNoZombies) {
  const int null = ::open("/dev/null", O_RDONLY);
  const int leaky = ::fcntl(null, F_DUPFD, 200);  // not close-on-exec
  ::close(null);
  ASSERT_GE(leaky, 200);
  const Result listed = external::solve(pair_case(), with_command("sh -c 'exec ls /proc/self/fd >&2'"));
  ::close(leaky);
  // 3 is ls's own, the directory it lists.
  EXPECT_EQ(listed.message.rfind("answer: stdout: empty (one JSON document is expected); stderr: 0 | 1 | 2 | 3", 0), 0u)
      << listed.message;

  const int before = open_descriptors();
  std::vector<Case> cases;
  for (double pi2 : {0.5, 0.75, 1.0, 1.5}) {
    cases.push_back(make_case(Scene::pair, PulseShape::sine, pi2, 0.5, 0.5));
    cases.push_back(make_case(Scene::wall, PulseShape::cosine, pi2, 1.0, 0.5));
  }
  Settings st = with_command(kAdapter);
  st.steps = 32;
  SweepOptions options;
  options.threads = 4;
  const std::vector<Row> rows = run_sweep(cases, *find_solver("external"), st, options);
  ASSERT_EQ(rows.size(), cases.size());
  for (const Row& row : rows) EXPECT_EQ(row.result.status, Status::ok) << row.result.message;
  EXPECT_EQ(open_descriptors(), before);
  errno = 0;
  EXPECT_EQ(::waitpid(-1, nullptr, WNOHANG), -1);
  EXPECT_EQ(errno, ECHILD) << "a child is left";
}

// A sweep's CPU time of an external point is the program's (the thread's own clock sees
// only the pipes): a program that spins for ~0.2 s of CPU is a row of at least 0.1 s.
TEST(ExternalProcesses, RowCpuSecondsIncludeTheProgramsCpu) {
  Settings st = with_command(
      "sh -c 'i=0; while [ $i -lt 100000 ]; do i=$((i+1)); done; echo \"{\\\"version\\\":1,\\\"status\\\":\\\"ok\\\",\\\"pi1\\\":1}\"'");
  st.monitor = false;
  const Row row = run_point(make_case(Scene::pair, PulseShape::sine, 1.0, 0.5, 0.5), 0, *find_solver("external"), st);
  ASSERT_EQ(row.result.status, Status::ok) << row.result.message;
  RecordProperty("cpu_seconds", test::sci(row.cpu_seconds));
  EXPECT_GT(row.cpu_seconds, 0.05);
  EXPECT_LE(row.cpu_seconds, row.seconds * 1.1 + 0.01);
}

// ---------------------------------------------------------------- the command line

}  // namespace external_tests
}  // namespace pb
