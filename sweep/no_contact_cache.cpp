#include "sweep/no_contact_cache.hpp"
#include "solvers/registry.hpp"

#include <bit>
#include <cmath>

namespace pb {

// A field added to one of these changes its size (unless it fits in padding): extend
// no_contact_key with it, then update the size here. The key holds a paper pulse's fields
// only (shape, amplitude, w): the record and pulse-model fields issue 21 added (waves,
// length, cycles, the record) are not in it, so such loads bypass the cache (pi1 below).
static_assert(sizeof(Body) == 5 * sizeof(double), "Body has a new field: add it to no_contact_key");
static_assert(sizeof(Pulse) == 152, "Pulse has a new field: add it to no_contact_key");
static_assert(sizeof(System) == 288, "System has a new field: add it to no_contact_key if the no-contact solve reads it");

namespace {

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

// event_driven::no_contact_pi1's start value of body `ref` (rest when the System gives none).
double start_of(const std::vector<double>& start, int ref) {
  return start.empty() ? 0.0 : start[static_cast<std::size_t>(ref)];
}

}  // namespace

NoContactKey no_contact_key(const System& s) {
  const Body& b = s.bodies[static_cast<std::size_t>(s.ref)];
  return {{bits(b.m), bits(b.w), bits(b.k), bits(b.c), static_cast<std::uint64_t>(s.pulse.shape),
           bits(s.pulse.amplitude), bits(s.pulse.w), bits(s.a_p), bits(s.t_end), bits(s.t_min), bits(s.delta),
           bits(s.eps), bits(s.xi), bits(start_of(s.u_start, s.ref)), bits(start_of(s.v_start, s.ref)), bits(b.u_y),
           bits(s.alpha)}};
}

std::size_t NoContactCache::Hash::operator()(const NoContactKey& k) const {
  std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a over the words, then a final mix
  for (std::uint64_t w : k.bits) h = (h ^ w) * 0x100000001b3ULL;
  return static_cast<std::size_t>(h ^ (h >> 29));
}

double NoContactCache::pi1(const System& system, const Settings& limits) {
  // A record or a pulse model is not described by the key: solved per point, uncached.
  if (!system.pulse.paper()) return no_contact_pi1(system, limits);
  const NoContactKey key = no_contact_key(system);
  Shard& shard = shards_[Hash{}(key) % kShards];
  {
    const std::lock_guard lock(shard.mutex);
    if (const auto it = shard.values.find(key); it != shard.values.end()) return it->second;
    ++shard.solves;
  }
  const double value = no_contact_pi1(system, limits);  // outside the lock: 13 us, and may throw
  if (std::isfinite(value)) {
    const std::lock_guard lock(shard.mutex);
    if (shard.values.size() >= kShardValues) shard.values.clear();
    shard.values.emplace(key, value);
  }
  return value;
}

std::size_t NoContactCache::solves() const {
  std::size_t n = 0;
  for (const Shard& shard : shards_) {
    const std::lock_guard lock(shard.mutex);
    n += shard.solves;
  }
  return n;
}

std::size_t NoContactCache::size() const {
  std::size_t n = 0;
  for (const Shard& shard : shards_) {
    const std::lock_guard lock(shard.mutex);
    n += shard.values.size();
  }
  return n;
}

}  // namespace pb
