#include "cases/fields.hpp"

#include <algorithm>
#include <numbers>

namespace pb {

bool used_by(const CaseField& field, Scene scene, PulseShape pulse) {
  switch (field.use) {
    case FieldUse::every: return true;
    case FieldUse::body1: return uses_body1(scene);
    case FieldUse::body2: return uses_body2(scene);
    case FieldUse::chain: return scene == Scene::chain;
    case FieldUse::makris_c: return pulse == PulseShape::makris_c;
    case FieldUse::mp: return pulse == PulseShape::mp;
    case FieldUse::record: return pulse == PulseShape::record;
  }
  return false;
}

double period_to_frequency(double tp) { return 2.0 * std::numbers::pi / tp; }

std::string flag_of(std::string_view name) {
  std::string flag = "--" + std::string(name);
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

}  // namespace pb
