#include "sweep/no_contact_cache.hpp"
#include "solvers/registry.hpp"
#include "cases/record.hpp"

#include <bit>
#include <cmath>
#include <utility>

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

namespace {

template <class Words>
std::size_t hash_words(const Words& words) {
  std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a over the words, then a final mix
  for (std::uint64_t w : words) h = (h ^ w) * 0x100000001b3ULL;
  return static_cast<std::size_t>(h ^ (h >> 29));
}

// Every value free_motion reads of a system: its bodies, start, load and scales, but not the
// contacts' gap and restitution (free_motion sets the gap to 0 and closes no contact). Empty
// for a pulse model, whose waves are not in it (solved per point).
// A linear system's motion under the load reversed is its mirror (every operation of the
// reference is odd in the load, so to the bit): one key serves both directivities, the load's
// sign left out of it, and `flip` says that this system's motion is the mirror of the key's.
std::vector<std::uint64_t> free_key(const System& s, bool& flip) {
  flip = !s.yields() && s.pulse.amplitude < 0.0;
  if (!s.pulse.paper() && !s.pulse.record) return {};
  const double amplitude = s.yields() ? s.pulse.amplitude : std::abs(s.pulse.amplitude);
  std::vector<std::uint64_t> k = {static_cast<std::uint64_t>(s.pulse.shape), bits(amplitude), bits(s.pulse.w),
                                  std::bit_cast<std::uint64_t>(s.pulse.record.get()), bits(s.a_p), bits(s.t_end),
                                  bits(s.t_min), bits(s.xi), bits(s.alpha), static_cast<std::uint64_t>(s.wall),
                                  static_cast<std::uint64_t>(s.ref)};
  // A record by its address, and by what tells two records apart should a later one take a
  // freed one's address (a cache that outlives its sweep's cases: the Python module's).
  if (const Record* r = s.pulse.record.get())
    for (double x : {static_cast<double>(r->a.size()), r->peak, r->t.back(), r->t_m, r->scale}) k.push_back(bits(x));
  for (const Body& b : s.bodies)
    for (double x : {b.m, b.w, b.k, b.c, b.u_y}) k.push_back(bits(x));
  for (const std::vector<double>* start : {&s.u_start, &s.v_start}) {
    k.push_back(start->size());
    for (double x : *start) k.push_back(bits(x));
  }
  return k;
}

}  // namespace

std::size_t NoContactCache::Hash::operator()(const NoContactKey& k) const { return hash_words(k.bits); }

std::size_t NoContactCache::WordsHash::operator()(const std::vector<std::uint64_t>& k) const { return hash_words(k); }

FreeMotion NoContactCache::free(const System& system, const Settings& limits) {
  bool flip = false;
  std::vector<std::uint64_t> key = free_key(system, flip);
  if (key.empty()) return free_motion(system, limits);
  const auto mirrored = [&](FreeMotion m) {
    if (flip) std::swap(m.closing, m.opening);
    return m;
  };
  Shard& shard = shards_[WordsHash{}(key) % kShards];
  {
    const std::lock_guard lock(shard.mutex);
    if (const auto it = shard.free.find(key); it != shard.free.end()) return mirrored(it->second);
  }
  FreeMotion value = free_motion(system, limits);  // outside the lock: a solve
  if (value.status == Status::ok) {
    const std::lock_guard lock(shard.mutex);
    if (shard.free.size() >= kShardValues) shard.free.clear();
    shard.free.emplace(std::move(key), mirrored(value));
  }
  return value;
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
