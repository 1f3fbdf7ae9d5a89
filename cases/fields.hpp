#pragma once
// Every number of a Case, declared once (as MuJoCo's mjxmacro.h declares its model's
// fields): its name, its member, the scenes that use it, its unit and its help. The
// command-line flags (--name with '_' as '-'), the CSV columns and the JSON keys of a row,
// the key that matches a row with a stored one and the reading of rows back are derived
// from this table, and so are the case-set keys (cases/case_set.cpp), so adding a number to
// Case takes its member, a row here, and its rule in validate() and make_system(). The
// case-set reader fixes only the order in which a family's lists expand (a new number
// expands just outside pi2, cases/README.md).
//
// The scene, pulse and directivity are names, not numbers, and the family a label: each
// has one spelling everywhere already (name()/parse_*() in case.hpp). A record's file is
// text, a field of the table like the numbers. Fields that only some pulses use (the pulse
// models' shapes, the record) are columns at the end of a row, after those older files have.
//
// An alias (kCaseAliases) is a second way to give a field: `tp` gives w_p as a period. It is
// a flag and a case-set key, not a column.

#include <array>
#include <limits>
#include <string>
#include <string_view>

#include "cases/case.hpp"

namespace pb {

// Which cases use a field: every one; by scene, those with a body 1 (pair, row3, and a
// chain's odd bodies), row3's body 2, the chain alone, every scene but the chain, pair and
// row3 (a yielding body's own Pi_y: a chain gives one for every body); by pulse, makris-c,
// mp, record.
enum class FieldUse { every, body1, body2, chain, not_chain, pair_row3, makris_c, mp, record };

// Whether a use is a pulse's (the field's column comes at the end of a row).
constexpr bool pulse_use(FieldUse use) {
  return use == FieldUse::makris_c || use == FieldUse::mp || use == FieldUse::record;
}

struct CaseField {
  std::string_view name;  // case-set key, CSV column, JSON key
  double Case::* number;  // one of these three is set
  int Case::* integer;
  FieldUse use;
  bool required;          // no default: a case given by flags must state it
  std::string_view help;  // with its unit, for --help
  std::string Case::* text = nullptr;
  // A field of yielding (cases/README.md, "Yielding"): its column comes after every other
  // one, and at its default (a Pi_y of infinity: elastic, as before; alpha 0) it is absent,
  // an empty column, no JSON key and no part of a row's key, so that an elastic case's row
  // is the row it always was.
  bool yielding = false;
  // A field added after every other (a record's scaling): its column comes last, and at its
  // default it is absent as a yielding field is.
  bool late = false;

