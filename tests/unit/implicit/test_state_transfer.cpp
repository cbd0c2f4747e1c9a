// The committed state carried from one cloud of a body to a refined one: a uniform history and a
// linear displacement arrive exactly, the points at old places keep their own history bit for
// bit, every new point gets one, and the equivalent plastic strain stays non-negative.
#include "meshfree/implicit/elasticity.hpp"
#include "meshfree/implicit/galerkin_model.hpp"
#include "meshfree/implicit/state_transfer.hpp"
#include "test_support.hpp"
#include <catch2/catch.hpp>
#include <cmath>
#include <map>

using namespace mf;

namespace {

struct Clouds {
  spec::ProblemSpec coarse, fine;
  implicit::GalerkinModel from, to;
};

/// The bar of the cyclic test on its own cloud and with a box of half its spacing.
Clouds clouds() {
  PhaseTimer timer;
  Clouds c{load_problem("bar_uniaxial_cyclic"),
           load_problem("bar_uniaxial_cyclic",
                        {"discretisation.refinement=[{box: [[0.2, 0.6], [0.7, 1.3]], "
                         "spacing: 0.05}]"}),
           {},
           {}};
  c.from = implicit::build_galerkin_model(c.coarse, test_session(), timer);
  c.to = implicit::build_galerkin_model(c.fine, test_session(), timer);
  return c;
}

Vec2 linear_u(const Vec2& x) {
  return {1e-3 * x.x() - 2e-3 * x.y() + 0.5, 3e-3 * x.x() + 1e-3};
}

/// Nodal parameters that are u's nodal values: u^h = u for a linear u (linear reproduction).
std::vector<double> parameters_of_linear(const implicit::GalerkinModel& m) {
  std::vector<double> d;
  for (const Vec2& x : m.node_positions()) {
    const Vec2 u = linear_u(x);
    d.push_back(u.x());
    d.push_back(u.y());
  }
  return d;
}

materials::J2State history_at(const Vec2& x) {
  materials::J2State s;
  for (int c = 0; c < 6; ++c) {
    s.plastic_strain(c) = 1e-3 * (c + 1) * (x.x() + x.y() * x.y());
    s.back_stress(c) = 10.0 * (c - 2.5) * x.x() * x.y();
  }
  // A plastic zone with a sharp edge: the interpolation undershoots beside it.
  s.alpha = x.y() > 1.0 ? 0.05 : 0.0;
  return s;
}

} // namespace

TEST_CASE("carried state: uniform history and linear displacement exact on the refined cloud",
          "[adaptivity][transfer]") {
  Clouds c = clouds();
  REQUIRE(c.to.node_count() > c.from.node_count());
  implicit::PointStates st(c.from.domain_table.rows());
  materials::J2State uniform;
  uniform.plastic_strain << 1e-3, -2e-3, 1e-3, 4e-4, 0.0, 0.0;
  uniform.back_stress << 5.0, -10.0, 5.0, 2.0, 0.0, 0.0;
  uniform.alpha = 2.5e-3;
  for (auto& h : st.committed) h = uniform;
  const implicit::CarriedState carried =
      implicit::carry_state(c.from, st, parameters_of_linear(c.from), c.to, test_session());
  REQUIRE(carried.history.size() == static_cast<std::size_t>(c.to.domain_table.rows()));
  CHECK(carried.copied > 0);
  CHECK(carried.interpolated > 0);
  CHECK(carried.copied + carried.interpolated == static_cast<long>(c.to.domain.x.size()));
  double worst = 0.0;
  for (const materials::J2State& h : carried.history) {
    worst = std::max(worst, (h.plastic_strain - uniform.plastic_strain).cwiseAbs().maxCoeff());
    worst = std::max(worst, 1e-3 * (h.back_stress - uniform.back_stress).cwiseAbs().maxCoeff());
    worst = std::max(worst, std::abs(h.alpha - uniform.alpha));
  }
  CHECK(worst < 1e-15); // a partition of unity of equal nodal averages: round-off only

  // u^h on the refined cloud at its Gauss points is the linear field.
  const implicit::ShapeTable& t = c.to.domain_table;
  double u_error = 0.0;
  for (int k = 0; k < t.rows(); ++k) {
    const Vec2 x = c.to.domain.x[c.to.domain_mine.rows[k]];
    u_error = std::max(u_error, (implicit::displacement_at(t, k, carried.d) - linear_u(x)).norm());
  }
  CHECK(u_error < 1e-12);
}

TEST_CASE("carried state: points at old places keep their history bit for bit, the others the "
          "RK approximation, alpha never negative",
          "[adaptivity][transfer]") {
  Clouds c = clouds();
  implicit::PointStates st(c.from.domain_table.rows());
  for (int k = 0; k < c.from.domain_table.rows(); ++k)
    st.committed[k] = history_at(c.from.domain.x[c.from.domain_mine.rows[k]]);
  const implicit::CarriedState carried =
      implicit::carry_state(c.from, st, parameters_of_linear(c.from), c.to, test_session());
  std::map<std::pair<double, double>, int> old_place;
  for (std::size_t r = 0; r < c.from.domain.x.size(); ++r)
    old_place[{c.from.domain.x[r].x(), c.from.domain.x[r].y()}] = static_cast<int>(r);
  long kept = 0, smooth = 0;
  double smooth_error = 0.0, smallest_alpha = 1.0;
  for (int k = 0; k < c.to.domain_table.rows(); ++k) {
    const Vec2 x = c.to.domain.x[c.to.domain_mine.rows[k]];
    const materials::J2State& h = carried.history[k];
    smallest_alpha = std::min(smallest_alpha, h.alpha);
    if (old_place.count({x.x(), x.y()})) {
      const materials::J2State exact = history_at(x);
      CHECK(h.plastic_strain == exact.plastic_strain);
      CHECK(h.back_stress == exact.back_stress);
      CHECK(h.alpha == exact.alpha);
      ++kept;
    } else {
      // The smooth components: an average over a support of the old points, within the
      // field's change over a support (about 0.2 here) of the value at x.
      const materials::J2State exact = history_at(x);
      smooth_error = std::max(
          smooth_error, (h.plastic_strain - exact.plastic_strain).cwiseAbs().maxCoeff() / 6e-3);
      ++smooth;
    }
  }
  INFO("kept " << kept << ", interpolated " << smooth);
  CHECK(kept == carried.copied);
  CHECK(smooth == carried.interpolated);
  CHECK(smooth_error < 0.05);
  CHECK(smallest_alpha >= 0.0);
}
