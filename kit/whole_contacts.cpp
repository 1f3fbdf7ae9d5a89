#include "kit/whole_contacts.hpp"

namespace pb {

WholeContacts::WholeContacts(const System& sys)
    : sys_(sys),
      closed_(ix(sys.n_contacts()), 0),
      isolated_(ix(sys.n_contacts()), 0),
      onset_(ix(sys.n_contacts()), 0.0),
      floor_(kRestitutionFloor * sys.a_p / sys.pulse.w) {}

void WholeContacts::step(int j, bool touched, const double* v) {
  const auto jj = ix(j);
  const double rate = sys_.gap_rate(j, v);
  if (touched && !closed_[jj]) {
    if (rate < 0.0) ++impacts_;
    for (char& flag : isolated_) flag = 0;  // nobody is alone now
    isolated_[jj] = n_closed_ == 0 && rate < -floor_;
    onset_[jj] = rate;
    closed_[jj] = 1;
    ++n_closed_;
  } else if (!touched && closed_[jj]) {
    if (isolated_[jj]) restitution_.add(-rate / onset_[jj]);
    isolated_[jj] = 0;
    closed_[jj] = 0;
    --n_closed_;
  }
}

void WholeContacts::finish(Result& r) const {
  r.impacts = impacts_;
  r.contact_phases = 0;
  r.restitution_over_contacts = true;
  restitution_.write(r);
}

}  // namespace pb
