#include "meshfree/explicit/sph_setup.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/explicit/surface_blast.hpp"
#include "meshfree/geometry/lattice.hpp"
#include "meshfree/geometry/outline_file.hpp"
#include "meshfree/sph/detonation.hpp"
#include "meshfree/sph/held_loads.hpp"
#include "meshfree/sph/state.hpp"
#include "meshfree/sph/surface_load.hpp"
#include "meshfree/sph/transmitting_boundary.hpp"
#include <algorithm>
#include <cmath>

namespace mf::explicit_dynamics {

namespace {

/// Whether a free particle lies in a region.
bool free_in(const sph::Hydro& h, int i, const spec::Region& region) {
  const std::vector<double>& X = h.particles.X;
  return !h.fields.fixed[i] &&
         region.contains(spec::Point(X[3 * i], X[3 * i + 1], X[3 * i + 2]), 1e-9);
}

/// The solver's material from the spec's: the equation of state, and the strength of a solid
/// (J2 from the material's plasticity with mu = G, granular, HJC, or elastic when it has a shear
/// modulus and no plasticity).
sph::Material to_solver(const spec::MaterialSpec& m) {
  sph::Material out;
  out.name = m.name;
  out.eos = *m.eos;
  using Model = spec::StrengthSpec::Model;
  const Model model = m.strength ? m.strength->model : Model::J2;
  if (model == Model::Granular) {
    materials::GranularStrength granular = m.strength->granular;
    if (granular.shear_modulus.x.empty()) // the material's own, a constant
      granular.shear_modulus = {{0.0}, {m.shear_modulus}};
    out.strength = granular;
  } else if (model == Model::Hjc) {
    out.strength = *m.hjc;
  } else if (m.plasticity &&
             std::holds_alternative<materials::DruckerPragerParameters>(*m.plasticity)) {
    out.strength = materials::DruckerPragerShear{
        m.shear_modulus, std::get<materials::DruckerPragerParameters>(*m.plasticity)};
  } else if (m.plasticity) {
    // The J2 return uses mu = G (E = 2G, nu = 0); the pressure is the equation of state's.
    materials::VonMises vm;
    vm.shear_modulus = m.shear_modulus;
    vm.j2 = std::get<materials::J2Parameters>(*m.plasticity);
    vm.j2.E = 2.0 * m.shear_modulus;
    vm.j2.nu = 0.0;
    out.strength = vm;
  } else if (m.shear_modulus > 0.0) {
    out.strength = materials::ElasticShear{m.shear_modulus};
  }
  if (m.strength) out.failure_strain = m.strength->failure_strain;
  return out;
}

/// The particles of region k: its lattice (or ring) less its circle's outside and its holes (of
/// any outline).
void add_region(sph::Hydro& h, const spec::SphSpec& s, std::size_t k) {
  const spec::SphRegion& b = s.regions[k];
  const int mat = b.material;
  const int before = h.particles.size();
  const spec::Region& g = b.region;
  const auto add = [&](const Vec3& x, double volume) {
    if (g.circle) {
      const double dx = x[0] - g.circle->center[0], dy = x[1] - g.circle->center[1];
      if (dx * dx + dy * dy > g.circle->radius * g.circle->radius) return;
    }
    for (const spec::Circle& c : g.holes) {
      const double dx = x[0] - c.center[0], dy = x[1] - c.center[1];
      if (dx * dx + dy * dy < c.radius * c.radius) return;
    }
    for (const geometry::OutlineHole& o : g.outline_holes)
      if (o.contains(Vec2(x[0], x[1]))) return;
    if (g.part && !g.part->contains(Vec2(x[0], x[1]), 0.0)) return;
    const double spacing = std::pow(volume, 1.0 / s.dimension);
    const double h0 = s.smoothing * spacing;
    const int i = sph::add_particle(h, x, volume, b.density, b.energy, h0, mat, b.fixed);
    // h = h0 (rho0 / rho)^(1/dim) within [min, max] h0: the density within these.
    h.fields.rho_lo[i] = b.density * std::pow(b.smoothing_bounds.max, -s.dimension);
    h.fields.rho_hi[i] = b.density * std::pow(b.smoothing_bounds.min, -s.dimension);
    for (int d = 0; d < 3; ++d) h.particles.v[3 * i + d] = b.velocity[d];
    if (const auto& p = b.velocity_profile)
      h.particles.v[3 * i + p->component] += p->table(x[p->along]);
  };
  if (g.ring)
    geometry::for_each_ring_point(g.ring->center, g.ring->inner_radius, g.ring->outer_radius,
                                  b.spacing, add);
  else {
    const geometry::Lattice grid =
        geometry::Lattice::fitted(g.box->lo, g.box->hi, b.spacing, s.dimension);
    double volume = grid.cell_volume(s.dimension);
    if (g.part) { // a file's body: its particles share its area
      int inside = 0;
      grid.for_each([&](const Vec3& x) { inside += g.part->contains(Vec2(x[0], x[1]), 0.0); });
      if (inside > 0) volume = geometry::file_body_area(*g.part) / inside;
    }
    grid.for_each([&](const Vec3& x) { add(x, volume); });
  }
  // A region whose circle or holes leave none of its lattice would make a body without
  // particles, or a material without any: refused as input, like an empty peridynamic region.
  MF_REQUIRE(h.particles.size() > before, "regions[", k,
             "]: holds no particle (its circle or holes leave none of its lattice points)");
}

/// Each particle of the layer carries its face area V / spacing and the Friedlander history
/// of its own distance and angle of incidence (loads/blast.hpp).
sph::SurfaceLoad blast_load(const sph::Hydro& h, const spec::SphBlastLoad& l, int dim) {
  const particles::ParticleSet& P = h.particles;
  sph::SurfaceLoad load;
  load.name = l.name;
  const spec::BlastSpec& blast = l.blast;
  for (int d = 0; d < 3; ++d) load.direction[d] = -blast.normal[d];
  for (const int i : P.owned())
    if (free_in(h, i, l.region)) {
      load.particles.push_back(i);
      load.area.push_back(sph::face_area(P, i, dim));
    }
  const Charge charge{blast.tnt_mass, blast.surface_burst, blast.clamp_below_range, blast.charge,
                      blast.normal};
  load.pulses = surface_pulses(charge, P.X, load.particles, l.key_path);
  MF_REQUIRE(!load.particles.empty(), l.key_path, ".box: selects no free particle");
  return load;
}

sph::SurfaceForce traction(const sph::Hydro& h, const spec::SphTraction& t) {
  std::vector<int> layer;
  for (const int i : h.particles.owned())
    if (free_in(h, i, t.region)) layer.push_back(i);
  MF_REQUIRE(!layer.empty(), t.key_path, ".box: selects no free particle");
  return sph::traction_force(h, t.name, layer, t.traction.data());
}

/// A symmetry plane, which the body must lie on one side of.
sph::SymmetryPlane symmetry_plane(const sph::Hydro& h, const spec::SphSymmetry& m) {
  const particles::ParticleSet& P = h.particles;
  int below = 0, above = 0;
  for (const int i : P.owned()) (P.X[3 * i + m.axis] < m.at ? below : above) += 1;
  MF_REQUIRE(below == 0 || above == 0, "boundary ", m.name, ": the plane ", "xyz"[m.axis], " = ",
             m.at, " cuts the body (", below, " particles below it, ", above, " above)");
  return {m.axis, m.at};
}

/// Lysmer dashpots with the particle's initial impedances rho c_L and rho c_s.
sph::TransmittingBoundary transmitting(const sph::Hydro& h, const spec::SphTransmitting& t,
                                       int dim) {
  const particles::ParticleSet& P = h.particles;
  const sph::ParticleFields& F = h.fields;
  sph::TransmittingBoundary b;
  b.name = t.name;
  for (int d = 0; d < 3; ++d) b.normal[d] = t.normal[d];
  for (const int i : P.owned()) {
    if (!free_in(h, i, t.region)) continue;
    b.particles.push_back(i);
    b.area.push_back(sph::face_area(P, i, dim));
    b.normal_impedance.push_back(F.rho[i] * F.c[i]);
    b.shear_impedance.push_back(std::sqrt(
        F.rho[i] * materials::shear_modulus(h.materials[P.material[i]].strength, F.rho[i])));
  }
  MF_REQUIRE(!b.particles.empty(), t.key_path, ".box: selects no free particle");
  return b;
}

} // namespace

sph::Hydro build_sph(const spec::SphSpec& s) {
  sph::Hydro h;
  for (const spec::MaterialSpec& m : s.materials) h.materials.push_back(to_solver(m));
  h.settings = s.numerics;
  h.dim = s.dimension;
  // The list holds (1 + skin)^dim times the interacting pairs, every one of them examined at
  // every rate evaluation, while the number of rebuilds goes as 1 / skin: the best margin
  // shrinks with the dimension (measured in README.md, SPH).
  h.settings.skin = h.dim == 1 ? 0.5 : 0.3;
  for (std::size_t k = 0; k < s.regions.size(); ++k) add_region(h, s, k);
  for (const spec::SphBlastLoad& l : s.loads) h.conditions.add(blast_load(h, l, s.dimension));
  for (const spec::SphTraction& t : s.tractions) h.conditions.add(traction(h, t));
  for (int d = 0; d < 3; ++d) h.body.gravity[d] = s.gravity[d];
  for (const spec::SphSymmetry& m : s.symmetry) h.symmetry.push_back(symmetry_plane(h, m));
  if (s.detonation_normal)
    sph::light_from_plane(h, s.detonation_point->data(), s.detonation_normal->data());
  else if (s.detonation_point)
    sph::light_from_point(h, s.detonation_point->data());
  sph::update_state(h);
  for (const spec::SphTransmitting& t : s.transmitting)
    h.conditions.add(transmitting(h, t, s.dimension));
  return h;
}

} // namespace mf::explicit_dynamics
