#pragma once
// The constitutive law at a point of a Galerkin body: the material of the point (material
// regions, later entries winning), its J2 parameters or elasticity, its body force (gravity
// times its density) and its initial (geostatic) stress, and the one stress update every
// Galerkin point and every point carried through the increments of a solve uses.
//
// The initial stress sigma0 enters as an initial elastic strain eps0 = C^-1 sigma0 (3D
// compliance, so that plane strain gets its eps0_zz) added to the strain handed to the pure J2
// update: sigma = sigma0 + C (eps - eps_p) at an elastic state, and the J2 trial stress starts
// from sigma0 (Abaqus *GEOSTATIC; Zienkiewicz & Taylor, The Finite Element Method vol. 1, 6th
// ed., eq. 2.4 sigma = D (eps - eps0) + sigma0).
#include "meshfree/core/types.hpp"
#include "meshfree/materials/constitutive_model.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include <utility>
#include <vector>

namespace mf::implicit {

/// The constitutive law at a point of the body: material index, its model (a J2 model with its
/// elastic constants if the material has no plasticity), and the initial (geostatic) stress
/// there [xx, yy, xy, zz].
struct PointLaw {
  int material = 0;
  materials::ConstitutiveModel params;
  bool plastic = false;
  Vec4 initial_stress = Vec4::Zero();
};

/// The index into spec.materials of the material at x: the last material region holding x, or
/// the analysis' material.
int material_at(const spec::ProblemSpec& spec, const Vec2& x);

/// The model of a material of the spec (E and nu, and its plasticity if it has one).
materials::ConstitutiveModel material_parameters(const spec::ProblemSpec& spec, int material);

/// The initial stress at x [xx, yy, xy, zz]: zero without `initial_stress`; geostatic: the
/// column integral of rho |g| from y up to the surface, piecewise exact (the density changes
/// only where the column crosses a region's or the body's boundary, and those crossings are the
/// integration breaks; outside the body, e.g. in a hole, the density is 0).
Vec4 initial_stress_at(const spec::ProblemSpec& spec, const Vec2& x);

PointLaw point_law(const spec::ProblemSpec& spec, const Vec2& x);

/// The body force per volume at x at body-force factor 1: body_force + rho g.
Vec2 body_force_at(const spec::ProblemSpec& spec, const Vec2& x);

/// The stress update of a Galerkin point (plane model, initial stress, its model or elastic).
materials::StressUpdate2D update_point(const spec::ProblemSpec& spec, const PointLaw& law,
                                       const Vec3& strain,
                                       const materials::MaterialState& committed);

/// The same update from its parts: the material's parameters, whether it is plastic, and the
/// point's initial stress. Elastic: sigma = sigma0 + C eps with C the plane elastic matrix.
/// strain_zz is the out-of-plane strain of the displacement (eps0_zz left out).
materials::StressUpdate2D update_law(materials::PlaneModel model,
                                     const materials::ConstitutiveModel& law, bool plastic,
                                     const Vec4& sigma0, const Vec3& strain,
                                     const materials::MaterialState& committed);

/// The laws of a set of points as flat arrays: per point the index of its material into small
/// per-material arrays, its body force and initial stress; no look-up in the loops that use it.
struct PointLaws {
  std::vector<materials::ConstitutiveModel> params; // per entry of spec.materials
  std::vector<char> plastic;                   // per entry of spec.materials
  std::vector<Mat3> elastic;                   // plane elastic matrix, per entry of spec.materials
  std::vector<int> material;                   // per point
  std::vector<Vec2> body_force;     // per point: body_force + rho g (empty when there is none)
  std::vector<Vec4> initial_stress; // per point (empty without an initial stress)
  bool any_plastic = false;         // some point has a plastic material
  bool one_material = true;         // every point has the same material

  /// The elastic stress of point k at `strain`, and its out-of-plane stress under `model`.
  std::pair<Vec3, double> elastic_stress(materials::PlaneModel model, int k,
                                         const Vec3& strain) const;

  materials::StressUpdate2D update(materials::PlaneModel model, int k, const Vec3& strain,
                                   const materials::MaterialState& committed) const {
    const int m = material[k];
    return update_law(model, params[m], plastic[m] != 0,
                      initial_stress.empty() ? Vec4::Zero().eval() : initial_stress[k], strain,
                      committed);
  }
};

/// The laws at the points x (the spec's materials that no point uses keep default entries).
PointLaws point_laws(const spec::ProblemSpec& spec, const std::vector<Vec2>& x);

/// Whether every material's tangent is symmetric (a non-associated flow's is not).
inline bool symmetric_tangents(const spec::ProblemSpec& spec) {
  for (const spec::MaterialSpec& m : spec.materials)
    if (m.plasticity && !materials::symmetric_tangent(*m.plasticity)) return false;
  return true;
}

inline bool has_gravity(const spec::ProblemSpec& spec) {
  return (spec.galerkin().gravity.array() != 0.0).any();
}
/// True when the body carries a body force (a uniform one or gravity).
inline bool has_body_force(const spec::ProblemSpec& spec) {
  return !spec.galerkin().body_force.isZero() || has_gravity(spec);
}

} // namespace mf::implicit
