#pragma once
// The Fig. 4 pair family as the benchmarks sample it: normal directivity, both pulses, the
// paper's eight Pi5, Pi6 = 1, Pi3 = 0.5, eps = 0.5, 50 log-spaced Pi2 in [0.1, 10].

#include <cmath>
#include <vector>

#include "cases/system.hpp"

namespace pb::bench {

inline std::vector<System> fig4_family() {
  std::vector<System> systems;
  for (PulseShape p : {PulseShape::sine, PulseShape::cosine}) {
    for (double pi5 : {0.1, 0.25, 0.5, 0.75, 1.33, 2.0, 4.0, 10.0}) {
      for (int k = 0; k < 50; ++k) {
        Case c;
        c.scene = Scene::pair;
        c.pulse = p;
        c.pi3 = 0.5;
        c.pi5 = pi5;
        c.pi6 = 1.0;
        c.eps = 0.5;
        c.pi2 = 0.1 * std::pow(100.0, k / 49.0);
        systems.push_back(make_system(c));
      }
    }
  }
  return systems;
}

}  // namespace pb::bench
