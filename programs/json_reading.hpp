#pragma once
// The reading of the protocol's JSON documents with every error naming its field ("field: why",
// as std::invalid_argument), shared by the single oscillators' documents (programs/protocol.cpp)
// and the buildings scene's answer (programs/buildings_answer.cpp), so that both refuse a bad
// document the same way: a key given twice, nesting too deep, the time limit passed while reading.

#include <chrono>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace pb::programs::reading {

using Json = nlohmann::json;
using Clock = std::chrono::steady_clock;

// How long an answer's message may be: a message is shown in a row (one of 100 MB was 528 MB
// resident).
inline constexpr std::size_t kMaxMessageBytes = 10'000;

[[noreturn]] void bad(const std::string& field, const std::string& why);
// object[key], or "field: missing".
const Json& member(const Json& object, const std::string& key, const std::string& field);
// A finite number.
double number(const Json& j, const std::string& field);
// A whole number >= 0.
long whole(const Json& j, const std::string& field);
// An optional number: absent or null is nullopt; anything else a finite number.
std::optional<double> maybe_number(const Json& object, std::string_view key);
// "protocol" (when given) and "version" are the protocol's.
void check_version(const Json& doc);
// One JSON object: no key twice in an object, nested at most 16 deep, parsed by `deadline`;
// `what` names the document in an error ("stdout").
Json parse_object(std::string_view text, const char* what, Clock::time_point deadline = Clock::time_point::max());

}  // namespace pb::programs::reading
