#include "solvers/mujoco/model.hpp"

#include <algorithm>
#include <cstring>
#include <iomanip>
#include <mutex>
#include <sstream>
#include <stdexcept>

namespace pb::mujoco {

namespace {

thread_local Control* t_load = nullptr;
thread_local Warnings t_warnings;

void on_control(const mjModel* m, mjData* d) {
  if (t_load) t_load->evaluate(m, d);
}

void on_warning(const char* message) {
  if (t_warnings.count++ == 0) t_warnings.first = message ? message : "";
}

[[noreturn]] void on_error(const char* message) {
  throw std::runtime_error(std::string("MuJoCo error: ") + (message ? message : "?"));
}

std::mutex& compile_lock() {
  static std::mutex lock;
  return lock;
}

// RK4's weights of its stages in the step's velocity update; one stage for the others.
constexpr double kRk4Weights[4] = {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0};

void attributes(std::ostream& out, const char* name, const double* values, int n) {
  out << ' ' << name << "=\"";
  for (int i = 0; i < n; ++i) out << (i ? " " : "") << values[i];
  out << '"';
}

}  // namespace

void prepare_process() {
  static std::once_flag once;
  std::call_once(once, [] {
    mjcb_control = &on_control;
    mju_user_warning = &on_warning;
    mju_user_error = &on_error;
  });
}

Warnings take_warnings() {
  Warnings w = std::move(t_warnings);
  t_warnings = Warnings{};
  return w;
}

Units units_of(const System& sys, const Config& config) {
  if (!config.calibrated) return {};
  return {sys.length_scale(), 1.0 / sys.pulse.w};
}

std::string scene_xml(const System& sys, const Config& config, const Units& units, double h_model,
                      const ContactParameters* contact) {
  const double L = units.length, T = units.time;
  const double radius = kRadius * sys.length_scale() / L;
  const double delta = sys.delta / L;
  const int nc = sys.n_contacts();
  std::ostringstream x;
  x << std::setprecision(17);
  x << "<mujoco model=\"pounding\">\n";
  // Every contact is one row (condim 1) of one explicit pair: no more than nc of either.
  // MuJoCo 2.2.2 sizes its stack from njmax and nv alone, too small for the implicit
  // integrator's dense nv x nv matrices: a 100-body chain overflowed it in compilation
  // with 20 nv^2 + 5000 and ran with 30 nv^2 (1000 bodies too); 60 nv^2 doubles that
  // (4.8 MB at 100 bodies, 480 MB at 1000).
  const int nv = sys.n_bodies();
  x << "  <size nconmax=\"" << std::max(nc, 1) << "\" njmax=\"" << std::max(nc, 1) << '"';
  if (config.integrator == Integrator::implicit) x << " nstack=\"" << 5000 + 60 * nv * nv << '"';
  x << "/>\n";
  x << "  <option timestep=\"" << h_model << "\" gravity=\"0 0 0\" integrator=\""
    << (config.integrator == Integrator::euler ? "Euler" : config.integrator == Integrator::rk4 ? "RK4" : "implicit")
    << '"';
  // The calibrated contacts ask the solver for its answer to round-off (a single row is
  // solved exactly by Newton's method; the default tolerance 1e-8 can stop a coupled pair
  // early).
  if (config.calibrated) x << " solver=\"Newton\" iterations=\"100\" tolerance=\"1e-12\"";
  x << "/>\n  <worldbody>\n";
  if (sys.wall)
    x << "    <geom name=\"wall\" type=\"plane\" pos=\"" << -radius - delta
      << " 0 0\" zaxis=\"1 0 0\" size=\"0 0 1\" contype=\"0\" conaffinity=\"0\"/>\n";
  for (int i = 0; i < sys.n_bodies(); ++i) {
    const Body& b = sys.bodies[ix(i)];
    // Mass in the System's unit; stiffness and damping in the model's time unit.
    x << "    <body name=\"b" << i << "\" pos=\"" << static_cast<double>(i) * (2.0 * radius + delta) << " 0 0\">\n";
    x << "      <joint name=\"j" << i << "\" type=\"slide\" axis=\"1 0 0\" stiffness=\"" << b.k * T * T
      << "\" damping=\"" << b.c * T << "\"/>\n";
    x << "      <inertial pos=\"0 0 0\" mass=\"" << b.m << "\" diaginertia=\"" << b.m << ' ' << b.m << ' ' << b.m
      << "\"/>\n";
    x << "      <geom name=\"g" << i << "\" type=\"sphere\" size=\"" << radius
      << "\" contype=\"0\" conaffinity=\"0\"/>\n    </body>\n";
  }
  x << "  </worldbody>\n  <contact>\n";
  for (int j = 0; j < nc; ++j) {
    const int l = sys.left(j), r = sys.right(j);
    x << "    <pair geom1=\"" << (l == kWall ? std::string("wall") : "g" + std::to_string(l)) << "\" geom2=\"g" << r
      << "\" condim=\"1\"";
    if (contact) {
      attributes(x, "solref", contact->solref.data(), 2);
      attributes(x, "solimp", contact->solimp.data(), 5);
      x << " margin=\"" << contact->margin << "\" gap=\"" << contact->gap << '"';
    }
    x << "/>\n";
  }
  x << "  </contact>\n</mujoco>\n";
  return x.str();
}

ModelPtr compile(const std::string& xml, std::string& error) {
  mjVFS vfs;
  mj_defaultVFS(&vfs);
  const char* name = "pounding.xml";
  ModelPtr model;
  char message[1000] = "";
  if (mj_makeEmptyFileVFS(&vfs, name, static_cast<int>(xml.size())) != 0) {
    error = "MuJoCo's virtual file system refused the model";
  } else {
    std::memcpy(vfs.filedata[mj_findFileVFS(&vfs, name)], xml.data(), xml.size());
    std::lock_guard<std::mutex> lock(compile_lock());
    model.reset(mj_loadXML(name, &vfs, message, sizeof message));
    if (!model) error = message[0] ? message : "MuJoCo could not compile the model";
  }
  mj_deleteVFS(&vfs);
  return model;
}

Load::Load(const System& sys, const Units& units, const std::vector<int>& contact_of_geom, int stages)
    : sys_(sys),
      load_(sys.pulse),
      units_(units),
      contact_of_geom_(contact_of_geom),
      stages_(stages),
      row_(ix(sys.n_contacts()), -1),
      force_(ix(sys.n_contacts()), 0.0),
      touched_(ix(sys.n_contacts()), 0) {
  for (const Body& b : sys.bodies) mass_.push_back(b.m);
}

void Load::begin_step() {
  evaluations_ = 0;
  std::fill(force_.begin(), force_.end(), 0.0);
  std::fill(touched_.begin(), touched_.end(), 0);
  std::fill(row_.begin(), row_.end(), -1);
}

void Load::collect(const mjData* d) {
  if (evaluations_ == 0 || evaluations_ > stages_) return;
  const double w = stages_ == 4 ? kRk4Weights[evaluations_ - 1] : 1.0;
  for (std::size_t j = 0; j < row_.size(); ++j)
    if (row_[j] >= 0) force_[j] += w * d->efc_force[row_[j]];
}

void Load::evaluate(const mjModel* m, mjData* d) {
  (void)m;
  // The previous evaluation's forces are still in efc_force: MuJoCo writes them only in
  // its constraint solver, which runs after this callback (checked by the test
  // HistoryForcesAreTheContactImpulseOfEachStep).
  collect(d);
  std::fill(row_.begin(), row_.end(), -1);
  for (int c = 0; c < d->ncon; ++c) {
    const mjContact& con = d->contact[c];
    const int j = contact_of_geom_[ix(std::max(con.geom1, con.geom2))];
    if (j < 0 || con.efc_address < 0) continue;
    row_[ix(j)] = con.efc_address;
    touched_[ix(j)] = 1;
  }
  ++evaluations_;
  // The pulse at this evaluation's own time, in model units (a_g T^2 / L).
  const double a = load_.accel(d->time * units_.time) * units_.time * units_.time / units_.length;
  for (std::size_t i = 0; i < mass_.size(); ++i) d->qfrc_applied[i] = -mass_[i] * a;
}

bool Load::end_step(const mjData* d) {
  collect(d);
  return evaluations_ == stages_;
}

LoadScope::LoadScope(Control& load) : before_(t_load) { t_load = &load; }
LoadScope::~LoadScope() { t_load = before_; }

}  // namespace pb::mujoco
