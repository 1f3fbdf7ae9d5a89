#pragma once
// Every field of a row that is not the case's (cases/fields.hpp has those), declared once:
// its name (CSV column, `run --json` key, Python key), its type, where its CSV column sits,
// whether `run --json` and the Python dict carry it, and the key of an external program's
// answer that carries it. The CSV row and its reader (rows/row.cpp, rows/row_read.cpp), the
// --json object and the Python dict (frontend/run_output.cpp) and the external answer, read
// and written (programs/protocol.cpp), are all loops over kResultFields: adding a result
// takes its member in Result, a row here, and the code that computes it.
//
// A field's value in a row is a Result member (real, whole) or made from the row (made); a
// made field is read back into the row by `store`, or not at all when it is made again from
// other fields (mu from pi1 and Pi_y). An answer carries a Result member as the solver has it
// (min_gap in the system's lengths), a row as its column shows it (min_gap over a_p / w_p^2).

#include <limits>
#include <span>
#include <string_view>
#include <vector>

#include "rows/row.hpp"

namespace pb {

enum class ResultType {
  number,  // a double; NaN (and infinity) is an empty field, null in JSON
  count,   // an integer
  text,
  object,  // a flat JSON object's text (a row's settings): text in CSV, an object in --json and Python
  status,  // Status by its name
  verdict,  // std::optional<bool>: true, false or empty (null)
  list      // numbers (a value per body): in CSV one field, separated by ';'; an array in --json and Python
};

// Where a field's CSV column sits among the case's columns (rows/row.cpp, csv_header): the
// columns were added over time at the end, so that scripts that read columns by position
// kept working, and the order stays.
enum class Place {
  none,         // not a CSV column
  middle,       // after the case's numbers every scene's bodies have
  tail,         // after the chain's numbers
  verdict,      // after the pulses' numbers
  yielding,     // after yielding's numbers
  physical,     // after the physical values a case was given
  own_time,     // then the external solver's own timings,
  record_step,  // a record's step over its sampling interval,
  estimate,     // and the error estimates,
  separation    // then the no-contact motion's separations and peaks, last
};

struct ResultField {
  std::string_view name;
  ResultType type;
  Place place;
  bool json = true;            // in `run --json` and the Python dict
  std::string_view answer{};   // its key in an external program's answer; empty: none
  double Result::* real = nullptr;  // a number that is a Result member
  long Result::* whole = nullptr;   // a count that is a Result member
  double (*made)(const Row&) = nullptr;     // a number or count made from the row
  void (*store)(Row&, double) = nullptr;    // a made number read back into a row; null: made again
  std::string_view (*text)(const Row&) = nullptr;  // a text
  void (*store_text)(Row&, std::string_view) = nullptr;
  std::vector<double> (*list)(const Row&) = nullptr;  // a list, as its column shows it
  void (*store_list)(Row&, std::vector<double>) = nullptr;
  // The value where a CSV field or an answer's key is empty or absent (min_gap: no contact closed).
  double missing = std::numeric_limits<double>::quiet_NaN();

  // The number (or count) of a row, as its column shows it.
  double number(const Row& row) const {
    return made ? made(row) : real ? row.result.*real : static_cast<double>(row.result.*whole);
  }
  // A number read from a row's column into the row; a made field without store is made again.
  void read(Row& row, double x) const {
    if (store)
      store(row, x);
    else if (!made && real)
      row.result.*real = x;
    else if (!made && whole)
      row.result.*whole = static_cast<long>(x);
  }
};

// In the order of their CSV columns within each Place, and of the keys of `run --json`.
extern const std::span<const ResultField> kResultFields;

// The field of that name; null when there is none.
const ResultField* find_result_field(std::string_view name);

}  // namespace pb
