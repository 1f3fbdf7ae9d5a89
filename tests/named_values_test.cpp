// A run's settings as named values: the JSON object a row's settings column holds.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "kit/named_values.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace named_values_tests {

TEST(NamedValues, WriteAJsonObjectInTheOrderTheyWereAdded) {
  NamedValues v;
  v.add("steps", 64).add("theta", 0.5).add("load", "end-samples").add("split_impulse", true);
  EXPECT_EQ(v.json(), R"({"steps":64,"theta":0.5,"load":"end-samples","split_impulse":true})");
  const auto parsed = nlohmann::ordered_json::parse(v.json());
  EXPECT_EQ(parsed.begin().key(), "steps");
  EXPECT_EQ(parsed.at("theta").get<double>(), 0.5);
}

TEST(NamedValues, NumbersReadBackToTheSameValueInTheirShortestText) {
  NamedValues v;
  v.add("third", 1.0 / 3.0).add("warmstart", 0.85f).add("one", 1.0).add("tiny", 1e-10);
  EXPECT_EQ(v.json(), R"({"third":0.3333333333333333,"warmstart":0.85,"one":1,"tiny":1e-10})");
  EXPECT_EQ(nlohmann::json::parse(v.json()).at("third").get<double>(), 1.0 / 3.0);
}

TEST(NamedValues, NonFiniteNumbersAreNamedAndNamesAndTextsAreEscaped) {
  NamedValues v;
  v.add("nan", std::numeric_limits<double>::quiet_NaN()).add("inf", INFINITY).add("low", -INFINITY);
  v.add("a\"b", "x\ny");
  EXPECT_EQ(v.json(), R"({"nan":"nan","inf":"inf","low":"-inf","a\"b":"x\ny"})");
  EXPECT_EQ(NamedValues().json(), "{}");
}

}  // namespace named_values_tests
}  // namespace pb
