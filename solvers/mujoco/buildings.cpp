#include "solvers/mujoco/buildings.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <iomanip>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "cases/text.hpp"
#include "kit/buildings_step_end.hpp"
#include "kit/fixed_step.hpp"
#include "kit/run_limits.hpp"
#include "solvers/mujoco/model.hpp"
#include "solvers/mujoco/mujoco_solver.hpp"

namespace pb::mujoco {

// Named, not anonymous: a unity build puts this file beside the single oscillators' Engine.
namespace floors {

namespace {

using buildings::BuildingsResult;

// The model's units: length, time and mass.
struct Scales {
  double length = 1.0, time = 1.0, mass = 1.0;
};

Scales scales_of(const BuildingModel& md, const Config& config) {
  if (!config.calibrated) return {};
  return {md.length_scale(), 1.0 / md.w_p, md.m(0)};
}

// Rayleigh's a0 and a1 of building b (as assemble() forms C from them).
void rayleigh_of(const BuildingModel& md, std::size_t b, double& a0, double& a1) {
  const Eigen::VectorXd& w = md.modes[b].w;
  rayleigh_coefficients(md.scene.xi, w(0), w.size() > 1 ? w(1) : w(0), a0, a1);
}

// The MJCF text of the scene: step h_model in model time, contacts as given (null: MuJoCo's).
std::string scene_xml(const BuildingModel& md, const Config& config, const Scales& s, double h_model,
                      const ContactParameters* contact) {
  const double T = s.time, M = s.mass;
  const double radius = kRadius * md.length_scale() / s.length, delta = md.scene.delta / s.length;
  const int nv = md.n_floors, nc = static_cast<int>(md.contacts.size());
  const bool rayleigh = md.scene.damping == BuildingDamping::rayleigh;
  std::ostringstream x;
  x << std::setprecision(17);
  x << "<mujoco model=\"buildings\">\n";
  // As the single oscillators' (model.cpp): a row per contact, and the implicit integrator's
  // dense nv x nv matrices on the stack.
  x << "  <size nconmax=\"" << std::max(nc, 1) << "\" njmax=\"" << std::max(nc, 1) << '"';
  if (config.integrator == Integrator::implicit) x << " nstack=\"" << 5000 + 60 * nv * nv << '"';
  x << "/>\n";
  x << "  <option timestep=\"" << h_model << "\" gravity=\"0 0 0\" integrator=\""
    << (config.integrator == Integrator::euler ? "Euler" : config.integrator == Integrator::rk4 ? "RK4" : "implicit")
    << '"';
  if (config.calibrated) x << " solver=\"Newton\" iterations=\"100\" tolerance=\"1e-12\"";
  x << "/>\n  <worldbody>\n";
  for (std::size_t b = 0; b < md.scene.buildings.size(); ++b) {
    double a0 = 0.0, a1 = 0.0;
    if (rayleigh) rayleigh_of(md, b, a0, a1);
    const int first = md.first[b];
    for (int i = first; i < first + md.scene.buildings[b].floors(); ++i) {
      x << "    <body name=\"f" << i << "\" pos=\"" << static_cast<double>(b) * (2.0 * radius + delta) << " 0 0\">\n";
      x << "      <joint name=\"j" << i << "\" type=\"slide\" axis=\"1 0 0\" damping=\"" << a0 * md.m(i) * T / M
        << "\"/>\n";
      x << "      <inertial pos=\"0 0 0\" mass=\"" << md.m(i) / M << "\" diaginertia=\"" << md.m(i) / M << ' '
        << md.m(i) / M << ' ' << md.m(i) / M << "\"/>\n";
      x << "      <geom name=\"g" << i << "\" type=\"sphere\" size=\"" << radius
        << "\" contype=\"0\" conaffinity=\"0\"/>\n    </body>\n";
    }
  }
  x << "  </worldbody>\n  <tendon>\n";
  for (std::size_t b = 0; b < md.scene.buildings.size(); ++b) {
    double a0 = 0.0, a1 = 0.0;
    if (rayleigh) rayleigh_of(md, b, a0, a1);
    const int first = md.first[b];
    for (int i = first; i < first + md.scene.buildings[b].floors(); ++i) {
      // Storey i: u_i - u_{i-1}, its spring at rest at 0 (the length at qpos0).
      x << "    <fixed name=\"s" << i << "\" springlength=\"0\" stiffness=\"" << md.k(i) * T * T / M << "\" damping=\""
        << a1 * md.k(i) * T / M << "\">\n      <joint joint=\"j" << i << "\" coef=\"1\"/>\n";
      if (i > first) x << "      <joint joint=\"j" << i - 1 << "\" coef=\"-1\"/>\n";
      x << "    </fixed>\n";
    }
  }
  x << "  </tendon>\n  <contact>\n";
  for (const FloorContact& fc : md.contacts) {
    x << "    <pair geom1=\"g" << fc.i_left << "\" geom2=\"g" << fc.i_right << "\" condim=\"1\"";
    if (contact) {
      x << " solref=\"" << contact->solref[0] << ' ' << contact->solref[1] << "\" solimp=\"";
      for (std::size_t k = 0; k < contact->solimp.size(); ++k) x << (k ? " " : "") << contact->solimp[k];
      x << "\" margin=\"" << contact->margin << "\" gap=\"" << contact->gap << '"';
    }
    x << "/>\n";
  }
  x << "  </contact>\n</mujoco>\n";
  return x.str();
}

// The ground load, and modal damping's -C v, at every evaluation of the dynamics.
class FloorLoad : public Control {
 public:
  FloorLoad(const BuildingModel& md, const Scales& s) : load_(md.scene.pulse), s_(s), n_(md.n_floors) {
    mass_ = md.m / s.mass;
    if (md.scene.damping == BuildingDamping::modal) c_ = md.C * (s.time / s.mass);
    force_.setZero(n_);
  }
  void evaluate(const mjModel*, mjData* d) override {
    const double a = load_.accel(d->time * s_.time) * s_.time * s_.time / s_.length;
    if (c_.size() > 0) {
      force_.noalias() = c_ * Eigen::Map<const Eigen::VectorXd>(d->qvel, n_);
      for (int i = 0; i < n_; ++i) d->qfrc_applied[i] = -mass_(i) * a - force_(i);
    } else {
      for (int i = 0; i < n_; ++i) d->qfrc_applied[i] = -mass_(i) * a;
    }
  }

