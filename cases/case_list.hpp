#pragma once
// The cases of a sweep, by point: held in memory (a vector's, which must outlive the list),
// or built on demand from a case-set file's families (load_case_list, cases/case_set.hpp).
// A Case is 320 bytes, and a million-point set held as a vector was 320 MB, most of a
// spectrum's peak (issue 36); built on demand, a set holds its families' value lists only.
// Either way list[i] is the same Case, field for field.

#include <concepts>
#include <cstddef>
#include <functional>
#include <ranges>
#include <span>

#include "cases/case.hpp"

namespace pb {

class CaseList {
 public:
  using Build = std::function<Case(std::size_t point)>;

  CaseList() = default;
  // Held cases: a view, as std::span is (implicit, so a vector, an array or a span of cases
  // passes as a list).
  template <class Held>
    requires std::ranges::contiguous_range<const Held&> && std::same_as<std::ranges::range_value_t<Held>, Case>
  CaseList(const Held& held) : held_(std::span<const Case>(held)), size_(held_.size()) {}
  // Built on demand: build(i) for 0 <= i < size, called from several threads at once.
  CaseList(std::size_t size, Build build) : size_(size), build_(std::move(build)) {}

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  Case operator[](std::size_t point) const { return build_ ? build_(point) : held_[point]; }

 private:
  std::span<const Case> held_;
  std::size_t size_ = 0;
  Build build_;
};

}  // namespace pb
