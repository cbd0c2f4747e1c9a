#pragma once
// Plausibility of a problem's numbers in the unit system its `units:` key declares. A modulus in
// Pa in an N-mm model, or a density in kg/m^3 in it, reads as valid input and runs; these checks
// turn such slips into warnings (never errors: an unusual material may be meant).
#include "meshfree/spec/problem_spec.hpp"
#include <optional>
#include <string>
#include <vector>

namespace mf::spec {

/// A declared unit system as factors to SI: a value in it times the factor is the SI value.
struct UnitSystem {
  double force = 1.0;  // N
  double length = 1.0; // m
  double time = 1.0;   // s
  double mass = 1.0;   // kg; force time^2 / length unless the key names a mass unit
  double stress() const { return force / (length * length); }
  double density() const { return mass / (length * length * length); }
  double speed() const { return length / time; }
  double acceleration() const { return length / (time * time); }
};

/// The unit system a `units:` value names ("N, mm, MPa", "N, m, kg, s", "kgf, mm, kgf/mm^2"),
/// or none when it names no force and length unit ("consistent", "dimensionless", empty).
std::optional<UnitSystem> parse_units(const std::string& units);

/// One line per implausible value (each cause once), naming the key, its value and the range
/// expected; empty when the units are not recognised or every value is plausible. The ranges
/// are those the README lists.
std::vector<std::string> unit_sanity_warnings(const ProblemSpec& spec);

/// Prints unit_sanity_warnings(spec) as warnings on stderr (rank 0).
void warn_unit_sanity(const ProblemSpec& spec);

} // namespace mf::spec
