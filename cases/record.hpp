#pragma once
// A recorded ground acceleration: samples (t_i, a_i), linear between them, zero before the
// first and after the last. Read once by cases/ (case-set files, `run --record`) and shared
// read-only by every run that uses it (System::pulse holds a shared_ptr to it), so that a
// sweep over a record holds its samples once.
//
// Two formats, told apart by the file's extension (cases/README.md, "Records"):
//   .at2 (any case)  PEER NGA: a header (every line before the first line of numbers), one
//                    of whose lines gives NPTS and DT ("NPTS= 3930, DT= .0100 SEC", "NPTS=
//                    4800, dt= .005", "3930 .0100 NPTS, DT"), and whose lines may name the
//                    unit as a word (g, gal, cm/s^2, m/s^2; none named: g); then exactly NPTS
//                    values, any number per line, and after them only lines that do not start
//                    with a number (a trailer such as "*** End Data ***"). t_i = i DT
//                    (i = 0 .. NPTS-1) and a_i = value_i times the unit in m/s^2, g being
//                    9.80665 m/s^2 (the standard gravity: the NGA flatfiles' unit).
//   anything else    CSV: one sample per line, "t, a_g" (a_g in m/s^2, or any unit the
//                    case's a_p is given in), '#' lines are comments, blank lines are
//                    skipped, and a first line with no number in it is a header.
// Every sample time is finite and >= 0, and the times rise strictly; every value is finite;
// at least two samples and at most kMaxRecordSamples, not all zero. A bad record is a
// RecordError "<file>:<line>: <reason>".

#include <cstddef>
#include <filesystem>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace pb {

inline constexpr double kStandardGravity = 9.80665;  // m/s^2: an AT2 record's unit g
// The reference handles every sample as an event and allows 1e6 events per run by default
// (Settings::step_cap): 2e5 samples (over 16 minutes at 0.005 s, ten times NGA's longest
// records) leave room for the impacts.
inline constexpr std::size_t kMaxRecordSamples = 200'000;

struct RecordError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The mean period T_m of Rathje, Abrahamson & Bray (1998, J. Geotech. Geoenviron. Eng.
// 124(2):150-159), a record's characteristic period: T_m = sum(C_i^2 / f_i) / sum(C_i^2) over
// the Fourier amplitudes C_i of the record at the frequencies f_i in kMeanPeriodBand (Hz;
// times in seconds). The record is taken on an even grid of its mean spacing (linear between
// its samples), zero-padded to a power of two. NaN when no amplitude falls in the band (a
// record of fewer than two samples, or one with nothing between 0.25 and 20 Hz).
// cases/README.md gives its value on a pure harmonic.
inline constexpr double kMeanPeriodBand[2] = {0.25, 20.0};
double mean_period(const std::vector<double>& t, const std::vector<double>& a);

struct Record {
  std::string source;        // the file it was read from, as named
  std::vector<double> t, a;  // sample times (rising) and accelerations
  double peak = 0.0;         // max |a_i|: the record's peak ground acceleration
  // mean_period(t, a), computed once with the samples (an FFT), shared with them.
  double t_m = std::numeric_limits<double>::quiet_NaN();
  // The factor its accelerations carry over the file's (cases/record_scale.hpp): 1 as read.
  double scale = 1.0;
  double length() const { return t.back(); }
  // 2 pi / T_m: the record's mean circular frequency. It is the record's default w_p, the
  // characteristic frequency its Pi terms are measured against when the user gives neither
  // w_p nor tp (cases/README.md, "Records"); NaN when T_m is.
  double mean_frequency() const;
  // The record's own length scale, its peak over the square of its mean circular frequency
  // 2 pi / T_m: a length of the ground motion that the a_p and w_p of its Pi terms, a unit
  // of the user's choosing, do not move (a Hertz-type contact's, cases/README.md).
  double length_scale() const;
  // The sampling interval DT: the mean spacing (t_n-1 - t_0) / (n - 1), an AT2 file's DT.
  double interval() const { return (t.back() - t.front()) / static_cast<double>(t.size() - 1); }
};

// The step rule `record` (Settings::steps_per_sample = k, cases/README.md "Records"): the
// step h = DT / m, m the least whole number >= k with DT / m <= h_max (the step the other
// settings give: T_min / N, or wh's). So a step is never longer than T_min / N, takes at
// least k steps per sample, and m steps span a sample interval exactly: on a record evenly
// sampled from t = 0 (every AT2 file) every sample is a step's end, and no step straddles
// a kink of the piecewise-linear load.
double record_step(const Record& r, double h_max, int k);

// Why a record without a mean period (T_m NaN) needs its w_p given: one phrase, for the
// CLI's and the case sets' errors.
std::string no_mean_period_reason();

// The record in `text` (the format by `source`'s extension); throws RecordError.
Record parse_record(std::string_view text, std::string_view source);
// A record from its samples (the external protocol's), checked as a file's are, a sample's
// index (from 1) standing for its line; throws RecordError.
Record record_from_samples(std::vector<double> t, std::vector<double> a, std::string_view source);
// Reads and parses the file; throws RecordError ("<file>: cannot read: <why>" too).
std::shared_ptr<const Record> read_record(const std::filesystem::path& file);

}  // namespace pb
