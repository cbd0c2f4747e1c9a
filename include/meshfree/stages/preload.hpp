#pragma once
// A converged implicit preload as the explicit stage of a staged run sees it, whatever its
// model: its state at the particles (passive material points carried through its increments),
// its held conditions on particle layers chosen by geometry, and its material and body force at
// a point. A plane preload (implicit::ElastoplasticResult of a GalerkinSpec) and a 3D one
// (implicit::SolidElastoplasticResult of a SolidSpec) are its two kinds; the SPH and the
// peridynamic stages run from either alike.
#include "meshfree/implicit/elastoplastic_result.hpp"
#include "meshfree/implicit/solid_elastoplastic.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include "meshfree/stages/held_conditions.hpp"
#include "meshfree/stages/preload_sampling.hpp"
#include <vector>

namespace mf::stages {

class Preload {
public:
  explicit Preload(const spec::ProblemSpec& spec) : spec_(spec) {}
  virtual ~Preload() = default;
  const spec::ProblemSpec& spec() const { return spec_; }

  /// The preload at particles of reference positions `x`, mirrored across link.mirror into the
  /// preload's part; a particle no node covers is an error naming link.key_path.
  virtual PreloadAtParticles sample(const std::vector<Vec3>& x,
                                    const spec::StageLink& link) const = 0;
  /// The conditions link.hold names, on particles at `x` (held_conditions.hpp).
  virtual std::vector<HeldCondition> held(const spec::StageLink& link, const std::vector<Vec3>& x,
                                          const HoldLayers& layers) const = 0;
  /// E and nu of the material at a point of the preload's part.
  virtual materials::IsotropicElastic elasticity_at(const Vec3& x) const = 0;
  /// The held body force per volume at a point of the preload's part at factor 1: gravity
  /// (rho g) or the uniform body force.
  virtual Vec3 body_force_at(bool gravity, const Vec3& x) const = 0;
  /// The acceleration of gravity at factor 1 (zero where the preload has none).
  virtual Vec3 gravity() const = 0;
  /// The number of displacement components a node carries: 2 (plane) or 3.
  virtual int dimension() const = 0;

private:
  const spec::ProblemSpec& spec_;
};

/// A plane preload (plane strain or plane stress, GalerkinSpec): its model and every increment's
/// nodal parameters (recorded by ProblemSpec::record_increment_parameters).
class PlanePreload : public Preload {
public:
  /// `spec` and `r` must outlive the preload.
  PlanePreload(const spec::ProblemSpec& spec, const implicit::ElastoplasticResult& r)
      : Preload(spec), r_(r) {}
  PreloadAtParticles sample(const std::vector<Vec3>& x, const spec::StageLink& link) const override;
  std::vector<HeldCondition> held(const spec::StageLink& link, const std::vector<Vec3>& x,
                                  const HoldLayers& layers) const override;
  materials::IsotropicElastic elasticity_at(const Vec3& x) const override;
  Vec3 body_force_at(bool gravity, const Vec3& x) const override;
  Vec3 gravity() const override;
  int dimension() const override { return 2; }

private:
  const implicit::ElastoplasticResult& r_;
};

/// A 3D preload (model solid_3d, SolidSpec): its model and every increment's nodal parameters
/// (SolidSpec::record_increment_parameters).
class SolidPreload : public Preload {
public:
  /// `spec` and `r` must outlive the preload.
  SolidPreload(const spec::ProblemSpec& spec, const implicit::SolidElastoplasticResult& r)
      : Preload(spec), r_(r) {}
  PreloadAtParticles sample(const std::vector<Vec3>& x, const spec::StageLink& link) const override;
  std::vector<HeldCondition> held(const spec::StageLink& link, const std::vector<Vec3>& x,
                                  const HoldLayers& layers) const override;
  materials::IsotropicElastic elasticity_at(const Vec3& x) const override;
  Vec3 body_force_at(bool gravity, const Vec3& x) const override;
  Vec3 gravity() const override { return Vec3::Zero(); }
  int dimension() const override { return 3; }

private:
  const implicit::SolidElastoplasticResult& r_;
};

} // namespace mf::stages
