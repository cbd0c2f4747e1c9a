#pragma once
// What the tables of held conditions (plane and 3D) share: the aluminium of both stages, the laws
// of the table, and the measures of a quiet handover read from a stage's history.
#include "meshfree/io/results.hpp"
#include "meshfree/stages/explicit_stage.hpp"
#include <algorithm>
#include <catch2/catch.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace held_table {

using namespace mf;

// Aluminium with a linear equation of state of the Galerkin body's bulk modulus, so that both
// stages have one elasticity.
inline const double kE = 70.0e9, kNu = 0.3, kRho = 2700.0, kYield = 240.0e6;
inline const double kBulk = kE / (3.0 * (1.0 - 2.0 * kNu));

enum class Law { Elastic, Isotropic, Kinematic };

/// The material of an SPH stage, or of a peridynamic one: a PMB bond law (nu = 1/4 in plane
/// strain and 3D, Silling 2000), or with `state_based` the LPS with the aluminium's own nu.
inline std::string material(Law law, bool peridynamic, bool state_based = false) {
  std::ostringstream s;
  s.precision(17);
  s << "materials:\n  - name: aluminium\n    E: " << kE
    << "\n    nu: " << (peridynamic && !state_based ? 0.25 : kNu) << "\n    density: " << kRho
    << "\n";
  if (peridynamic) {
    s << (state_based ? "    bond: {law: lps}\n" : "    bond: {law: pmb}\n");
    return s.str();
  }
  if (law != Law::Elastic) {
    s << "    plasticity: {yield_stress: " << kYield << ", hardening: {type: linear, H: 2.24e9}";
    if (law == Law::Kinematic) s << ", kinematic_modulus: 5.0e9";
    s << "}\n";
  }
  s << "    eos: {type: linear_polynomial, rho0: " << kRho << ", c: [0, " << kBulk
    << ", 0, 0, 0, 0, 0]}\n";
  return s.str();
}

/// The strain to reach: half the uniaxial yield strain when elastic, twice it when plastic.
inline double strain(Law law) {
  return (law == Law::Elastic ? 0.5 : 2.0) * kYield / kE;
}

inline std::size_t column(const io::History& h, const std::string& name) {
  const auto& c = h.columns();
  const auto it = std::find(c.begin(), c.end(), name);
  REQUIRE(it != c.end());
  return static_cast<std::size_t>(it - c.begin());
}

/// The particles' reference positions of a stage's end state.
inline std::vector<Vec3> positions(const stages::ExplicitStage& st) {
  std::vector<Vec3> X(st.position.size() / 3);
  for (std::size_t i = 0; i < X.size(); ++i)
    X[i] = Vec3(st.position[3 * i], st.position[3 * i + 1], st.position[3 * i + 2]);
  return X;
}

/// Over the explicit stage's rows: the last step, and the largest kinetic energy over the
/// energy `scale` gives for the row.
template <class Scale>
void largest_kinetic(const io::History& H, Scale scale, long& steps, double& ratio) {
  const std::size_t stage = column(H, "stage"), step = column(H, "step"),
                    kinetic = column(H, "kinetic_energy");
  for (const auto& row : H.rows()) {
    if (row[stage] != 1.0) continue;
    steps = std::max(steps, static_cast<long>(row[step]));
    ratio = std::max(ratio, row[kinetic] / scale(row));
  }
}

struct Quietness {
  long steps = 0;
  double kinetic = 0.0;  // largest kinetic energy over the run / stored strain energy
  double interior = 0.0; // largest stress change of an interior particle / largest |sigma|
  double out_of_balance = 0.0;
  double residual = 0.0;       // the out-of-balance the held conditions leave, before any balancing
  double plastic_change = 0.0; // largest change of alpha / largest alpha
};

struct PdQuietness {
  long steps = 0;
  double kinetic = 0.0;  // largest kinetic / strain energy over the run
  double interior = 0.0; // largest |u - u^h| of an interior particle / largest |u^h|
  double pd_vs_uh = 0.0; // |u_PD - u^h| / |u^h| over the body after the relaxation
  int relax_iterations = 0;
};

inline const char* law_name(Law law) {
  return law == Law::Elastic ? "elastic" : law == Law::Isotropic ? "isotropic" : "kinematic";
}

} // namespace held_table
