#pragma once
// Gauges of an explicit run: each follows the particle nearest its point at the start (a
// Lagrangian gauge), writes the quantities it records as history columns "<gauge>_<quantity>" at
// every recorded instant, and keeps the largest |value| of the quantities it tracks over every
// step, recorded or not (a peak between two history rows is not lost).
#include "meshfree/core/error.hpp"
#include "meshfree/core/types.hpp"
#include "meshfree/distribution/ranks.hpp"
#include "meshfree/io/state_file.hpp"
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace mf::explicit_dynamics {

struct GaugePoint {
  std::string name;
  Vec3 at{0, 0, 0};
};

/// The particle nearest `at` among the first n (positions x, y, z per particle); the first one
/// on a tie.
int nearest_particle(const std::vector<double>& positions, int n, const Vec3& at);

class Gauges {
public:
  /// A quantity of one particle.
  using Quantity = std::function<double(int particle)>;
  Gauges() = default;
  /// Each gauge follows the particle nearest its point among the first n of `positions`; on a
  /// run spread over MPI ranks (n: the owned ones) among every rank's, held by the rank that
  /// owns it (the lowest rank on a tie, which holds the lowest ids). Collective.
  /// `ids`: the particles' global ids (empty: the gauges cannot follow() particles).
  Gauges(const std::vector<GaugePoint>& points, const std::vector<double>& positions, int n,
         const distribution::Ranks& ranks = {}, const std::vector<long>& ids = {});
  /// After particles moved between ranks: each gauge's particle is looked up again among the
  /// first n of `ids` (increasing), this rank's owned particles.
  void follow(const std::vector<long>& ids, int n);
  /// A history column per gauge.
  void record(std::string quantity, Quantity q);
  /// A maximum over every step per gauge.
  void track(std::string quantity, Quantity q);
  /// The particle of each gauge, -1 where another rank holds it.
  const std::vector<int>& particles() const { return particle_; }
  /// "<gauge>_<quantity>" of every gauge and recorded quantity, gauge by gauge.
  std::vector<std::string> columns() const;
  /// Appends the recorded quantities in the order of columns(). Collective.
  void append_to(std::vector<double>& row) const;
  /// Takes the tracked quantities of this step into the maxima.
  void update_maxima();
  /// "<gauge>_<quantity>" and the largest |value| so far, gauge by gauge. Collective.
  std::vector<std::pair<std::string, double>> maxima() const;

  /// The particles followed and the maxima so far (a checkpoint keeps them).
  /// A checkpoint of other gauges is refused.
  template <class Visit> void for_each_state(Visit&& visit) {
    const std::size_t ids = id_.size();
    std::vector<double> most;
    for (const auto& m : maxima_) most.push_back(m.second);
    visit("particle", particle_), visit("id", id_), visit("maxima", most);
    if (particle_.size() != names_.size() || id_.size() != ids || most.size() != maxima_.size())
      io::refuse_checkpoint("the checkpoint holds " + std::to_string(particle_.size()) +
                            " gauges, this run has " + std::to_string(names_.size()));
    for (std::size_t k = 0; k < most.size(); ++k) maxima_[k].second = most[k];
  }

private:
  distribution::Ranks ranks_;
  std::vector<std::string> names_;
  std::vector<int> particle_;
  std::vector<long> id_; // each gauge's particle's global id, when given
  std::vector<std::pair<std::string, Quantity>> recorded_, tracked_;
  std::vector<std::pair<std::string, double>> maxima_;
};

} // namespace mf::explicit_dynamics
