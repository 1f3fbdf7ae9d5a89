#include "rows/minimal_rows.hpp"

#include <algorithm>
#include <iterator>
#include <optional>
#include <sstream>
#include <utility>

#include "cases/fields.hpp"
#include "cases/input_file.hpp"
#include "cases/text.hpp"

namespace pb {

namespace {

// The columns read_csv requires that a file may leave out, with the field each then holds
// ("" for point: the row's index).
std::vector<std::pair<std::string, std::string>> defaults() {
  std::vector<std::pair<std::string, std::string>> out = {{"family", ""}, {"point", ""}};
  const Case standard;
  for (const CaseField& field : kCaseFields)
    if (field.use == FieldUse::every && !field.required && !field.yielding)
      out.emplace_back(field.name, format_number(field.get(standard)));
  for (const char* column : {"solver", "variant", "settings"}) out.emplace_back(column, "");
  out.emplace_back("status", "ok");
  return out;
}

}  // namespace

std::vector<std::string_view> minimal_columns() {
  std::vector<std::string_view> columns = {"scene", "pulse", "directivity"};
  for (const CaseField& field : kCaseFields)
    if (field.required) columns.push_back(field.name);
  columns.push_back("pi1");
  return columns;
}

// The file is completed, record by record, with the columns it leaves out, and then read
// by read_csv: one reader for every file of rows, its checks and messages included. A
// record keeps its lines, so the line numbers of read_csv's messages are the file's.
RowFile read_minimal_csv(std::istream& in, std::string_view source) {
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (!text.empty() && text.back() != '\n') text += '\n';  // a last line without its '\n' is read too
  std::istringstream records(text);
  std::ostringstream completed;
  std::vector<std::string> header;
  std::vector<std::pair<std::string, std::string>> added;  // the columns the file leaves out
  const auto has = [&](std::string_view column) { return std::find(header.begin(), header.end(), column) != header.end(); };
  std::size_t line = 1, rows = 0;
  std::string record;
  while (read_csv_record(records, record)) {
    const std::size_t at = line;
    line += 1 + static_cast<std::size_t>(std::count(record.begin(), record.end(), '\n'));
    const auto fail = [&](std::string_view column, std::string_view why) {
      return RowReadError(std::string(source) + ":" + std::to_string(at) + ": " + std::string(column) + ": " +
                          std::string(why));
    };
    if (!record.empty() && record.back() == '\r') record.pop_back();
    if (header.empty() && record.starts_with('#')) {
      completed << record << '\n';
      continue;
    }
    if (header.empty()) {
      header = split_csv(record);
      // Those of some scenes' bodies are checked on each row, against its scene.
      for (std::string_view column : minimal_columns()) {
        const bool some_scenes = std::any_of(kCaseFields.begin(), kCaseFields.end(), [&](const CaseField& f) {
          return f.name == column && f.use != FieldUse::every;
        });
        if (!some_scenes && !has(column)) throw fail(column, "missing column");
      }
      for (const auto& [column, field] : defaults())
        if (!has(column)) added.emplace_back(column, field);
      for (const auto& [column, field] : added) record += "," + column;
    } else if (!record.empty()) {
      // The numbers of the record's scene's bodies (a scene read_csv refuses is its to name).
      const std::vector<std::string> fields = split_csv(record);
      const auto scene_at = static_cast<std::size_t>(std::find(header.begin(), header.end(), "scene") - header.begin());
      const std::optional<Scene> scene = scene_at < fields.size() ? parse_scene(fields[scene_at]) : std::nullopt;
      const auto pulse_at = static_cast<std::size_t>(std::find(header.begin(), header.end(), "pulse") - header.begin());
      const std::optional<PulseShape> pulse = pulse_at < fields.size() ? parse_pulse(fields[pulse_at]) : std::nullopt;
      if (scene && pulse) {
        const Scene sc = *scene;
        const PulseShape pu = *pulse;
        for (const CaseField& field : kCaseFields) {
          if (!field.required || !used_by(field, sc, pu) || has(field.name)) continue;
          const std::string user = pulse_use(field.use) ? "pulse " + std::string(name(pu)) : "scene " + std::string(name(sc));
          throw fail(field.name, "missing column (" + user + " uses it)");
        }
      }
      for (const auto& [column, field] : added)
        record += "," + (column == "point" ? std::to_string(rows) : csv_field(field));
      ++rows;
    }
    completed << record << '\n';
  }
  std::istringstream full(completed.str());
  return read_csv(full, source);
}

RowFile read_minimal_csv_file(const std::string& path) {
  std::istringstream in(read_input_file<RowReadError>(path));
  return read_minimal_csv(in, path);
}

}  // namespace pb
