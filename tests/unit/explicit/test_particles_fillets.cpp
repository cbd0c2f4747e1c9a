// A peridynamic body reaches its geometry through the same plane body as the implicit ones, so
// rounded corners take particles away (convex) or add them (re-entrant): none lies outside the
// rounded outline, and the particles' volumes add up to the body's area within 0.5%.
#include "meshfree/explicit/pd_setup.hpp"
#include "test_support.hpp"
#include <catch2/catch.hpp>
#include <cmath>

using namespace mf;

TEST_CASE("a peridynamic body's geometry takes rounded corners", "[pd][fillets]") {
  // An L of arms 0.2 wide in the box [0, 1] x [0, 0.6]: its outer corner (1, 0) rounded with
  // radius 0.1, its re-entrant corner (0.2, 0.2) with 0.05.
  const double pi = std::acos(-1.0);
  const double area = 1.0 * 0.2 + 0.2 * 0.4 - (1.0 - pi / 4.0) * 0.01 + (1.0 - pi / 4.0) * 0.0025;
  const spec::ProblemSpec spec = load_problem(
      "pd_slab_blast", {"geometry={polygon: {vertices: [[0, 0], [1, 0], [1, 0.2], [0.2, 0.2], "
                        "[0.2, 0.6], [0, 0.6]]},"
                        " fillets: [{at: [1, 0], radius: 0.1}, {at: [0.2, 0.2], radius: 0.05}]}",
                        "boundary=[]", "output.gauges=[]", "discretisation.spacing=0.005"});
  PhaseTimer timer;
  const explicit_dynamics::PdSetup setup = explicit_dynamics::build_pd_setup(spec, timer);
  const particles::ParticleSet& P = setup.model.particles;
  double volume = 0.0;
  int outside = 0, in_added_corner = 0;
  for (int i = 0; i < P.owned_count(); ++i) {
    const Vec2 x(P.X[3 * i], P.X[3 * i + 1]);
    volume += P.volume[i];
    outside += spec.domain.contains(x, 1e-12) ? 0 : 1;
    // between the re-entrant corner and its arc: material the rounding adds
    in_added_corner += x.x() > 0.2 && x.y() > 0.2 && (x - Vec2(0.25, 0.25)).norm() > 0.05 ? 1 : 0;
  }
  CHECK(outside == 0);
  CHECK(in_added_corner > 0);
  CHECK(std::abs(volume - area) / area < 5e-3);
}
