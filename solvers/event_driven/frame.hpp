#pragma once
// The reference's state at an event and the closed-form motion that continues it (a
// "frame"): bodies joined by persistent contacts move as one damped oscillator (a
// cluster, DERIVATION.md §1), every other body alone; per contact, the gap of an open one
// or the force of a persistent one.
//
// A frame can be rebuilt for a stretch of bodies only. The contact LCP decides each run of
// closed contacts on its own (runs share no body, so no force of one reaches another) and
// needs the motion of that run's bodies alone, once per candidate active set: rebuilding
// the whole chain for each would cost O(N) per candidate.

#include <cstdint>
#include <vector>

#include "cases/system.hpp"
#include "solvers/event_driven/wave.hpp"

namespace pb::event_driven {

struct State {
  double t = 0.0;
  std::vector<double> u, v, g;  // per body, per body, per contact
  std::vector<char> active;     // per contact: persistent contact
  // Yielding (System::yields(); empty otherwise), per body: its branch, 0 elastic or +-1
  // yielding at z = +-u_y, and on the elastic branch its plastic offset e = u - z
  // (DERIVATION.md §10). An elastic body stays on branch 0 with e = 0.
  std::vector<signed char> branch;
  std::vector<double> e;
};

struct Frame {
  std::vector<Wave> body;
  // Per body (or empty: not kept), which cluster motion its wave is: build_frame gives every
  // body of a cluster that motion plus its offset, so bodies with one number have waves
  // equal but for f0 (WaveAt); 0: not known. `motions` numbers them.
  std::vector<std::uint64_t> motion;
  std::uint64_t motions = 0;
  std::vector<Wave> contact;  // gap (open contact) or force (persistent contact)
  // Per body that yields (2 i, 2 i + 1; empty for a system that does not): on the elastic
  // branch u_y - z and u_y + z, which fall to zero where it yields; yielding at z = s u_y,
  // s u' (2 i alone), which falls to zero where it unloads.
  std::vector<Wave> yield;
};

// Body i's restoring force on its branch, k u + r0 (DERIVATION.md §10): k, r0 = 0 for an
// elastic body; k and -(1 - alpha) k e on the elastic branch; alpha k and s (1 - alpha) k u_y
// yielding at z = s u_y.
struct Spring {
  double k, r0;
};
Spring spring(const System& s, const State& st, int i);

// The hysteretic variable z of body i (its u for a body that does not yield).
double hysteretic_z(const System& s, const State& st, int i);

// The contacts whose bodies all lie in first..last (the wall contact belongs to body 0).
inline int first_contact(const System& s, int first_body) {
  return s.wall && first_body == 0 ? 0 : first_body + (s.wall ? 1 : 0);
}
inline int last_contact(const System& s, int last_body) { return last_body - 1 + (s.wall ? 1 : 0); }
// The bodies of contacts first..last.
inline int first_body(const System& s, int first_contact) {
  return s.left(first_contact) == kWall ? 0 : s.left(first_contact);
}
inline int last_body(const System& s, int last_contact) { return s.right(last_contact); }

// Whether contacts j < k share a body (G = W^T M^-1 W couples only such neighbours).
inline bool adjacent(const System& s, int j, int k) { return s.right(j) == s.left(k); }

// Rebuilds the motion of bodies first..last, and of the contacts among them, from st at
// st.t. fr must hold one wave per body and per contact of s; the others are left alone.
void build_frame(const System& s, const State& st, int first, int last, Frame& fr);

// Body i's wave as build_frame(s, st, first, last, fr) would write it, where first..last is
// its cluster (a run of persistent contacts in st, whole), without the other bodies' waves,
// the cluster's forces or its gaps: what a gap between a rebuilt body and one that keeps its
// wave needs of the latter (DERIVATION.md §9), the same bits for O(1) waves, not O(cluster).
void body_motion(const System& s, const State& st, int first, int last, int i, Wave& u);

// Rebuilds the wave of open contact j from st.g[j] at st.t and its bodies' waves from st.t
// (`left` null at the wall). build_frame does this for the contacts between the bodies it
// rebuilds; the reference's lazy events (DERIVATION.md §9) for a contact between a rebuilt
// body and one it keeps, whose wave is rebuilt at st.t for this alone.
void build_gap(const State& st, int j, const Wave& right, const Wave* left, Wave& g);

// Moves the bodies of each cluster that `joined` (per contact) makes among bodies from..to so
// that its gaps are exactly closed, keeping its centre of mass (a cluster at the wall goes to
// it). Every joined contact must lie among those bodies.
void close_gaps(const System& s, const std::vector<char>& joined, std::vector<double>& u, int from, int to);

}  // namespace pb::event_driven
