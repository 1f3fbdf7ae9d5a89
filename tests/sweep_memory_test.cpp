// A spectrum's memory is flat in its points (issue 36), checked through counters, not RSS:
// a case set built on demand holds no list of cases (the allocator's count of bytes in use),
// and the partial file's writer never queues more than its cap of rows, however many points
// the sweep has and however fast they finish. The measured peaks at a million points are in
// docs/cli.md ("Success").

#include <gtest/gtest.h>
#include <malloc.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "output/partial_writer.hpp"
#include "cases/buildings_set.hpp"
#include "cases/case_set.hpp"
#include "rows/row.hpp"
#include "rows/row_read.hpp"
#include "kit/solver.hpp"
#include "solvers/registry.hpp"
#include "output/partial_rows.hpp"
#include "sweep/sweep.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace sweep_memory_tests {

namespace fs = std::filesystem;

std::string spectrum_set(int families, int points) {
  std::string text = "name = \"flat\"\n";
  for (int f = 0; f < families; ++f)
    text += "[[family]]\nname = \"f" + std::to_string(f) +
            "\"\nscene = \"wall\"\npulse = \"sine\"\ndirectivity = \"normal\"\neps = 0.5\npi3 = " +
            std::to_string(f + 1) + "e-1\npi2 = { from = 0.2, to = 5, points = " + std::to_string(points) +
            ", spacing = \"log\" }\n";
  return text;
}

std::size_t heap_in_use() { return mallinfo2().uordblks; }

