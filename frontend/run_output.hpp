#pragma once
// What `run` reports of a solved case, shared by the command line and the Python module
// (python/): the object `run --json` prints, the columns of `run --history`, and the check of
// `--samples`.

#include <cmath>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <nlohmann/json.hpp>

#include "frontend/case_flags.hpp"
#include "rows/row.hpp"

namespace pb::app {

// Where the fields of `run --json`'s object go, in order: nlohmann's JSON for the command
// line, a dict for the Python module, which builds it without JSON between (a trip through
// JSON was a third of poundbench.run's fixed cost). A key given again keeps its first place.
class FieldSink {
 public:
  virtual ~FieldSink() = default;
  virtual void null(std::string_view key) = 0;
  virtual void boolean(std::string_view key, bool x) = 0;
  virtual void integer(std::string_view key, long long x) = 0;
  virtual void number(std::string_view key, double x) = 0;  // finite
  virtual void text(std::string_view key, std::string_view x) = 0;
  // A flat JSON object's text (a row's settings, NamedValues): names to numbers, strings, booleans.
  virtual void object(std::string_view key, std::string_view json) = 0;
  // Numbers (a value per body), a NaN as null.
  virtual void list(std::string_view key, std::span<const double> xs) = 0;
};

// `fields[key] = value` into a FieldSink: a number that is not finite is null (JSON has no
// spelling for it), an empty optional<bool> null.
struct RowFields {
  struct Object {
    std::string_view json;
  };
  struct Field {
    FieldSink& sink;
    std::string_view key;
    template <class T>
    void operator=(const T& x) {
      if constexpr (std::is_same_v<T, bool>) sink.boolean(key, x);
      else if constexpr (std::is_integral_v<T>) sink.integer(key, static_cast<long long>(x));
      else if constexpr (std::is_floating_point_v<T>) std::isfinite(x) ? sink.number(key, x) : sink.null(key);
      else if constexpr (std::is_same_v<T, std::optional<bool>>) x ? sink.boolean(key, *x) : sink.null(key);
      else if constexpr (std::is_same_v<T, Object>) sink.object(key, x.json);
      else if constexpr (std::is_same_v<T, std::vector<double>>) sink.list(key, x);
      else sink.text(key, std::string_view(x));
    }
  };
  FieldSink& sink;
  Field operator[](std::string_view key) { return {sink, key}; }
};

// The fields of `run --json`'s object (docs/cli.md), in order; a row of a case file names it
// and its point.
void row_fields(const Row& row, const ChosenCase& chosen, FieldSink& sink);
// That object as JSON.
nlohmann::ordered_json row_json(const Row& row, const ChosenCase& chosen);

// What a record case's w_p is: "mean period" when it is the record's 2 pi / T_m (the default,
// or a w_p or tp given equal to it), "given" otherwise; empty for every other pulse, and for
// a case without its samples.
std::string w_p_source(const Case& c);

// The columns of a history: t, then u, v of each body and g, lambda of each contact, labelled
// as in the paper (pair: t,u1,u0,v1,v0,g1,lambda1).
std::vector<std::string> history_columns(const Case& c);

// --samples N for the case's history: bounded so that a history fits in memory; throws BadInput.
void check_samples(int samples, const Case& c);

}  // namespace pb::app