 private:
  LoadCursor load_;
  Scales s_;
  int n_;
  Eigen::VectorXd mass_, force_;
  Eigen::MatrixXd c_;  // modal damping in model units; empty for Rayleigh (the elements carry it)
};

// The n steps of h; the status and message of a run that stopped early go into r.
void run(const BuildingModel& md, const Scales& s, double h, double h_model, long n, const Settings& set,
         mjModel* m, mjData* d, BuildingsResult& r, buildings::FloorPeaks& peaks) {
  const int nf = md.n_floors;
  const std::size_t nc = md.contacts.size();
  // Per geom: the contact whose right floor it is, or -1 (each floor is the right end of one at most).
  std::vector<int> contact_of_geom(static_cast<std::size_t>(m->ngeom), -1);
  for (std::size_t j = 0; j < nc; ++j) {
    const int g = mj_name2id(m, mjOBJ_GEOM, ("g" + std::to_string(md.contacts[j].i_right)).c_str());
    if (g >= 0) contact_of_geom[static_cast<std::size_t>(g)] = static_cast<int>(j);
  }
  FloorLoad load(md, s);
  std::vector<double> u(static_cast<std::size_t>(nf), 0.0), v(u);
  std::vector<char> touched(nc, 0), now(nc, 0);
  const double plastic = kRestitutionFloor * md.speed_scale();
  const double speed = s.length / s.time;
  peaks.sample(0.0, u.data());
  Deadline deadline(set);
  long k = 0;
  const auto stop = [&](Status st, const std::string& why) {
    r.status = st;
    r.message = why + " at step " + std::to_string(k) + " (t = " + format_number(static_cast<double>(k) * h) + ")";
  };
  for (; k < n; ++k) {
    d->time = static_cast<double>(k) * h_model;  // from the step's index, not MuJoCo's running sum
    {
      LoadScope scope(load);
      mj_step(m, d);
    }
    bool bad = false;
    for (int w : {mjWARN_BADQPOS, mjWARN_BADQVEL, mjWARN_BADQACC}) bad = bad || d->warning[w].number > 0;
    if (bad) {
      ++k;
      stop(Status::nan, "MuJoCo found a NaN, inf or |value| > 1e10 in its state and reset it");
      break;
    }
    // The contacts that pushed at the step's last evaluation; a new one approaching at the
    // step's start (the state in u, v) is an impact.
    std::fill(now.begin(), now.end(), 0);
    for (int c = 0; c < d->ncon; ++c) {
      const mjContact& con = d->contact[c];
      const int j = contact_of_geom[static_cast<std::size_t>(std::max(con.geom1, con.geom2))];
      if (j >= 0 && con.efc_address >= 0 && d->efc_force[con.efc_address] > 0.0) now[static_cast<std::size_t>(j)] = 1;
    }
    for (std::size_t j = 0; j < nc; ++j) {
      const FloorContact& fc = md.contacts[j];
      const double rate = v[static_cast<std::size_t>(fc.i_right)] - v[static_cast<std::size_t>(fc.i_left)];
      if (now[j] && !touched[j] && -rate > plastic) peaks.impact(j, static_cast<double>(k + 1) * h, -rate);
      touched[j] = now[j];
    }
    for (int i = 0; i < nf; ++i) {
      u[static_cast<std::size_t>(i)] = d->qpos[i] * s.length;
      v[static_cast<std::size_t>(i)] = d->qvel[i] * speed;
    }
    if (!buildings::end_step(md, k, n, h, u.data(), v.data(), peaks, &deadline, r)) {
      ++k;
      break;
    }
  }
  r.events = k;
  if (const Warnings w = take_warnings(); w.count > 0)
    r.message += (r.message.empty() ? "" : "; ") + std::string("MuJoCo warned ") + std::to_string(w.count) +
                 " times (first: " + w.first + ")";
}

}  // namespace

}  // namespace floors

buildings::BuildingsResult solve_buildings(const BuildingModel& model, const Settings& settings) {
  if (std::string why = validate(model.scene); !why.empty()) return buildings::failed(why);
  if (std::string why = check(settings); !why.empty()) return buildings::failed(why);
  const std::optional<Config> config = kVariants.find(settings.variant);
  if (!config) return buildings::failed("unknown variant '" + settings.variant + "'");
  buildings::BuildingsResult r;
  long n = 0;
  if (!buildings::plan_steps(model, settings, kDefaultSteps, r, n)) return r;
  buildings::FloorPeaks peaks(model);
  try {
    prepare_process();
    const floors::Scales s = floors::scales_of(model, *config);
    const double h_model = r.step / s.time;
    std::optional<ContactParameters> contact;
    if (config->calibrated) contact = calibrated_contact(model.scene.eps, contact_steps(settings), h_model);
    std::string error;
    ModelPtr m = compile(floors::scene_xml(model, *config, s, h_model, contact ? &*contact : nullptr), error);
    if (!m) return buildings::failed("MuJoCo could not compile the model: " + error, r.step);
    DataPtr d(mj_makeData(m.get()));
    if (!d) return buildings::failed("MuJoCo could not make its data", r.step);
    (void)take_warnings();  // only this run's steps count
    floors::run(model, s, r.step, h_model, n, settings, m.get(), d.get(), r, peaks);
  } catch (const std::exception& e) {
    r.status = Status::failed;
    r.message = e.what();
  }
  peaks.into(r);
  return r;
}

}  // namespace pb::mujoco
