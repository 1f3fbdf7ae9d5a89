#pragma once
// Whole contacts, as a soft-contact engine has them (MuJoCo's calibrated spring-dampers,
// Simbody's Hunt-Crossley elements): a contact is closed over the steps in which it acts,
// and ends when its force does. Counts the impacts (closures while approaching) and measures
// the restitution of the isolated ones over the whole contact, -g'(end) / g'(onset): the only
// contact closed from its onset to its end, approaching faster than kRestitutionFloor
// a_p / w_p. A soft contact has no persistent phase of its own: contact_phases stays 0.

#include <vector>

#include "cases/system.hpp"
#include "kit/isolated_restitution.hpp"
#include "kit/solver.hpp"

namespace pb {

class WholeContacts {
 public:
  explicit WholeContacts(const System& sys);

  // Contact j acted (touched) or did not in the step that started at velocities v.
  void step(int j, bool touched, const double* v);
  // Writes impacts, contact_phases and the restitution of the isolated contacts.
  void finish(Result& r) const;

 private:
  const System& sys_;
  std::vector<char> closed_, isolated_;
  std::vector<double> onset_;
  int n_closed_ = 0;
  long impacts_ = 0;
  double floor_;
  IsolatedRestitution restitution_;
};

}  // namespace pb
