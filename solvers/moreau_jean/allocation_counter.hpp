#pragma once
// Counting allocations in the test binary: moreau_jean_test.cpp replaces the global operator
// new (one definition per program) with one that counts the calls of a thread while an
// AllocationCounter of that thread lives, and defines the two counters here; every test of
// the binary that holds a step loop to "no allocation" (the single oscillators' loops there,
// the buildings' loop in buildings_test.cpp) reads them through this.

namespace pb::test {

extern thread_local bool g_counting_allocations;
extern thread_local long g_allocations;

struct AllocationCounter {
  AllocationCounter() {
    g_allocations = 0;
    g_counting_allocations = true;
  }
  ~AllocationCounter() { g_counting_allocations = false; }
  AllocationCounter(const AllocationCounter&) = delete;
  AllocationCounter& operator=(const AllocationCounter&) = delete;
  long count() const { return g_allocations; }
};

}  // namespace pb::test
