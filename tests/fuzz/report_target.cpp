#include "tests/fuzz/report_target.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <fstream>
#include <map>
#include <set>

#include "tests/fuzz/harness.hpp"

namespace pb::fuzz {

namespace {

// ---------------------------------------------------------------- the input's form

struct ReportFiles {
  std::string study_name = "s.csv", study;
  std::optional<std::string> points_name;  // none: no --points
  std::string points;
  std::string out = "report";
  bool must_refuse = false;  // a value outside its column's domain is in a row the report reads
};

// A file name the harness writes, inside the run's folder: a mutated or hand-written name
// that climbs out (an absolute path, "..") is taken as the default.
std::string inside(const std::string& name, const std::string& fallback) {
  if (name.empty() || name.front() == '/' || name.find("..") != std::string::npos) return fallback;
  return name;
}

ReportFiles parse_files(const std::string& text) {
  ReportFiles f;
  std::string* into = nullptr;
  for (const std::string& line : split_lines(text)) {
    if (line.rfind("@@ study ", 0) == 0) {
      f.study_name = inside(line.substr(9), "s.csv");
      into = &f.study;
    } else if (line.rfind("@@ points ", 0) == 0) {
      f.points_name = inside(line.substr(10), "p.csv");
      into = &f.points;
    } else if (line.rfind("@@ out ", 0) == 0) {
      f.out = line.substr(7) == "." ? "." : inside(line.substr(7), "report");
      into = nullptr;
    } else if (line == "@@ expect 2") {
      f.must_refuse = true;
      into = nullptr;
    } else if (into != nullptr) {
      *into += line + '\n';
    }
  }
  return f;
}

std::string files_text(const ReportFiles& f) {
  std::string text = "@@ study " + f.study_name + '\n' + f.study;
  if (f.points_name) text += "@@ points " + *f.points_name + '\n' + f.points;
  return text + "@@ out " + f.out + '\n' + (f.must_refuse ? "@@ expect 2\n" : "");
}

// ---------------------------------------------------------------- CSV, for the mutations

using Table = std::vector<std::vector<std::string>>;

Table parse_csv(std::string_view text) {
  Table rows(1);
  std::string field;
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') field += text[++i];
      else if (c == '"') quoted = false;
      else field += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      rows.back().push_back(std::move(field));
      field.clear();
    } else if (c == '\n') {
      rows.back().push_back(std::move(field));
      field.clear();
      rows.emplace_back();
    } else {
      field += c;
    }
  }
  if (!field.empty() || !rows.back().empty()) rows.back().push_back(std::move(field));
  if (rows.back().empty()) rows.pop_back();
  return rows;
}

std::string csv_text(const Table& rows) {
  std::string text;
  for (const auto& row : rows) {
    for (std::size_t i = 0; i < row.size(); ++i) {
      const std::string& v = row[i];
      if (i) text += ',';
      if (v.find_first_of(",\"\n\r") == std::string::npos) {
        text += v;
        continue;
      }
      text += '"';
      for (char c : v) text += c == '"' ? std::string("\"\"") : std::string(1, c);
      text += '"';
    }
    text += '\n';
  }
  return text;
}

// ---------------------------------------------------------------- the values

