#pragma once
// The LAMMPS lattice references of reference/lammps/ (their README: recipe and conventions):
// the particles of `particles.csv` and the displacement frames of `displacements.csv`, read with
// the strings LAMMPS read, and the largest difference of a run's displacements from them.
#include "meshfree/pd/model.hpp"
#include "test_support.hpp"
#include <catch2/catch.hpp>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace mf::test {

/// Adds the particles of `dir/particles.csv` (id order) to m at `density`, material 0; returns
/// their initial velocities (3 a particle).
inline std::vector<double> read_lammps_particles(const std::string& dir, pd::Model& m,
                                                 double density) {
  std::ifstream in(dir + "particles.csv");
  REQUIRE(in.good());
  std::string line;
  std::getline(in, line);
  std::vector<double> v0;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    double id, x, y, z, vol, vx, vy, vz;
    char comma;
    ss >> id >> comma >> x >> comma >> y >> comma >> z >> comma >> vol >> comma >> vx >> comma >>
        vy >> comma >> vz;
    m.particles.add({x, y, z}, vol, density, 0);
    v0.insert(v0.end(), {vx, vy, vz});
  }
  return v0;
}

/// The frames of `dir/displacements.csv`: step -> displacements (3 a particle, id order).
inline std::map<int, std::vector<double>> read_lammps_frames(const std::string& dir,
                                                             int particles) {
  std::ifstream ref(dir + "displacements.csv");
  REQUIRE(ref.good());
  std::string line;
  std::getline(ref, line);
  std::map<int, std::vector<double>> frames;
  while (std::getline(ref, line)) {
    std::stringstream ss(line);
    double step, time, id, ux, uy, uz;
    char comma;
    ss >> step >> comma >> time >> comma >> id >> comma >> ux >> comma >> uy >> comma >> uz;
    auto& u = frames[static_cast<int>(step)];
    u.resize(3 * static_cast<std::size_t>(particles));
    const int i = static_cast<int>(id) - 1;
    u[3 * i] = ux, u[3 * i + 1] = uy, u[3 * i + 2] = uz;
  }
  return frames;
}

/// max_k |u_k - ref_k| / max_k |ref_k|.
inline double relative_difference(const std::vector<double>& u, const std::vector<double>& ref) {
  double scale = 0.0, diff = 0.0;
  for (std::size_t k = 0; k < u.size(); ++k) {
    scale = std::max(scale, std::abs(ref[k]));
    diff = std::max(diff, std::abs(u[k] - ref[k]));
  }
  return diff / scale;
}

} // namespace mf::test
