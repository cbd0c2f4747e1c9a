#include "meshfree/loads/time_function.hpp"
#include "meshfree/core/input_file.hpp"
#include "meshfree/core/error.hpp"
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace mf::loads {

double TimeFunction::operator()(double t) const {
  switch (kind) {
  case Kind::Constant:
    return value;
  case Kind::Ramp:
    if (t <= t0) return 0.0;
    if (t >= t1) return 1.0;
    return (t - t0) / (t1 - t0);
  case Kind::Sine:
    if (duration > 0.0 && t > duration) return 0.0;
    return amplitude * std::sin(omega * t + phase);
  case Kind::Table: {
    if (t < 0.0 || samples.empty()) return 0.0;
    const double k = std::floor(t / sample_step + 1e-9);
    if (k >= static_cast<double>(samples.size())) return 0.0;
    return samples[static_cast<std::size_t>(k)];
  }
  }
  return 0.0;
}

std::vector<double> haar_approximation(const std::vector<double>& samples, int level) {
  std::vector<double> a = samples;
  for (int j = 0; j < level; ++j) {
    if (a.size() <= 1) break;
    std::vector<double> next((a.size() + 1) / 2);
    for (std::size_t k = 0; k < next.size(); ++k) {
      const double first = a[2 * k];
      const double second = 2 * k + 1 < a.size() ? a[2 * k + 1] : a.back();
      next[k] = 0.5 * (first + second);
    }
    a.swap(next);
  }
  return a;
}

std::vector<double> read_samples(const std::string& path) {
  require_regular_file(path, "load table");
  std::ifstream in(path);
  MF_REQUIRE(in.good(), path, ": cannot open the load table");
  std::string line;
  std::getline(in, line); // header
  std::vector<double> out;
  int row = 1;
  while (std::getline(in, line)) {
    ++row;
    if (line.empty()) continue;
    const std::size_t comma = line.find(',');
    MF_REQUIRE(comma != std::string::npos, path, ":", row, ": expected 'index,value', got '", line,
               "'");
    try {
      std::size_t used = 0;
      const std::string v = line.substr(comma + 1);
      out.push_back(std::stod(v, &used));
      MF_REQUIRE(std::isfinite(out.back()), path, ":", row, ": not a finite number");
    } catch (const std::invalid_argument&) {
      fail(path, ":", row, ": not a number: '", line.substr(0, 80), "'");
    } catch (const std::out_of_range&) {
      fail(path, ":", row, ": not a finite number: '", line.substr(0, 80), "'");
    }
  }
  MF_REQUIRE(!out.empty(), path, ": the table has no samples");
  return out;
}

} // namespace mf::loads