const std::vector<std::string>& name_values() {
  static const std::vector<std::string> v = {
      "a|b", "a/b", "a\\b", "../up", "/abs", "a\nb", "a\r\nb", "a,b", "\"q\"", "[x](y)", "![i](j)",
      "<script>alert(1)</script>", "", " ", ".", "..", "#", "`", "**", "\xc3\xbc", "\xff\xfe", "\t",
      "a|b/c\nd", std::string(5000, 'L'), std::string(100'000, 'N')};
  return v;
}

const std::vector<std::string>& number_strings() {
  static const std::vector<std::string> v = {"-1", "nan", "NaN", "inf", "-inf", "1e308", "-1e308", "1e-320", "0",
                                             "-0", "", "x", "1,5", "9223372036854775808", "1e999", " 1", "0x10",
                                             "1.5", "-1e-6", "+inf", "Infinity"};
  return v;
}

const std::vector<std::string>& settings_values() {
  static const std::vector<std::string> v = [] {
    std::vector<std::string> values = {"{", "[]", "{}", "\"x\"", "null", "{\"steps\": 1.5}", "{\"steps\": 0}",
                                       "{\"steps\": 1e400}", "{\"steps\": NaN}", "{\"steps\": \"16\"}",
                                       "{\"theta\": \"x\"}", "{\"contact\": []}", "{\"stiffness\": null}",
                                       "{\"wh\": \"x\"}", "{\"steps\": 16, \"steps\": 64}", "{\"steps\": true}"};
    values.push_back(std::string(100'000, '[') + std::string(100'000, ']'));
    return values;
  }();
  return v;
}

const std::set<std::string>& name_columns() {
  static const std::set<std::string> c = {"family", "solver", "variant", "scene", "pulse", "directivity", "status",
                                          "message", "cost", "resolved", "unresolved", "finite", "energy"};
  return c;
}

// A value for `column`: of its own kind mostly, of any kind sometimes.
const std::string& value_for(const std::string& column, Rng& rng) {
  const std::size_t kind = rng.one_in(4) ? rng.below(3)
                           : column == "settings"            ? 2
                           : name_columns().contains(column) ? 0
                                                             : 1;
  return rng.pick(kind == 0 ? name_values() : kind == 1 ? number_strings() : settings_values());
}

// ---------------------------------------------------------------- the mutations

// A family (or a setting) renamed the same in both files, so that the study still holds
// together and the name reaches the answer, the figures and the page.
void rename_everywhere(ReportFiles& f, const std::string& column, Rng& rng) {
  Table study = parse_csv(f.study), points = parse_csv(f.points);
  if (study.size() < 2) return;
  const auto at = std::find(study[0].begin(), study[0].end(), column);
  if (at == study[0].end()) return;
  const std::size_t col = static_cast<std::size_t>(at - study[0].begin());
  const auto& row = study[1 + rng.below(study.size() - 1)];
  if (col >= row.size()) return;
  const std::string old = row[col];
  const std::string& now = column == "settings" ? rng.pick(settings_values()) : rng.pick(name_values());
  for (Table* t : {&study, &points}) {
    if (t->empty()) continue;
    const auto c = std::find((*t)[0].begin(), (*t)[0].end(), column);
    if (c == (*t)[0].end()) continue;
    const std::size_t k = static_cast<std::size_t>(c - (*t)[0].begin());
    for (std::size_t i = 1; i < t->size(); ++i)
      if (k < (*t)[i].size() && (*t)[i][k] == old) (*t)[i][k] = now;
  }
  f.study = csv_text(study);
  if (f.points_name) f.points = csv_text(points);
}

// Whether `value` is outside the domain of `column` whatever the row (docs/cli.md, `poundbench
// report`): the oracle of the campaign's "a bad input must exit 2", kept to values that are
// bad in every numeric column the report reads.
bool outside_domain(const std::string& column, const std::string& value) {
  static const std::set<std::string> numeric = {"points", "failed", "err_median", "err_p95", "err_max",
                                                "cpu_median_s", "runs", "ok", "point", "pi2", "pi1",
                                                "cpu_seconds"};
  static const std::set<std::string> bad = {"-1", "nan", "NaN", "x", "1,5", "-1e-6", "-inf"};
  return numeric.contains(column) && bad.contains(value);
}

// One mutation of a CSV file; returns whether it put a value outside its domain into a row
// the report reads (then the input must be refused, until another mutation changes it).
bool mutate_table(std::string& text, Rng& rng) {
  Table t = parse_csv(text);
  if (t.empty()) return false;
  const std::size_t r = t.size() > 1 && !rng.one_in(10) ? 1 + rng.below(t.size() - 1) : 0;
  bool bad = false;
  switch (rng.below(5)) {
    case 0:
    case 1: {  // a field
      if (t[r].empty()) break;
      const std::size_t c = rng.below(t[r].size());
      const std::string column = c < t[0].size() ? t[0][c] : "";
      t[r][c] = value_for(column, rng);
      bad = r > 0 && t[r].size() == t[0].size() && outside_domain(column, t[r][c]);
      break;
    }
    case 2: {  // a column removed
      const std::size_t c = rng.below(t[0].size());
      for (auto& row : t)
        if (c < row.size()) row.erase(row.begin() + static_cast<std::ptrdiff_t>(c));
      break;
    }
    case 3:  // a row repeated
      t.insert(t.begin() + static_cast<std::ptrdiff_t>(r), t[r]);
      break;
    default:  // a row removed
      t.erase(t.begin() + static_cast<std::ptrdiff_t>(r));
      break;
  }
  text = csv_text(t);
  return bad;
}

// The inputs put in --out (".") under a name the report writes, or in a folder of their own.
void place(ReportFiles& f, Rng& rng) {
  static const std::vector<std::string> names = {"README.md", "report.html", "figures/wp-wall-in-house.png",
                                                  "figures/spectrum-wall.png", "s.csv", "in/s.csv"};
  f.out = rng.one_in(3) ? "report" : ".";
  if (f.points_name && rng.one_in(2)) f.points_name = rng.pick(names);
  else f.study_name = rng.pick(names);
  if (f.points_name && *f.points_name == f.study_name) f.points_name = "p.csv";
}

}  // namespace

std::vector<std::string> report_seeds() {
  std::vector<std::string> seeds;
  for (const fs::path& file : corpus_files("report-seeds")) seeds.push_back(read_file(file));
  return seeds;
}

std::string mutate_report(std::string_view seed, Rng& rng) {
  ReportFiles f = parse_files(std::string(seed));
  const std::size_t mutations = 1 + rng.below(4);
  for (std::size_t m = 0; m < mutations; ++m) {
    std::string& text = f.points_name && rng.one_in(2) ? f.points : f.study;
    f.must_refuse = false;
    switch (rng.below(8)) {
      case 0:
      case 1:
        rename_everywhere(f, rng.one_in(4) ? "settings" : rng.one_in(3) ? "solver" : "family", rng);
        break;
      case 2:
      case 3:
      case 4:
        f.must_refuse = mutate_table(text, rng);
        break;
      case 5:
        if (!text.empty()) text.resize(rng.below(text.size()));  // a file cut short
        break;
      case 6:
        place(f, rng);
        break;
      default:
        if (rng.one_in(2)) f.points_name.reset();
        else f.must_refuse = mutate_table(text, rng);
        break;
    }
  }
  return files_text(f);
}

namespace {

std::optional<std::string> check_written(const fs::path& out, const ChildOutcome& o) {
  if (!o.err.empty()) return "exit 0 with stderr: " + excerpt(o.err, 300);
  for (const char* name : {"README.md", "report.html"})
    if (!fs::is_regular_file(out / name)) return std::string("exit 0 without ") + name;
  const std::string readme = read_file(out / "README.md");
  for (std::size_t at = readme.find("](figures/"); at != std::string::npos; at = readme.find("](figures/", at + 1)) {
    const std::size_t end = readme.find(')', at);
    const std::string figure = readme.substr(at + 2, end - at - 2);
    if (!fs::is_regular_file(out / figure)) return "README.md shows " + excerpt(figure, 120) + ", which is not written";
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::string> check_report(const std::string& text, const ChildLimits& limits) {
  static std::atomic<int> counter{0};
  const fs::path dir = fs::temp_directory_path() /
                       ("poundbench-fuzz-report-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const ReportFiles f = parse_files(expand_generators(text));
  std::map<std::string, std::string> inputs = {{f.study_name, f.study}};
  if (f.points_name) inputs[*f.points_name] = f.points;
  for (const auto& [name, contents] : inputs) {
    fs::create_directories((dir / name).parent_path());
    std::ofstream(dir / name, std::ios::binary) << contents;
  }
  std::vector<std::string> args = {"report", f.study_name};
  if (f.points_name) args.insert(args.end(), {"--points", *f.points_name});
  args.insert(args.end(), {"--out", f.out});

  const std::set<std::string> before = listing(dir);
  const ChildOutcome o = run_program(POUNDBENCH_EXE, args, dir, limits);
  const std::set<std::string> after = listing(dir);
  std::optional<std::string> problem;
  for (const auto& [name, contents] : inputs)
    if (!problem && read_file(dir / name) != contents) problem = "changed its input " + name + " (" + o.describe() + ")";
  for (const std::string& name : after)
    if (!problem && fs::path(name).filename().string().front() == '.')
      problem = "left a folder of its own: " + name + " (" + o.describe() + ")";
  if (!problem && o.err.find("Traceback") != std::string::npos) problem = "a traceback: " + excerpt(o.err, 300);
  if (!problem && (!o.exited || !sanitizer_line(o.err).empty() || (o.exit_code != 0 && o.exit_code != 2)))
    problem = o.describe() + (o.err.empty() ? "" : "; stderr: " + excerpt(o.err, 300));
  if (!problem && o.exit_code == 2) {
    if (auto bad = one_line_problem(o.err, o.err_size, "stderr")) problem = "exit 2: " + *bad;
    else if (o.err.rfind("poundbench: ", 0) != 0) problem = "exit 2: stderr does not start with 'poundbench: '";
    else if (after != before) problem = "exit 2: wrote into the folder: " + *std::find_if(after.begin(), after.end(),
                                                                                        [&](const std::string& n) {
                                                                                          return !before.contains(n);
                                                                                        });
  }
  if (!problem && o.exit_code == 0 && f.must_refuse) problem = "accepted a value outside its column's domain (exit 0)";
  if (!problem && o.exit_code == 0) problem = check_written(dir / f.out, o);
  fs::remove_all(dir);
  return problem;
}

}  // namespace pb::fuzz