  // A number's value; NaN for text (which case_key and the rows take as text).
  double get(const Case& c) const {
    return number ? c.*number : integer ? static_cast<double>(c.*integer) : std::numeric_limits<double>::quiet_NaN();
  }
};

inline constexpr std::array<CaseField, 26> kCaseFields = {{
    {"pi2", &Case::pi2, nullptr, FieldUse::every, true, "Pi2 = w0 / w_p"},
    {"pi3", &Case::pi3, nullptr, FieldUse::every, true, "Pi3 = delta w_p^2 / a_p (gap)"},
    {"eps", &Case::eps, nullptr, FieldUse::every, true, "Coefficient of restitution, in [0, 1]"},
    {"pi5", &Case::pi5, nullptr, FieldUse::body1, true, "Pi5 = w0 / w1 (pair, row3; chain: the odd bodies)"},
    {"pi6", &Case::pi6, nullptr, FieldUse::body1, true, "Pi6 = m0 / m1 (pair, row3; chain: the odd bodies)"},
    {"pi7", &Case::pi7, nullptr, FieldUse::body2, true, "Pi7 = w0 / w2 (row3)"},
    {"pi8", &Case::pi8, nullptr, FieldUse::body2, true, "Pi8 = m0 / m2 (row3)"},
    {"xi", &Case::xi, nullptr, FieldUse::every, false, "Damping ratio of every body"},
    {"n_free", &Case::n_free, nullptr, FieldUse::every, false, "Free-vibration periods T_max after the pulse"},
    {"a_p", &Case::a_p, nullptr, FieldUse::every, false,
     "Pulse amplitude a_p (Pi1 does not depend on it); a record: the a_p of its Pi terms, default its peak"},
    {"w_p", &Case::w_p, nullptr, FieldUse::every, false,
     "Pulse circular frequency w_p (Pi1 does not depend on it); a record: default 2 pi / T_m, its mean period's"},
    {"bodies", nullptr, &Case::bodies, FieldUse::chain, true, "Chain: number of bodies N, 2 to 1000"},
    {"kick", &Case::kick, nullptr, FieldUse::chain, false,
     "Chain: start velocity of body 0 (the left end) towards +x, times w_p / a_p"},
    {"cycles", nullptr, &Case::cycles, FieldUse::makris_c, true, "makris-c: the pulse's cycles n, 1 to 100"},
    {"mp_gamma", &Case::mp_gamma, nullptr, FieldUse::mp, true,
     "mp: gamma, the pulse's oscillatory character, > 1 (it lasts gamma T_p)"},
    {"mp_nu", &Case::mp_nu, nullptr, FieldUse::mp, true, "mp: nu, the phase of its velocity, in degrees"},
    {"record", nullptr, nullptr, FieldUse::record, true,
     "record: the accelerogram, a two-column CSV (t, a_g) or a PEER NGA .AT2 file (values in g)", &Case::record},
    {"pi_y0", &Case::pi_y0, nullptr, FieldUse::not_chain, false,
     "Pi_y0 = u_y0 w_p^2 / a_p: body 0 yields at u_y0 (bilinear, kinematic hardening); inf: elastic", nullptr, true},
    {"pi_y1", &Case::pi_y1, nullptr, FieldUse::pair_row3, false, "Pi_y1 = u_y1 w_p^2 / a_p (pair, row3); inf: elastic",
     nullptr, true},
    {"pi_y2", &Case::pi_y2, nullptr, FieldUse::body2, false, "Pi_y2 = u_y2 w_p^2 / a_p (row3); inf: elastic", nullptr,
     true},
    {"pi_y", &Case::pi_y, nullptr, FieldUse::chain, false,
     "Chain: Pi_y = u_y w_p^2 / a_p of every body; inf: elastic", nullptr, true},
    {"alpha", &Case::alpha, nullptr, FieldUse::every, false,
     "Post-yield stiffness over the elastic one, in [0, 1), of every yielding body (0: elastic-perfectly plastic)",
     nullptr, true},
    {"record_scale", &Case::record_scale, nullptr, FieldUse::record, false,
     "record: a factor on its accelerations (1: as recorded); or give pga, pga_g or sa", nullptr, false, true},
    {"pga", &Case::pga, nullptr, FieldUse::record, false,
     "record: scale it to this peak ground acceleration (m/s^2)", nullptr, false, true},
    {"sa", &Case::sa, nullptr, FieldUse::record, false,
     "record: scale it to this pseudo-spectral acceleration w^2 max|u| (m/s^2) at sa_period, damping xi", nullptr,
     false, true},
    {"sa_period", &Case::sa_period, nullptr, FieldUse::record, false, "record: the period of sa (s)", nullptr, false,
     true},
}};

// A field's value from one case into another (a number, a whole number or text).
inline void copy_field(const CaseField& field, const Case& from, Case& to) {
  if (field.number)
    to.*field.number = from.*field.number;
  else if (field.integer)
    to.*field.integer = from.*field.integer;
  else
    to.*field.text = from.*field.text;
}

// Whether a field is written for a case (a row's column, a JSON key, a part of the row's
// key): the case uses it and, for a field of yielding, it is not at its default.
bool written(const CaseField& field, const Case& c);

// Whether a case of this scene and pulse has the bodies (or start, or load) a field describes.
bool used_by(const CaseField& field, Scene scene, PulseShape pulse);
// The same for a use that is a scene's (every use but the pulses').
bool scene_uses(FieldUse use, Scene scene);
inline bool used_by(const CaseField& field, const Case& c) { return used_by(field, c.scene, c.pulse); }

// A second name for a field, with its value converted: `tp` (a pulse period) gives
// w_p = 2 pi / tp. A flag and a case-set key; giving both it and its field is an error.
struct CaseAlias {
  std::string_view name;
  std::string_view field;     // the field it gives
  double (*convert)(double);  // its value to the field's
  std::string_view help;
};
double period_to_frequency(double tp);
double g_to_si(double a_g);  // an acceleration in g as m/s^2 (kStandardGravity)
inline constexpr std::array<CaseAlias, 2> kCaseAliases = {{
    {"tp", "w_p", &period_to_frequency, "Pulse period T_p: sets w_p = 2 pi / tp (a record's identified pulse)"},
    {"pga_g", "pga", &g_to_si, "record: pga in g (9.80665 m/s^2)"},
}};

// The command-line flag of a field (of a Case, or of solver Settings): "--n-free" for n_free.
std::string flag_of(std::string_view name);
inline std::string flag_of(const CaseField& field) { return flag_of(field.name); }

}  // namespace pb
