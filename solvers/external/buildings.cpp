// The external solver on the buildings scene (solvers/external/external.hpp, solve_buildings):
// the scene's case document to the program, its answer read back into a BuildingsResult
// (programs/buildings_protocol.hpp), with every outcome of the program a result as for the single
// oscillators (external.cpp): it cannot start, exits badly, answers something that is not an
// answer (failed, naming the field), passes the time limit or is stopped (time-limit).

#include <cmath>
#include <exception>
#include <string>

#include "kit/buildings_result.hpp"
#include "programs/buildings_protocol.hpp"
#include "programs/protocol.hpp"
#include "solvers/external/external.hpp"

namespace pb::external {

buildings::BuildingsResult solve_buildings(const BuildingModel& model, const Settings& settings) {
  buildings::BuildingsResult r;
  r.t_end = model.t_end;
  const auto finish = [&](Status status, std::string message) {
    buildings::BuildingsResult out = buildings::failed(std::move(message), r.step);
    out.status = status;
    out.t_end = model.t_end;
    return out;
  };
  programs::CommandWords command;
  Status status = Status::ok;
  if (std::string why = cannot_start(settings, command, status); !why.empty()) return finish(status, why);
  // The step asked for (--steps, --wh), planned as the scene's time-steppers plan theirs: the
  // program gets the h they would take, and a step they would refuse is refused here.
  if (settings.steps > 0 || settings.wh > 0.0 || settings.h_s > 0.0) {
    long n = 0;
    if (!buildings::plan_steps(model, settings, 1, r, n)) return r;
  }
  const programs::CaseDocument document = programs::buildings_case_document(model, settings, r.step);
  if (!document.error.empty()) return finish(Status::failed, document.error);
  // What a Python callable raises is the point's failed result, as a sweep makes it a failed row
  // for the oscillators (sweep/sweep.cpp): no buildings sweep catches it.
  Exchanged x;
  try {
    x = exchange_document(document.text, command, settings);
  } catch (const std::exception& e) {
    return finish(Status::failed, programs::printable_line(e.what()));
  }
  if (!x.why.empty()) {
    r = finish(x.status, x.why);
  } else if (std::string bad = programs::read_buildings_answer(x.run.out, model, r, x.deadline); !bad.empty()) {
    std::string message = answer_refused(x, bad, status);
    r = finish(status, std::move(message));
  }
  // One printable line of UTF-8 in a row, as the single oscillators' (external.cpp).
  r.message = programs::printable_line(r.message);
  return r;
}

}  // namespace pb::external
