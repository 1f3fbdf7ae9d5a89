#pragma once
// The no-contact Pi1 of a sweep's points, solved once per distinct no-contact problem.
//
// Every row carries Pi1 of body 0 alone (no_contact_pi1, the reference on a one-body
// System), and most points of a spectrum share it: the paper set's 23 820 points differ in
// the contact's Pi terms far more than in body 0's. Solved per point it cost 13 us, 22 % of
// the reference sweep's CPU (issue 23). A sweep keeps one cache for all its runs and
// threads; a miss solves outside the lock, so two threads may solve one key at once and
// store the same value.
//
// The key is every value of the one-body System that no_contact_pi1 solves
// (event_driven.cpp builds it: body 0, its start state, and the System's other scalars as
// they are), compared bit for bit, so a hit returns exactly the value a solve would: rows do
// not change. It keeps t_min, delta and eps although a body alone has no contact: t_min sets
// the reference's search tolerances (its floor and settle time), and delta and eps cost
// little to keep (the paper set: 8 176 distinct keys against 6 576 without them and 4 620
// without t_min too) while a key without them would rely on the reference never reading
// them there. NoContactKey's static_asserts fail to compile when System, Body or Pulse gain
// a field, so that the key is extended with it.
//
// Only the paper's pulses are cached: a record's samples and a pulse model's waves are not in
// the key, and their sweeps are short. Only finite values are kept: a solve cut short by its time limit or the sweep's stop (NaN)
// is solved again by the next point that needs it, as it would have been without a cache.
//
// The motion with every contact removed (free_motion: a row's separations, kit/separation.hpp)
// is kept too, by every value of the whole System but the contacts' (delta, eps), a record by
// its samples' address (shared by the sweep's cases of one record): a study's settings share
// their points' free motions, which cost two to three peak searches a point.

#include <array>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <unordered_map>
#include <vector>

#include "kit/separation.hpp"
#include "cases/system.hpp"
#include "kit/solver.hpp"

namespace pb {

// The bits of every value the one-body no-contact System holds.
struct NoContactKey {
  std::array<std::uint64_t, 17> bits{};
  bool operator==(const NoContactKey&) const = default;
};

NoContactKey no_contact_key(const System& system);

class NoContactCache {
 public:
  // no_contact_pi1(system, limits), from the cache when an earlier point had the same key.
  // Throws what no_contact_pi1 throws (nothing is stored then).
  double pi1(const System& system, const Settings& limits);

  // free_motion(system, limits), from the cache when an earlier point had the same system
  // but for delta and eps. Only an ok motion is kept.
  FreeMotion free(const System& system, const Settings& limits);

  std::size_t solves() const;  // misses so far (no_contact_pi1 calls)
  std::size_t size() const;    // values kept

 private:
  struct Hash {
    std::size_t operator()(const NoContactKey& k) const;
  };
  // Keys are spread over shards by their hash, each with its own lock and map. With one of
  // each, the sweep's threads wrote the same cache lines at every point: two threads swept
  // the Fig. 4 families at 1.78x one thread's rate, against 1.88x with no cache at all.
  static constexpr std::size_t kShards = 16;
  // A shard that holds this many values is emptied before it takes one more: the cache stays
  // under 11 MB (about 170 bytes a value) on a sweep of a million distinct points, where it
  // grew with the points; the paper set's 8 176 keys fit many times over.
  static constexpr std::size_t kShardValues = 4096;
  struct WordsHash {
    std::size_t operator()(const std::vector<std::uint64_t>& k) const;
  };
  struct alignas(64) Shard {
    mutable std::mutex mutex;
    std::unordered_map<NoContactKey, double, Hash> values;
    std::unordered_map<std::vector<std::uint64_t>, FreeMotion, WordsHash> free;
    std::size_t solves = 0;
  };
  std::array<Shard, kShards> shards_;
};

}  // namespace pb
