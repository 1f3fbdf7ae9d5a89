#include "cases/fields.hpp"

#include <algorithm>

namespace pb {

bool used_by(const CaseField& field, Scene scene) {
  switch (field.use) {
    case FieldUse::every: return true;
    case FieldUse::body1: return uses_body1(scene);
    case FieldUse::body2: return uses_body2(scene);
    case FieldUse::chain: return scene == Scene::chain;
  }
  return false;
}

std::string flag_of(std::string_view name) {
  std::string flag = "--" + std::string(name);
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

}  // namespace pb
