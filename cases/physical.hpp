#pragma once
// A case given by its physical quantities instead of its Pi terms (cases/README.md,
// "Physical units"): natural periods in s, masses in kg, the gap in m; the pulse by a_p
// (m/s^2) and w_p (or its period tp, s) as any case; a record in its file's units. This is
// the one place that turns them into the Pi terms (make_system() then maps those back, so
// a physical case and the Pi-term case it gives are one Case), and the one place of the
// other conversions between SI and Pi terms that the rooms above call: a contact stiffness
// (--k-contact, a settings list's k_contact) into K, a step in seconds into w_max h, a
// velocity into its Pi term, and the units of length and mass that turn a result's Pi terms
// into metres and newtons (rows/result_fields.cpp).
//
// The fields are declared once, as kCaseFields are: their flags (--t0, --gap, ...), case-set
// keys, JSON keys and row columns derive from kPhysicalFields. A value not given is NaN.

#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

#include "cases/case.hpp"
#include "cases/fields.hpp"

namespace pb {

struct System;

// One physical field: the Pi term it gives (empty for m0, which only sets the unit of the
// other masses), and which scenes use it (as CaseField::use).
struct PhysicalField {
  std::string_view name;
  double Physical::* member;
  std::string_view pi;  // the kCaseFields name it replaces
  FieldUse use;
  std::string_view help;
};

inline constexpr std::array<PhysicalField, 11> kPhysicalFields = {{
    {"t0", &Physical::t0, "pi2", FieldUse::every, "Physical units: natural period of body 0 (s), instead of --pi2"},
    {"t1", &Physical::t1, "pi5", FieldUse::body1, "Physical units: natural period of body 1 (s; chain: the odd bodies), instead of --pi5"},
    {"t2", &Physical::t2, "pi7", FieldUse::body2, "Physical units: natural period of body 2 (s, row3), instead of --pi7"},
    {"m0", &Physical::m0, "", FieldUse::every, "Physical units: mass of body 0 (kg; default 1, the other masses then ratios to it)"},
    {"m1", &Physical::m1, "pi6", FieldUse::body1, "Physical units: mass of body 1 (kg; chain: the odd bodies; default m0), instead of --pi6"},
    {"m2", &Physical::m2, "pi8", FieldUse::body2, "Physical units: mass of body 2 (kg, row3; default m0), instead of --pi8"},
    {"gap", &Physical::gap, "pi3", FieldUse::every, "Physical units: the gap delta (m) of every contact, instead of --pi3"},
    // Issue 39's yielding: Pi_y = u_y w_p^2 / a_p; not given (or inf), elastic.
    {"uy0", &Physical::uy0, "pi_y0", FieldUse::not_chain, "Physical units: yield displacement of body 0 (m; inf: elastic), instead of --pi-y0"},
    {"uy1", &Physical::uy1, "pi_y1", FieldUse::pair_row3, "Physical units: yield displacement of body 1 (m, pair, row3), instead of --pi-y1"},
    {"uy2", &Physical::uy2, "pi_y2", FieldUse::body2, "Physical units: yield displacement of body 2 (m, row3), instead of --pi-y2"},
    {"uy", &Physical::uy, "pi_y", FieldUse::chain, "Physical units: yield displacement of every chain body (m), instead of --pi-y"},
}};

// The masses m0, m1, m2 (kg) lie in [kMinMass, kMaxMass]. A run is solved with m0 = 1 (it
// cancels from Pi1), and a contact force is reported in N as the run's force times m0: at
// m0 = 1e308 that overflowed, and a compliant run said ok with contact_force_max null
// (issue 46). Within 1e-30..1e30 kg (a grain of sand to two hundred thousand Earths) a force
// stays within 1e30 of the run's own, itself bounded by the valid domain (case.hpp) far below
// overflow; and a physical stiffness k / (m0 w0^2) likewise.
inline constexpr double kMinMass = 1e-30, kMaxMass = 1e30;

// Whether x is a value the field takes, and the reason it is not ("must be finite and > 0").
// NaN is no value: it is Physical's "not given", so where a field is read (a flag, a case-set
// key, a keyword) a NaN given must be refused with physical_rule, as --pi-y0 nan is.
bool physical_value_ok(const PhysicalField& field, double x);
std::string physical_rule(const PhysicalField& field);

// validate()'s "field: reason" for a case in physical units, where the field is a Pi term
// that a physical field gave (pi2 from t0, pi3 from gap, pi5 from t1, ...): the same reason
// under the physical field the user gave, with the Pi term's value ("t0: gives pi2 = 2 pi /
// (t0 w_p) = inf (pi2: must be finite and > 0)"). Any other message is returned as it is.
std::string physical_reason(const Case& c, const std::string& field_reason);

// Whether a scene has the body a physical field describes.
bool used_by(const PhysicalField& field, Scene scene);

// Whether the case was given in physical units (any physical field given).
bool physical(const Case& c);

// The Pi terms of c from c.physical and c's pulse scale (a_p, w_p, final), for the fields
// its scene uses: Pi2 = w0 / w_p (w0 = 2 pi / t0), Pi3 = gap w_p^2 / a_p, Pi5 = w0 / w1,
// Pi6 = m0 / m1, Pi7 = w0 / w2, Pi8 = m0 / m2, Pi_y = u_y w_p^2 / a_p (uy0 .. uy). Returns "field: reason" for a value that is
// missing (t0, gap; t1 where the scene has body 1, t2 where it has body 2) or not one the
// field takes (physical_rule), or for an a_p or w_p outside the domain (check_scale: the Pi
// terms are computed from them, so a bad one is named as itself, not as the gap).
std::optional<std::string> apply_physical(Case& c);

// Where a physical case's unit of frequency w_p comes from when neither w_p nor tp is
// given: a record's mean frequency 2 pi / T_m (NaN for one without a mean period); every
// other pulse has no default (its tp is the pulse's own period).
double default_w_p(const Case& c);

// The Pi term K of a physical contact stiffness k (N/m for a linear element, N/m^1.5 for the
// Hertz family): K = k / (m0 w0^2), times sqrt(L) for the Hertz family, L the contact's
// length (System::contact_length_scale()). k is in the case's own units, so c must be given
// in physical units (its m0 the unit of mass, default 1 kg); the result is K whatever the
// a_p and w_p of its Pi terms (tested).
double stiffness_pi_term(const Case& c, double k, bool hertz);

// The largest relative approach velocity at an impact (m/s) as a Pi term: over a_p / w_p.
inline double velocity_pi_term(const Case& c, double v) { return v * c.w_p / c.a_p; }

// A fixed step h (s, the system's time) as its Pi form w_max h = 2 pi h / t_min, the form of
// Settings::wh (kit/solver.hpp: time_step maps it back).
double step_pi_term(const System& s, double h);

// The case's unit of length, a_p / w_p^2: a length in metres is its Pi term times it (m when
// the case was given in physical units, or a pulse's a_p and w_p in SI).
inline double length_unit(const Case& c) { return c.a_p / (c.w_p * c.w_p); }

// The case's unit of mass: its m0 as given (kg), 1 otherwise (make_system's m0). A force per
// unit of m0 times it is in N.
inline double mass_unit(const Case& c) { return std::isnan(c.physical.m0) ? 1.0 : c.physical.m0; }

}  // namespace pb
