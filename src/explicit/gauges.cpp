#include "meshfree/explicit/gauges.hpp"
#include <algorithm>
#include <cmath>
#include <limits>

namespace mf::explicit_dynamics {

int nearest_particle(const std::vector<double>& positions, int n, const Vec3& at) {
  int best = 0;
  double d2 = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i) {
    double e = 0.0;
    for (int d = 0; d < 3; ++d)
      e += (positions[3 * i + d] - at(d)) * (positions[3 * i + d] - at(d));
    if (e < d2) d2 = e, best = i;
  }
  return best;
}

Gauges::Gauges(const std::vector<GaugePoint>& points, const std::vector<double>& positions, int n) {
  for (const GaugePoint& g : points) {
    names_.push_back(g.name);
    particle_.push_back(nearest_particle(positions, n, g.at));
  }
}

void Gauges::record(std::string quantity, Quantity q) {
  recorded_.emplace_back(std::move(quantity), std::move(q));
}

void Gauges::track(std::string quantity, Quantity q) {
  tracked_.emplace_back(std::move(quantity), std::move(q));
  // Maxima gauge by gauge: rebuilt in that order with the quantity added.
  std::vector<std::pair<std::string, double>> m;
  for (const std::string& g : names_)
    for (const auto& [name, f] : tracked_) m.emplace_back(g + "_" + name, 0.0);
  maxima_ = std::move(m);
}

std::vector<std::string> Gauges::columns() const {
  std::vector<std::string> c;
  for (const std::string& g : names_)
    for (const auto& [name, f] : recorded_) c.push_back(g + "_" + name);
  return c;
}

void Gauges::append_to(std::vector<double>& row) const {
  for (int i : particle_)
    for (const auto& [name, f] : recorded_) row.push_back(f(i));
}

void Gauges::update_maxima() {
  std::size_t k = 0;
  for (int i : particle_)
    for (const auto& [name, f] : tracked_) {
      maxima_[k].second = std::max(maxima_[k].second, std::abs(f(i)));
      ++k;
    }
}

} // namespace mf::explicit_dynamics
