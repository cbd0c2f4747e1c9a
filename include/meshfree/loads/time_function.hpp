#pragma once
// Time functions that scale loads and prescribed motions: constant, linear ramp, sine, and tables
// of samples (inline or from a CSV file), with the Haar (db1) approximation of paper 000 that
// halves a sampled history per level.
#include <string>
#include <vector>

namespace mf::loads {

struct TimeFunction {
  enum class Kind { Constant, Ramp, Sine, Table };
  Kind kind = Kind::Constant;
  double value = 1.0;                  // constant
  double t0 = 0.0, t1 = 1.0;           // ramp: 0 before t0, 1 after t1, linear between
  double amplitude = 1.0, omega = 0.0; // sine: amplitude sin(omega t + phase) for t < duration
  double phase = 0.0;
  double duration = 0.0;       // sine, table: 0 after it (0 for the sine: forever)
  std::vector<double> samples; // table: sample k holds on [k dt, (k + 1) dt)
  double sample_step = 0.0;    // table: duration / samples

  double operator()(double t) const;
};

/// Block means of 2^level samples: each level averages consecutive pairs, repeating the last
/// sample of an odd-length history, so N_j = ceil(N_{j-1} / 2). This is the Haar (db1)
/// approximation coefficient A_j of paper 000 divided by sqrt(2)^j, which keeps the amplitude
/// (the paper's Fig. 12 shows approximations at the original amplitude).
std::vector<double> haar_approximation(const std::vector<double>& samples, int level);

/// The second column of a CSV file with a header row (index,value), as the samples of a table.
std::vector<double> read_samples(const std::string& path);

} // namespace mf::loads
