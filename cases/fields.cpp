#include "cases/fields.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "cases/record.hpp"

namespace pb {

bool scene_uses(FieldUse use, Scene scene) {
  switch (use) {
    case FieldUse::every: return true;
    case FieldUse::body1: return uses_body1(scene);
    case FieldUse::body2: return uses_body2(scene);
    case FieldUse::chain: return scene == Scene::chain;
    case FieldUse::not_chain: return scene != Scene::chain;
    case FieldUse::pair_row3: return scene == Scene::pair || scene == Scene::row3;
    default: return false;
  }
}

bool used_by(const CaseField& field, Scene scene, PulseShape pulse) {
  switch (field.use) {
    case FieldUse::makris_c: return pulse == PulseShape::makris_c;
    case FieldUse::mp: return pulse == PulseShape::mp;
    case FieldUse::record: return pulse == PulseShape::record;
    default: return scene_uses(field.use, scene);
  }
}

bool written(const CaseField& field, const Case& c) {
  if (!used_by(field, c)) return false;
  if (!field.yielding && !field.late) return true;
  const double x = field.get(c), d = field.get(Case{});
  return x != d && !(std::isnan(x) && std::isnan(d));  // NaN: a target not given
}

double period_to_frequency(double tp) { return 2.0 * std::numbers::pi / tp; }

double g_to_si(double a_g) { return a_g * kStandardGravity; }

// Written in place: called some 65 times a poundbench.run call (every case and setting field
// asked whether its flag was given), "--" + name and a replace cost 230 instructions each there.
std::string flag_of(std::string_view name) {
  std::string flag(name.size() + 2, '-');
  std::replace_copy(name.begin(), name.end(), flag.begin() + 2, '_', '-');
  return flag;
}

}  // namespace pb
