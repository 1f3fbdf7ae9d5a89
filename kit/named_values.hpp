#pragma once
// A run's settings as named values, in the order its solver lists them: what a row records
// of how it was solved (SolverInfo::describe). Written as one JSON object, so the CSV's
// settings column and `run --json` carry names and typed values that any reader parses
// with its JSON library, rather than a "k=v;..." string each reader would split again.

#include <string>
#include <string_view>

namespace pb {

class NamedValues {
 public:
  NamedValues& add(std::string_view name, double value);
  // A float as its own shortest text (0.85f as 0.85, not as the double 0.8500000238...).
  NamedValues& add(std::string_view name, float value);
  NamedValues& add(std::string_view name, long long value);
  NamedValues& add(std::string_view name, int value) { return add(name, static_cast<long long>(value)); }
  NamedValues& add(std::string_view name, long value) { return add(name, static_cast<long long>(value)); }
  NamedValues& add(std::string_view name, bool value);
  NamedValues& add(std::string_view name, std::string_view text);
  NamedValues& add(std::string_view name, const char* text) { return add(name, std::string_view(text)); }

  // {"steps":64,"theta":0.5}; {} when empty. A non-finite number is written as the
  // string "inf", "-inf" or "nan".
  std::string json() const { return json_ + '}'; }

 private:
  NamedValues& add_raw(std::string_view name, std::string_view json_value);
  std::string json_ = "{";
};

struct Settings;
// A contact element's stiffness in a describe(): its Pi term `pi_term` (the value it runs with)
// and Settings::k_contact where the user gave one in N/m; the Pi term alone is left out where
// only k_contact was given (a study's run, whose cases each take their own Pi term from it).
void add_stiffness(NamedValues& out, const Settings& settings, double pi_term);

}  // namespace pb
