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

Gauges::Gauges(const std::vector<GaugePoint>& points, const std::vector<double>& positions, int n,
               const distribution::Ranks& ranks, const std::vector<long>& ids)
    : ranks_(ranks) {
  for (const GaugePoint& g : points) {
    names_.push_back(g.name);
    const int i = nearest_particle(positions, n, g.at);
    double d2 = std::numeric_limits<double>::infinity();
    if (n > 0)
      d2 =
          (Vec3(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]) - g.at).squaredNorm();
    particle_.push_back(ranks.rank_of_min(d2) == ranks.rank ? i : -1);
    if (!ids.empty()) // the holder's id, the others adding zero
      id_.push_back(ranks.sum(particle_.back() >= 0 ? ids[i] : 0L));
  }
}

void Gauges::follow(const std::vector<long>& ids, int n) {
  for (std::size_t g = 0; g < id_.size(); ++g) {
    const auto it = std::lower_bound(ids.begin(), ids.begin() + n, id_[g]);
    particle_[g] = it != ids.begin() + n && *it == id_[g] ? static_cast<int>(it - ids.begin()) : -1;
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
  const std::size_t first = row.size();
  for (int i : particle_)
    for (const auto& [name, f] : recorded_) row.push_back(i >= 0 ? f(i) : 0.0);
  // Each value comes from the one rank that holds its gauge; the others add zero.
  ranks_.sum(row.data() + first, static_cast<int>(row.size() - first));
}

std::vector<std::pair<std::string, double>> Gauges::maxima() const {
  std::vector<std::pair<std::string, double>> m = maxima_;
  for (auto& [name, value] : m) value = ranks_.max(value);
  return m;
}

void Gauges::update_maxima() {
  std::size_t k = 0;
  for (int i : particle_)
    for (const auto& [name, f] : tracked_) {
      if (i < 0) {
        ++k;
        continue;
      }
      maxima_[k].second = std::max(maxima_[k].second, std::abs(f(i)));
      ++k;
    }
}

} // namespace mf::explicit_dynamics
