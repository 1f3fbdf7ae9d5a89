#pragma once
// Case-set files: TOML that people write by hand, expanded into a list of Cases.
// The format is documented in cases/README.md; the shipped sets are in cases/sets/.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "cases/case.hpp"
#include "cases/case_list.hpp"

namespace pb {

// A bad case-set file. what() is one line: "<file>:<line>: <field>: <reason>"
// (the line is left out where it is not known).
struct CaseSetError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct CaseSet {
  std::string name;
  std::string description;
  std::vector<Case> cases;  // in file order, then in the order the grids expand
};

CaseSet parse_case_set(std::string_view toml_text, std::string_view source_name);
CaseSet load_case_set(const std::filesystem::path& file);

// The same set with its cases built on demand (cases/case_list.hpp), for a sweep that must
// not hold them (`spectrum`: a million points held 320 MB). The file is checked as fully as
// load_case_set checks it, every case built once and dropped; the list keeps what the file
// gave (each family's values and the records it names).
struct CaseListSet {
  std::string name;
  std::string description;
  CaseList cases;
};
CaseListSet parse_case_list(std::string_view toml_text, std::string_view source_name);
CaseListSet load_case_list(const std::filesystem::path& file);

}  // namespace pb
