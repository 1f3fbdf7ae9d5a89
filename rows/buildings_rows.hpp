#pragma once
// The rows of a buildings sweep (`poundbench spectrum` over a buildings case set): one CSV row
// per floor of every building of every point, floor 1 first, so that a spectrum of any floor's
// peak or any storey's drift is a selection of rows. Beside the solver's peaks, each row holds
// the exact reference's no-contact peaks of the same floor (the response without pounding) and
// the impacts of the contact between this floor and the right neighbour's, and the gap that
// avoids pounding there with the rules' gaps (empty for the rightmost building, or a floor that
// touches nothing). docs/cli.md lists the columns.

#include <ostream>
#include <string>
#include <vector>

#include "cases/buildings_set.hpp"
#include "kit/separation.hpp"
#include "kit/buildings_result.hpp"

namespace pb {

// What a sweep found for one point.
struct BuildingsPoint {
  buildings::BuildingsResult result;      // the solver's
  buildings::BuildingsResult no_contact;  // the exact reference's, every contact removed (free_motion)
  // Per contact of the scene (as BuildingModel::contacts): the gap that avoids pounding and the
  // rules, from no_contact; empty where that did not finish ok.
  std::vector<FloorSeparation> separation;
  double seconds = 0.0, cpu_seconds = 0.0;  // the solver's solve (sweep/stopwatch.hpp)
  double a_p = 1.0, w_p = 1.0;  // the point's scales (BuildingModel's)
};

std::string buildings_csv_header();
// The point's rows, one line each (with its end), appended to out. settings: the solver's
// describe() of the run.
void append_buildings_rows(std::string& out, const BuildingCase& c, std::size_t point, std::string_view solver,
                           std::string_view settings, const BuildingsPoint& p);

}  // namespace pb
