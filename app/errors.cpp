#include "app/errors.hpp"

#include "cases/case_set.hpp"

namespace pb::app {

int exit_code_of(const std::exception& e) {
  if (dynamic_cast<const BadInput*>(&e) || dynamic_cast<const CaseSetError*>(&e)) return 2;
  return 1;
}

}  // namespace pb::app
