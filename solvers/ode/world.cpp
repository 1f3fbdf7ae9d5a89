#include "solvers/ode/world.hpp"

#include <cstdarg>
#include <cstdio>
#include <mutex>

namespace pb::ode {

namespace {

thread_local std::string t_messages;
thread_local long t_lcp_failures = 0;

// ODE calls this for dMessage on the thread that stepped; the default handler prints.
void keep_message(int number, const char* format, va_list args) {
  if (number == d_ERR_LCP) ++t_lcp_failures;
  char text[512];
  std::vsnprintf(text, sizeof text, format, args);
  if (!t_messages.empty()) t_messages += "; ";
  t_messages += "ODE message " + std::to_string(number) + ": " + text;
}

bool initialise_process() {
  if (dInitODE2(0) == 0) return false;
  dSetMessageHandler(&keep_message);
  return true;
}

}  // namespace

bool prepare_thread() {
  static std::once_flag once;
  static bool process_ok = false;
  std::call_once(once, [] { process_ok = initialise_process(); });
  if (!process_ok) return false;
  thread_local bool thread_ok = dAllocateODEDataForThread(dAllocateFlagBasicData) != 0;
  return thread_ok;
}

int quick_step(dWorldID world, double h, int rows) {
  if (rows < 2) return dWorldQuickStep(world, h);
  static std::mutex random_order;
  const std::lock_guard<std::mutex> lock(random_order);
  dRandSetSeed(0);
  return dWorldQuickStep(world, h);
}

long lcp_failures() { return t_lcp_failures; }

std::string take_messages() {
  std::string out;
  out.swap(t_messages);
  return out;
}

World::World() {
  threading_ = dThreadingAllocateSelfThreadedImplementation();
  if (threading_ == nullptr) return;
  world_ = dWorldCreate();
  if (world_ == nullptr) return;
  dWorldSetStepThreadingImplementation(world_, dThreadingImplementationGetFunctions(threading_), threading_);
  contacts_ = dJointGroupCreate(0);
}

World::~World() {
  // The group first: dWorldDestroy leaves grouped joints to their group.
  if (contacts_ != nullptr) dJointGroupDestroy(contacts_);
  if (world_ != nullptr) dWorldDestroy(world_);
  if (threading_ != nullptr) dThreadingFreeImplementation(threading_);
}

void configure_world(dWorldID w, const Config& config) {
  dWorldSetGravity(w, 0.0, 0.0, 0.0);
  dWorldSetERP(w, config.erp);
  dWorldSetCFM(w, config.cfm);
  dWorldSetContactMaxCorrectingVel(w, config.max_vel);
  dWorldSetContactSurfaceLayer(w, config.surface_layer);
  dWorldSetAutoDisableFlag(w, 0);
  dWorldSetDamping(w, 0.0, 0.0);
  if (config.stepper == Stepper::quickstep) {
    dWorldSetQuickStepNumIterations(w, config.iterations);
    dWorldSetQuickStepW(w, config.sor);
  }
}

}  // namespace pb::ode
