// Particle bodies with holes of any outline: an SPH region's `holes` and a peridynamic body's
// geometry take slots, polygons and rectangles as the implicit bodies do. No particle lies in a
// hole, and the particles' volumes add up to the body's area less the holes' (the lattice's
// staircase along the outlines is all that is left).
#include "meshfree/explicit/pd_setup.hpp"
#include "meshfree/explicit/sph_setup.hpp"
#include "test_support.hpp"
#include <catch2/catch.hpp>
#include <cmath>

using namespace mf;

namespace {

const double pi = std::acos(-1.0);

/// A slot of width 0.05 between (0.3, 0.1) and (0.6, 0.1), and a triangle, in YAML.
const std::string kHoles = "[{slot: {from: [0.3, 0.1], to: [0.6, 0.1], width: 0.05}}, "
                           "{polygon: [[0.75, 0.05], [0.9, 0.05], [0.8, 0.15]]}, "
                           "{rectangle: {origin: [0.1, 0.05], size: [0.05, 0.1]}}]";
const double kHoleArea = 0.05 * 0.3 + pi * 0.025 * 0.025 + 0.5 * 0.15 * 0.1 + 0.05 * 0.1;

std::vector<geometry::OutlineHole> holes() {
  return {geometry::OutlineHole::slot({0.3, 0.1}, {0.6, 0.1}, 0.025),
          geometry::OutlineHole::polygon({{0.75, 0.05}, {0.9, 0.05}, {0.8, 0.15}}),
          geometry::OutlineHole::polygon({{0.1, 0.05}, {0.15, 0.05}, {0.15, 0.15}, {0.1, 0.15}})};
}

/// No owned particle lies in a hole farther than round-off from its outline (a lattice row on a
/// hole's edge belongs to the body), and their volumes add up to the body's area within 0.5%.
void check_particles(const particles::ParticleSet& P) {
  double volume = 0.0;
  int inside = 0;
  for (int i = 0; i < P.owned_count(); ++i) {
    volume += P.volume[i];
    for (const auto& o : holes())
      inside += o.contains(Vec2(P.X[3 * i], P.X[3 * i + 1]), 1e-12) ? 1 : 0;
  }
  CHECK(inside == 0);
  const double exact = 0.2 - kHoleArea;
  CHECK(std::abs(volume - exact) / exact < 5e-3);
}

} // namespace

TEST_CASE("an SPH region's holes of any outline leave no particle inside and the rest's volume",
          "[sph][holes]") {
  const spec::ProblemSpec spec =
      load_problem("sph_plate_blast", {"regions.0.box=[[0, 0], [1.0, 0.2]]",
                                       "regions.0.holes=" + kHoles, "boundary=[]"});
  const sph::Hydro h = explicit_dynamics::build_sph(spec.sph());
  check_particles(h.particles);
}

TEST_CASE("a peridynamic body's geometry takes holes of any outline", "[pd][holes]") {
  const spec::ProblemSpec spec = load_problem(
      "pd_slab_blast", {"geometry.rectangle.size=[1.0, 0.2]", "geometry.holes=" + kHoles,
                        "boundary=[]", "output.gauges=[]", "discretisation.spacing=0.005"});
  PhaseTimer timer;
  const explicit_dynamics::PdSetup setup = explicit_dynamics::build_pd_setup(spec, timer);
  check_particles(setup.model.particles);
}
