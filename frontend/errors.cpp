#include "frontend/errors.hpp"

#include <algorithm>
#include <string_view>

#include "cases/case_set.hpp"
#include "cases/text.hpp"

namespace pb::app {

namespace {

constexpr std::size_t kMaxMessagePart = 200;
constexpr std::size_t kMaxMessage = 1000;

}  // namespace

std::string one_line(const std::string& message) {
  std::string line;
  for (std::size_t start = 0; start <= message.size();) {
    const std::size_t end = std::min(message.find(": ", start), message.size());
    if (start > 0) line += ": ";
    line += clip(std::string_view(message).substr(start, end - start), kMaxMessagePart);
    start = end + 2;
  }
  line = clip(line, kMaxMessage);
  std::replace(line.begin(), line.end(), '\n', ' ');  // one line, whatever the source
  return line;
}

int exit_code_of(const std::exception& e) {
  if (dynamic_cast<const BadInput*>(&e) || dynamic_cast<const CaseSetError*>(&e)) return 2;
  return 1;
}

}  // namespace pb::app
