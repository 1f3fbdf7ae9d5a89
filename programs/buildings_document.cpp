// The buildings scene's case document (programs/buildings_protocol.hpp), written straight out as
// compact JSON as the single oscillators' is (programs/case_document.cpp): every number in its
// shortest round-trip form, so a program reads back the very doubles poundbench solves with.

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "programs/buildings_protocol.hpp"
#include "programs/compact_json.hpp"

namespace pb::programs {

namespace buildings_document {

// Building b's block of the model's damping matrix, row by row.
void write_damping_matrix(CompactJson& j, const BuildingModel& model, int b) {
  const int first = model.first[static_cast<std::size_t>(b)];
  const int n = model.scene.buildings[static_cast<std::size_t>(b)].floors();
  j.open('[');
  for (int r = 0; r < n; ++r) {
    j.open('[');
    for (int c = 0; c < n; ++c) j.number(model.C(first + r, first + c));
    j.close(']');
  }
  j.close(']');
}

// The rule C came from: rayleigh with its a0, a1 (C = a0 M + a1 K), or modal; xi either way.
void write_damping_rule(CompactJson& j, const BuildingModel& model, int b) {
  const BuildingModes& modes = model.modes[static_cast<std::size_t>(b)];
  const double xi = model.scene.xi;
  j.open('{');
  if (model.scene.damping == BuildingDamping::rayleigh) {
    double a0 = 0.0, a1 = 0.0;
    rayleigh_coefficients(xi, modes.w(0), modes.w.size() > 1 ? modes.w(1) : modes.w(0), a0, a1);
    j.key("rule").string("rayleigh").key("xi").number(xi).key("a0").number(a0).key("a1").number(a1);
  } else {
    j.key("rule").string("modal").key("xi").number(xi);
  }
  j.close('}');
}

bool all_finite(const Eigen::MatrixXd& x) { return x.allFinite(); }

}  // namespace buildings_document

CaseDocument buildings_case_document(const BuildingModel& model, const Settings& settings, double step) {
  using namespace buildings_document;
  CaseDocument doc;
  const BuildingScene& scene = model.scene;
  if (!all_finite(model.C) || !all_finite(model.K) || !model.m.allFinite() || !std::isfinite(model.t_end) ||
      !std::isfinite(scene.pulse.amplitude) || !std::isfinite(scene.pulse.w)) {
    doc.error = "buildings: every mass, stiffness, damping, the load and t_end must be finite (JSON has no NaN or infinity)";
    return doc;
  }
  std::string& text = doc.text;
  text.reserve(1024 + static_cast<std::size_t>(model.n_floors * model.n_floors) * 24 +
               (scene.pulse.record ? 48 * scene.pulse.record->t.size() : 0));
  CompactJson j(text);
  j.open('{').key("protocol").string(kProtocol).key("version").integer(kVersion);
  j.key("scene").string(kBuildingsSceneName);
  j.key("conventions").open('{').key("units").string("SI").key("u").string("relative to the ground");
  j.key("gap").string("delta + u_right - u_left").close('}');
  j.key("buildings").open('[');
  for (std::size_t b = 0; b < scene.buildings.size(); ++b) {
    const Building& building = scene.buildings[b];
    j.open('{').key("masses").numbers(building.masses).key("stiffnesses").numbers(building.stiffnesses);
    const Eigen::VectorXd& w = model.modes[b].w;
    j.key("w").numbers(std::vector<double>(w.data(), w.data() + w.size()));
    j.key("damping");
    write_damping_rule(j, model, static_cast<int>(b));
    j.key("C");
    write_damping_matrix(j, model, static_cast<int>(b));
    j.close('}');
  }
  j.close(']').key("contacts").open('[');
  for (const FloorContact& c : model.contacts)
    j.open('{').key("left").integer(c.left).key("right").integer(c.right).key("floor").integer(c.floor)
        .key("gap").number(scene.delta).close('}');
  j.close(']').key("eps").number(scene.eps).key("load");
  write_load(j, scene.pulse);
  j.key("a_p").number(model.a_p).key("w_p").number(model.w_p).key("length_scale").number(model.length_scale());
  j.key("t_end").number(model.t_end).key("t_min").number(model.t_min);
  j.key("step");
  if (std::isfinite(step)) j.number(step);
  else j.null();
  j.key("steps_per_period");
  if (std::isfinite(step) && settings.steps > 0 && !(settings.wh > 0.0)) j.integer(settings.steps);
  else j.null();
  j.key("step_cap").integer(settings.step_cap).key("time_limit").number(settings.time_limit);
  j.key("monitor").boolean(settings.monitor);
  j.close('}');
  text += '\n';
  return doc;
}

}  // namespace pb::programs
