#include "meshfree/explicit/sph_setup.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/explicit/surface_blast.hpp"
#include "meshfree/geometry/lattice.hpp"
#include "meshfree/sph/detonation.hpp"
#include "meshfree/sph/state.hpp"
#include <algorithm>
#include <cmath>

namespace mf::explicit_dynamics {

namespace {

/// Whether a free particle lies in the box [lo, hi].
bool free_in_box(const sph::Hydro& h, int i, const std::array<double, 3>& lo,
                 const std::array<double, 3>& hi) {
  if (h.fields.fixed[i]) return false;
  const std::vector<double>& X = h.particles.X;
  for (int d = 0; d < 3; ++d)
    if (X[3 * i + d] < lo[d] - 1e-9 || X[3 * i + d] > hi[d] + 1e-9) return false;
  return true;
}

/// The face area of a particle in a surface layer one particle thick: V / spacing.
double face_area(const particles::ParticleSet& P, int i, int dim) {
  const double volume = P.mass[i] / P.density[i];
  return volume / std::pow(volume, 1.0 / dim);
}

int material_index(const io::SphSpec& s, const std::string& name) {
  for (std::size_t k = 0; k < s.materials.size(); ++k)
    if (s.materials[k].name == name) return static_cast<int>(k);
  return -1;
}

} // namespace

sph::Hydro build_sph(const io::SphSpec& s) {
  sph::Hydro h;
  h.materials = s.materials;
  h.settings = s.settings;
  const particles::ParticleSet& P = h.particles;
  const sph::ParticleFields& F = h.fields;
  h.dim = s.dimension;
  for (const io::SphBlock& b : s.blocks) {
    const int mat = material_index(s, b.material);
    const auto add = [&](const Vec3& x, double volume) {
      if (b.inside) {
        const double dx = x[0] - b.inside->center[0], dy = x[1] - b.inside->center[1];
        if (dx * dx + dy * dy > b.inside->radius * b.inside->radius) return;
      }
      for (const io::SphCircle& c : b.holes) {
        const double dx = x[0] - c.center[0], dy = x[1] - c.center[1];
        if (dx * dx + dy * dy < c.radius * c.radius) return;
      }
      const double spacing = std::pow(volume, 1.0 / s.dimension);
      const int i =
          sph::add_particle(h, x, volume, b.density, b.energy, s.smoothing * spacing, mat, b.fixed);
      for (int d = 0; d < 3; ++d) h.particles.v[3 * i + d] = b.velocity[d];
    };
    const auto vec = [](const std::array<double, 3>& a) { return Vec3(a[0], a[1], a[2]); };
    if (b.is_ring)
      geometry::for_each_ring_point(vec(b.ring.center), b.ring_inner_radius, b.ring.radius,
                                    b.spacing, add);
    else {
      const geometry::Lattice grid =
          geometry::Lattice::fitted(vec(b.lo), vec(b.hi), b.spacing, s.dimension);
      const double volume = grid.cell_volume(s.dimension);
      grid.for_each([&](const Vec3& x) { add(x, volume); });
    }
  }
  for (const io::SphBlastLoad& l : s.loads) {
    // Each particle of the layer carries its face area V / spacing and the Friedlander history
    // of its own distance and angle of incidence (loads/blast.hpp).
    sph::SurfaceLoad load;
    load.name = l.name;
    for (int d = 0; d < 3; ++d) load.direction[d] = -l.normal[d];
    for (const int i : P.owned())
      if (free_in_box(h, i, l.lo, l.hi)) {
        load.particles.push_back(i);
        load.area.push_back(face_area(P, i, s.dimension));
      }
    const Charge charge{l.tnt_mass, l.surface_burst, l.clamp_below_range,
                        Vec3(l.charge[0], l.charge[1], l.charge[2]),
                        Vec3(l.normal[0], l.normal[1], l.normal[2])};
    load.pulses = surface_pulses(charge, P.X, load.particles, l.key_path);
    MF_REQUIRE(!load.particles.empty(), l.key_path, ".box: selects no free particle");
    h.loads.push_back(load);
  }
  h.symmetry = s.symmetry;
  for (std::size_t q = 0; q < s.symmetry.size(); ++q) {
    // The body must lie on one side of each symmetry plane.
    const sph::SymmetryPlane& m = s.symmetry[q];
    int below = 0, above = 0;
    for (const int i : P.owned()) (P.X[3 * i + m.axis] < m.at ? below : above) += 1;
    MF_REQUIRE(below == 0 || above == 0, "symmetry[", q, "]: the plane ", "xyz"[m.axis], " = ",
               m.at, " cuts the body (", below, " particles below it, ", above, " above)");
  }
  if (s.detonation_normal)
    sph::light_from_plane(h, s.detonation_point->data(), s.detonation_normal->data());
  else if (s.detonation_point)
    sph::light_from_point(h, s.detonation_point->data());
  sph::update_state(h);
  for (const io::SphTransmitting& t : s.transmitting) {
    // Lysmer dashpots with the particle's initial impedances rho c_L and rho c_s.
    sph::TransmittingBoundary b;
    b.name = t.name;
    for (int d = 0; d < 3; ++d) b.normal[d] = t.normal[d];
    for (const int i : P.owned()) {
      if (!free_in_box(h, i, t.lo, t.hi)) continue;
      b.particles.push_back(i);
      b.area.push_back(face_area(P, i, s.dimension));
      b.normal_impedance.push_back(F.rho[i] * F.c[i]);
      b.shear_impedance.push_back(std::sqrt(
          F.rho[i] * materials::shear_modulus(h.materials[P.material[i]].strength, F.rho[i])));
    }
    MF_REQUIRE(!b.particles.empty(), t.key_path, ".box: selects no free particle");
    h.transmitting.push_back(b);
  }
  return h;
}

} // namespace mf::explicit_dynamics
