#include "frontend/run_output.hpp"

#include <cmath>

#include "cases/fields.hpp"
#include "cases/record.hpp"
#include "frontend/errors.hpp"
#include "cases/physical.hpp"
#include "rows/result_fields.hpp"

namespace pb::app {

namespace {

// The paper's labels of the bodies, left to right (body 0 is the reported one).
// A chain's bodies are numbered from its left end.
std::vector<std::string> body_labels(const Case& c) {
  switch (c.scene) {
    case Scene::wall: return {"0"};
    case Scene::pair: return {"1", "0"};
    case Scene::row3: return {"1", "0", "2"};
    case Scene::chain: {
      std::vector<std::string> labels;
      for (int i = 0; i < c.bodies; ++i) labels.push_back(std::to_string(i));
      return labels;
    }
  }
  return {};
}

void case_fields(const Case& c, RowFields& j) {
  j["family"] = c.family;
  j["scene"] = name(c.scene);
  j["pulse"] = name(c.pulse);
  j["directivity"] = name(c.directivity);
  for (const CaseField& field : kCaseFields) {
    if (!written(field, c)) continue;
    if (field.text)
      j[field.name] = c.*field.text;
    else if (field.integer)
      j[field.name] = c.*field.integer;
    else
      j[field.name] = c.*field.number;
  }
}

// --json's object, as nlohmann's JSON.
class JsonSink final : public FieldSink {
 public:
  nlohmann::ordered_json j;
  void null(std::string_view key) override { j[std::string(key)] = nullptr; }
  void boolean(std::string_view key, bool x) override { j[std::string(key)] = x; }
  void integer(std::string_view key, long long x) override { j[std::string(key)] = x; }
  void number(std::string_view key, double x) override { j[std::string(key)] = x; }
  void text(std::string_view key, std::string_view x) override { j[std::string(key)] = x; }
  void object(std::string_view key, std::string_view json) override { j[std::string(key)] = nlohmann::json::parse(json); }
  void list(std::string_view key, std::span<const double> xs) override {
    nlohmann::ordered_json a = nlohmann::ordered_json::array();
    for (double x : xs) a.push_back(std::isfinite(x) ? nlohmann::ordered_json(x) : nlohmann::ordered_json(nullptr));
    j[std::string(key)] = std::move(a);
  }
};

// A history is held in memory, then written as CSV (about 20 bytes a value), so its size
// is bounded before the run: 1e6 samples resolve a run of the longest allowed length
// (1e6 shortest periods, cases/case.hpp) to one sample a period, finer than any plot
// or check needs; and 2e7 values (160 MB held, about 400 MB written) bound the history
// of a long chain, whose rows have 4 N - 1 values. --samples 1e8 of a pair asked for 5.6 GB.
constexpr long long kMaxHistorySamples = 1'000'000;
constexpr long long kMaxHistoryValues = 20'000'000;

}  // namespace

void row_fields(const Row& row, const ChosenCase& chosen, FieldSink& sink) {
  RowFields j{sink};
  // The row's results (rows/result_fields.hpp), in its table's order.
  for (const ResultField& f : kResultFields) {
    if (!f.json) continue;
    switch (f.type) {
      case ResultType::number: j[f.name] = f.number(row); break;
      case ResultType::count: j[f.name] = f.whole ? row.result.*f.whole : static_cast<long long>(f.number(row)); break;
      case ResultType::text: j[f.name] = f.text(row); break;
      case ResultType::object: j[f.name] = RowFields::Object{f.text(row)}; break;
      case ResultType::status: j[f.name] = name(row.result.status); break;
      case ResultType::verdict: j[f.name] = row.result.resolved; break;
      case ResultType::list: j[f.name] = f.list(row); break;
    }
  }
  if (!chosen.case_file.empty()) {
    j["case_file"] = chosen.case_file;
    j["point"] = chosen.point;
  }
  case_fields(row.input, j);
  if (const std::string source = w_p_source(row.input); !source.empty()) {
    j["record_peak"] = row.input.samples->peak;
    j["record_t_m"] = row.input.samples->t_m;
    j["w_p_source"] = source;
  }
  // A case in physical units: the values it was given (the Pi terms above follow from them).
  for (const PhysicalField& field : kPhysicalFields)
    if (!std::isnan(row.input.physical.*field.member)) j[field.name] = row.input.physical.*field.member;
}

nlohmann::ordered_json row_json(const Row& row, const ChosenCase& chosen) {
  JsonSink sink;
  row_fields(row, chosen, sink);
  return std::move(sink.j);
}

std::string w_p_source(const Case& c) {
  if (c.pulse != PulseShape::record || !c.samples) return {};
  return c.w_p == c.samples->mean_frequency() ? "mean period" : "given";
}

std::vector<std::string> history_columns(const Case& c) {
  const std::vector<std::string> bodies = body_labels(c);
  std::vector<std::string> columns = {"t"};
  for (const char* quantity : {"u", "v"})
    for (const std::string& body : bodies) columns.push_back(quantity + body);
  for (const char* quantity : {"g", "lambda"})
    for (int j = 1; j <= contact_count(c); ++j) columns.push_back(quantity + std::to_string(j));
  return columns;
}

void check_samples(int samples, const Case& c) {
  if (samples < 2) throw BadInput("--samples: must be >= 2");
  if (samples > kMaxHistorySamples)
    throw BadInput("--samples: must be <= " + std::to_string(kMaxHistorySamples));
  const long long row = 1 + 2LL * body_count(c) + 2LL * contact_count(c);
  if (samples * row > kMaxHistoryValues)
    throw BadInput("--samples: at most " + std::to_string(kMaxHistoryValues / row) + " for this scene (" +
                   std::to_string(row) + " values a sample, " + std::to_string(kMaxHistoryValues) +
                   " values of history at most)");
}

}  // namespace pb::app