// The format's cap, a million points: held, 320 MB of Cases (sizeof(Case) = 320); built on
// demand, the families' value lists, about 1.2 MB (a grid's 1e5 values and their lines,
// ten times). The bound, 32 MB, is a tenth of the held list.
TEST(CaseList, AMillionPointSetHoldsItsFamiliesValuesNotItsCases) {
  const std::string text = spectrum_set(10, 100'000);
  const std::size_t before = heap_in_use();
  const CaseListSet set = parse_case_list(text, "flat.toml");
  const std::size_t held = heap_in_use() - before;
  ASSERT_EQ(set.cases.size(), 1'000'000u);
  EXPECT_LT(held, std::size_t{32} << 20) << "bytes in use after loading: " << held;
  const Case last = set.cases[999'999];
  EXPECT_EQ(last.family, "f9");
  EXPECT_EQ(last.pi2, 5.0);  // a grid's last point is exactly its end
  EXPECT_EQ(last.pi3, 1.0);
  EXPECT_EQ(set.cases[100'000].pi2, 0.2);
  EXPECT_EQ(set.cases[100'000].family, "f1");
}

// A case built on demand is the held list's, field for field as a row prints it (and with
// the same record's samples), on every shipped set: scenes, pulses, records, physical units,
// symmetric rows, chains and yielding bodies.
TEST(CaseList, BuildsEveryShippedSetsCasesAsTheHeldListHoldsThem) {
  std::size_t compared = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(POUNDBENCH_SOURCE_DIR) / "cases" / "sets")) {
    if (entry.path().extension() != ".toml") continue;
    if (load_buildings_set(entry.path())) continue;  // the buildings scene: no Cases, and no sweep yet
    const CaseSet held = load_case_set(entry.path());
    const CaseListSet lazy = load_case_list(entry.path());
    EXPECT_EQ(lazy.name, held.name);
    EXPECT_EQ(lazy.description, held.description);
    ASSERT_EQ(lazy.cases.size(), held.cases.size()) << entry.path();
    for (std::size_t i = 0; i < held.cases.size(); ++i) {
      Row a, b;
      a.input = held.cases[i];
      b.input = lazy.cases[i];
      ASSERT_EQ(csv_line(b), csv_line(a)) << entry.path() << " point " << i;
      ASSERT_EQ(b.input.samples == nullptr, a.input.samples == nullptr) << entry.path() << " point " << i;
      if (a.input.samples) {
        EXPECT_EQ(b.input.samples->source, a.input.samples->source);
        EXPECT_EQ(b.input.samples->a, a.input.samples->a);
      }
      ++compared;
    }
  }
  EXPECT_GT(compared, 23'820u);  // the paper set alone has 23 820
}

// The same error for a bad point whether the set is held or built on demand: every case is
// built and checked as the file loads.
TEST(CaseList, RefusesABadPointAsTheHeldSetDoes) {
  const std::string text = spectrum_set(2, 10) + "[[family]]\nname = \"bad\"\nscene = \"wall\"\npulse = \"sine\"\n"
                                                 "directivity = \"normal\"\neps = [0.5, 1.5]\npi3 = 0.5\npi2 = 1\n";
  std::string held, lazy;
  try {
    parse_case_set(text, "bad.toml");
  } catch (const CaseSetError& e) {
    held = e.what();
  }
  try {
    parse_case_list(text, "bad.toml");
  } catch (const CaseSetError& e) {
    lazy = e.what();
  }
  EXPECT_NE(held, "");
  EXPECT_EQ(lazy, held);
}

// A real sweep whose points finish faster than any watcher would write them (Moreau-Jean at 8
// steps a period, some 10 us a point, and no watcher at all): the writer's queue holds at most
// kMaxQueued rows (the worker that fills it writes it), and every row reaches the file once.
TEST(PartialWriter, QueuesAtMostItsCapOfRowsWhateverTheSweepsLength) {
  const fs::path file = fs::temp_directory_path() / ("poundbench-writer-" + std::to_string(::getpid()) + ".csv");
  fs::remove(file);
  const CaseListSet set = parse_case_list(spectrum_set(1, 20'000), "flat.toml");
  Settings settings;
  settings.steps = 8;
  settings.monitor = false;
  const SweepRun run{find_solver("moreau-jean"), settings};
  std::size_t peak = 0;
  {
    app::PartialWriter writer(file.string(), false, set.cases.size(), nullptr, set.cases.size());
    SweepOptions options;
    options.threads = 2;
    options.keep_rows = false;
    options.on_finished = [&](const Row& row) { writer.queue(row); };  // as run_resumable does
    EXPECT_TRUE(run_sweep(set.cases, std::span(&run, 1), options).empty());
    writer.write_all();
    writer.close();
    peak = writer.peak_queued();
  }
  EXPECT_LE(peak, app::PartialWriter::kMaxQueued);
  EXPECT_GT(peak, 0u);
  std::ifstream in(file);
  std::vector<bool> seen(set.cases.size(), false);
  std::size_t lines = 0;
  for (std::string line; std::getline(in, line); ++lines) {
    const std::size_t point = std::stoul(line.substr(line.find(',') + 1));
    ASSERT_LT(point, seen.size());
    EXPECT_FALSE(seen[point]) << "point " << point << " twice";
    seen[point] = true;
  }
  EXPECT_EQ(lines, set.cases.size());
  fs::remove(file);
}

// A resumed spectrum cuts its partial file after the last whole record instead of rewriting
// it, when every record is the line poundbench writes for its row: the shape says whether
// they are and where the whole records end, before a torn last line. An edit that the checks
// accept (a trailing zero in pi2) makes the file one to rewrite.
TEST(PartialRows, TheShapeSaysWhetherEveryRowIsAsWrittenAndWhereTheWholeRecordsEnd) {
  const CaseListSet set = parse_case_list(spectrum_set(1, 20), "flat.toml");
  Settings settings;
  settings.steps = 8;
  const SweepRun run{find_solver("moreau-jean"), settings};
  const std::vector<Row> rows = run_sweep(set.cases, std::span(&run, 1));
  std::string text = partial_header(false) + "\n";
  for (const Row& row : rows) text += partial_line(row, false) + "\n";
  const auto shape_of = [&](const std::string& file) {
    std::istringstream in(file);
    PartialFileShape shape;
    std::size_t count = 0;
    for_each_partial_row(in, "p.csv", set.cases, std::span(&run, 1), [&](Row&&) { ++count; }, &shape);
    EXPECT_EQ(count, rows.size());
    return shape;
  };
  PartialFileShape shape = shape_of(text);
  EXPECT_TRUE(shape.as_printed);
  EXPECT_EQ(shape.whole_bytes, text.size());
  shape = shape_of(text + partial_line(rows[0], false).substr(0, 40));  // a torn last line
  EXPECT_TRUE(shape.as_printed);
  EXPECT_EQ(shape.whole_bytes, text.size());

  const std::string line = partial_line(rows[3], false);
  const std::string pi2 = split_csv(line)[5];
  std::string edited = text;
  edited.replace(edited.find(line), line.size(), std::string(line).replace(line.find(pi2), pi2.size(), pi2 + "0"));
  shape = shape_of(edited);
  EXPECT_FALSE(shape.as_printed);
  EXPECT_EQ(shape.whole_bytes, edited.size());
}

}  // namespace sweep_memory_tests
}  // namespace pb
