// The committed state carried from one cloud of a body to a refined one: a uniform history and a
// linear displacement arrive exactly, the points at old places keep their own history bit for
// bit, and every other new point the whole history of its nearest old point.
#include "meshfree/implicit/elasticity.hpp"
#include "meshfree/implicit/galerkin_model.hpp"
#include "meshfree/implicit/point_law.hpp"
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

/// The bar of the cyclic test on its own cloud and with a box of half its spacing (`extra`
/// settings on both).
Clouds clouds(std::vector<std::string> extra = {}) {
  PhaseTimer timer;
  std::vector<std::string> refined = extra;
  refined.push_back("discretisation.refinement=[{box: [[0.2, 0.6], [0.7, 1.3]], spacing: 0.05}]");
  Clouds c{load_problem("bar_uniaxial_cyclic", extra),
           load_problem("bar_uniaxial_cyclic", refined),
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

materials::MaterialState history_at(const Vec2& x) {
  materials::MaterialState s;
  for (int c = 0; c < 6; ++c) {
    s.plastic_strain(c) = 1e-3 * (c + 1) * (x.x() + x.y() * x.y());
    s.back_stress(c) = 10.0 * (c - 2.5) * x.x() * x.y();
  }
  // A plastic zone with a sharp edge.
  s.alpha = x.y() > 1.0 ? 0.05 : 0.0;
  return s;
}

/// The history history_at of every point of the coarse cloud carried to the fine one.
implicit::CarriedState carried_history(const Clouds& c) {
  implicit::PointStates st(c.from.domain_table.rows());
  for (int k = 0; k < c.from.domain_table.rows(); ++k)
    st.committed[k] = history_at(c.from.domain.x[c.from.domain_mine.rows[k]]);
  return implicit::carry_state(c.fine, c.from, st, parameters_of_linear(c.from), c.to,
                               test_session());
}

/// The nearest of the old points to x by a search of all of them, the lowest index among equals.
std::size_t nearest_old(const std::vector<Vec2>& old, const Vec2& x) {
  std::size_t r = 0;
  for (std::size_t q = 1; q < old.size(); ++q)
    if ((old[q] - x).squaredNorm() < (old[r] - x).squaredNorm()) r = q;
  return r;
}

} // namespace

TEST_CASE("carried state: uniform history and linear displacement exact on the refined cloud",
          "[adaptivity][transfer]") {
  Clouds c = clouds();
  REQUIRE(c.to.node_count() > c.from.node_count());
  implicit::PointStates st(c.from.domain_table.rows());
  materials::MaterialState uniform;
  uniform.plastic_strain << 1e-3, -2e-3, 1e-3, 4e-4, 0.0, 0.0;
  uniform.back_stress << 5.0, -10.0, 5.0, 2.0, 0.0, 0.0;
  uniform.alpha = 2.5e-3;
  for (auto& h : st.committed) h = uniform;
  const implicit::CarriedState carried =
      implicit::carry_state(c.fine, c.from, st, parameters_of_linear(c.from), c.to, test_session());
  REQUIRE(carried.history.size() == static_cast<std::size_t>(c.to.domain_table.rows()));
  CHECK(carried.copied > 0);
  CHECK(carried.nearest > 0);
  CHECK(carried.copied + carried.nearest == static_cast<long>(c.to.domain.x.size()));
  double worst = 0.0;
  for (const materials::MaterialState& h : carried.history) {
    worst = std::max(worst, (h.plastic_strain - uniform.plastic_strain).cwiseAbs().maxCoeff());
    worst = std::max(worst, 1e-3 * (h.back_stress - uniform.back_stress).cwiseAbs().maxCoeff());
    worst = std::max(worst, std::abs(h.alpha - uniform.alpha));
  }
  CHECK(worst == 0.0); // copies of one state

  // u^h on the refined cloud at its Gauss points is the linear field.
  const implicit::ShapeTable& t = c.to.domain_table;
  double u_error = 0.0;
  for (int k = 0; k < t.rows(); ++k) {
    const Vec2 x = c.to.domain.x[c.to.domain_mine.rows[k]];
    u_error = std::max(u_error, (implicit::displacement_at(t, k, carried.d) - linear_u(x)).norm());
  }
  CHECK(u_error < 1e-12);
}

TEST_CASE("carried state: points at old places keep their history bit for bit, the others "
          "their nearest old point's",
          "[adaptivity][transfer]") {
  Clouds c = clouds();
  const implicit::CarriedState carried = carried_history(c);
  const std::vector<Vec2>& old = c.from.domain.x;
  long kept = 0, near = 0;
  for (int k = 0; k < c.to.domain_table.rows(); ++k) {
    const Vec2 x = c.to.domain.x[c.to.domain_mine.rows[k]];
    const std::size_t r = nearest_old(old, x);
    const materials::MaterialState& h = carried.history[k];
    const materials::MaterialState exact = history_at(old[r]);
    INFO("point (" << x.x() << ", " << x.y() << "), nearest old (" << old[r].x() << ", "
                   << old[r].y() << ")");
    CHECK(h.plastic_strain == exact.plastic_strain);
    CHECK(h.back_stress == exact.back_stress);
    CHECK(h.alpha == exact.alpha);
    ++(old[r] == x ? kept : near);
  }
  INFO("kept " << kept << ", from the nearest " << near);
  CHECK(kept == carried.copied);
  CHECK(near == carried.nearest);
  CHECK(near > 0);
}

TEST_CASE("carried state: a point takes the history of its nearest old point of its own material",
          "[adaptivity][transfer]") {
  // An elastic region over the bar's upper part, its interface y = 0.98 inside the refined box:
  // new points just below it are nearer to old points above it, of the other material.
  Clouds c =
      clouds({"materials=[{name: steel, E: 2.0e5, nu: 0.3, plasticity: {yield_stress: 250}}, "
              "{name: glass, E: 7.0e4, nu: 0.2}]",
              "material=steel", "material_regions=[{material: glass, box: [[0, 0.98], [1, 2]]}]"});
  const implicit::CarriedState carried = carried_history(c);
  const std::vector<Vec2>& old = c.from.domain.x;
  long across = 0; // points whose nearest old point of any material is of the other one
  for (int k = 0; k < c.to.domain_table.rows(); ++k) {
    const Vec2 x = c.to.domain.x[c.to.domain_mine.rows[k]];
    const int material = implicit::material_at(c.fine, x);
    std::size_t r = old.size(), any = 0;
    for (std::size_t q = 0; q < old.size(); ++q) {
      if ((old[q] - x).squaredNorm() < (old[any] - x).squaredNorm()) any = q;
      if (implicit::material_at(c.fine, old[q]) != material) continue;
      if (r == old.size() || (old[q] - x).squaredNorm() < (old[r] - x).squaredNorm()) r = q;
    }
    REQUIRE(r < old.size());
    across += implicit::material_at(c.fine, old[any]) != material;
    const materials::MaterialState exact = history_at(old[r]);
    CHECK(carried.history[k].plastic_strain == exact.plastic_strain);
    CHECK(carried.history[k].alpha == exact.alpha);
  }
  INFO("new points nearest to an old point of the other material: " << across);
  CHECK(across > 0);
}

TEST_CASE("carried state: a yielded point keeps its old point's stress on the new cloud's "
          "strain, one that never yielded its plastic strain",
          "[adaptivity][transfer]") {
  // A displacement of the coarse cloud that is not linear (so its strain differs from the fine
  // cloud's at a point and at its nearest old point). A new point of the plastic zone (alpha > 0,
  // y > 1) has its old point's strain minus plastic strain, and the same stress from the
  // material's update (the return map from the same elastic trial), in plane stress and plane
  // strain (whose sigma_zz depends on the plastic strain's zz component, kept); the others keep
  // the old plastic strain, their stress that of the new strain.
  for (const char* model : {"plane_stress", "plane_strain"}) {
    Clouds c = clouds({std::string("model.type=") + model});
    std::vector<double> d = parameters_of_linear(c.from);
    const std::vector<Vec2>& nodes = c.from.node_positions();
    for (std::size_t I = 0; I < nodes.size(); ++I)
      d[2 * I + 1] += 1e-3 * std::sin(3.0 * nodes[I].x()) * nodes[I].y() * nodes[I].y();
    implicit::PointStates st(c.from.domain_table.rows());
    for (int k = 0; k < c.from.domain_table.rows(); ++k)
      st.committed[k] = history_at(c.from.domain.x[c.from.domain_mine.rows[k]]);
    const implicit::CarriedState carried =
        implicit::carry_state(c.fine, c.from, st, d, c.to, test_session());
    const std::vector<materials::MaterialState> moved =
        implicit::history_keeping_stress(carried, c.to, carried.d);
    const std::vector<Vec2>& old = c.from.domain.x;
    const implicit::PointLaws laws = implicit::point_laws(c.fine, old);
    const materials::PlaneModel plane = c.fine.model;
    double worst = 0.0, stress = 0.0, scale = 0.0, shifted = 0.0;
    long yielded = 0, elastic = 0;
    for (int k = 0; k < c.to.domain_table.rows(); ++k) {
      const std::size_t r = nearest_old(old, c.to.domain.x[c.to.domain_mine.rows[k]]);
      const Vec3 e_old = implicit::strain_at(c.from.domain_table, static_cast<int>(r), d);
      const Vec3 e_new = implicit::strain_at(c.to.domain_table, k, carried.d);
      const materials::MaterialState was = history_at(old[r]);
      if (!(was.alpha > 0.0)) {
        CHECK(moved[k].plastic_strain == was.plastic_strain);
        ++elastic;
        continue;
      }
      Vec3 p_old, p_new;
      for (int a = 0; a < 3; ++a) {
        p_old(a) = was.plastic_strain(materials::kPlane[a]);
        p_new(a) = moved[k].plastic_strain(materials::kPlane[a]);
      }
      worst = std::max(worst, ((e_new - p_new) - (e_old - p_old)).cwiseAbs().maxCoeff());
      shifted = std::max(shifted, (p_new - p_old).cwiseAbs().maxCoeff());
      const materials::StressUpdate2D then = laws.update(plane, static_cast<int>(r), e_old, was);
      const materials::StressUpdate2D now =
          laws.update(plane, static_cast<int>(r), e_new, moved[k]);
      stress = std::max({stress, (now.stress - then.stress).cwiseAbs().maxCoeff(),
                         std::abs(now.stress_zz - then.stress_zz)});
      scale = std::max(scale, then.stress.cwiseAbs().maxCoeff());
      CHECK(moved[k].alpha == was.alpha);
      CHECK(moved[k].back_stress == was.back_stress);
      CHECK(moved[k].plastic_strain(2) == was.plastic_strain(2));
      ++yielded;
    }
    INFO(model << ": largest change of the elastic strain " << worst << ", of the stress " << stress
               << " (largest stress " << scale << "), of the plastic strain " << shifted
               << "; points yielded " << yielded << ", elastic " << elastic);
    CHECK(yielded > 0);
    CHECK(elastic > 0);
    CHECK(worst < 1e-15);
    CHECK(stress <= 1e-10 * scale);
    CHECK(shifted > 1e-6); // the two clouds' strains do differ
  }
}

namespace {
/// `refinement` boxes of `spacing` stepping diagonally across the bar from (x, y), `n` of them
/// 0.4 wide, one bar spacing apart: the boxes refinement along a shear band makes.
std::string staircase(double x, double y, int n, double spacing) {
  std::string boxes;
  for (int i = 0; i < n; ++i)
    boxes += (i ? ", " : "") + detail::concat("{box: [[", x + 0.1 * i, ", ", y + 0.1 * i, "], [",
                                              x + 0.1 * i + 0.4, ", ", y + 0.1 * i + 0.4,
                                              "]], spacing: ", spacing, "}");
  return boxes;
}
} // namespace

TEST_CASE("carried state: the refined cloud's u^h keeps the old strain where boxes of two "
          "spacings meet (a fit at the nodes alone wiggles between them)",
          "[adaptivity][transfer]") {
  // Both clouds with the adapted supports; the refined one by a staircase of boxes, by a box
  // with a finer one inside, and by the staircase on a base spacing that does not divide the bar.
  struct Case {
    const char* what;
    double spacing;
    std::string boxes;
  };
  const std::vector<Case> cases = {
      {"a staircase of boxes", 0.1, staircase(0.1, 0.3, 6, 0.05)},
      {"a box with a finer one inside", 0.1,
       "{box: [[0.2, 0.6], [0.8, 1.4]], spacing: 0.05}, "
       "{box: [[0.4, 0.8], [0.6, 1.0]], spacing: 0.025}"},
      {"a staircase on a spacing that does not divide the bar", 0.13,
       staircase(0.1, 0.3, 6, 0.065)},
  };
  const Case& c = cases[GENERATE(0, 1, 2)];
  INFO(c.what);
  const std::vector<std::string> adapt = {"discretisation.adapt={target: 0.5, every: 1}",
                                          detail::concat("discretisation.spacing=", c.spacing)};
  PhaseTimer timer;
  std::vector<std::string> refined = adapt;
  refined.push_back("discretisation.refinement=[" + c.boxes + "]");
  const spec::ProblemSpec coarse = load_problem("bar_uniaxial_cyclic", adapt);
  const spec::ProblemSpec fine = load_problem("bar_uniaxial_cyclic", refined);
  const implicit::GalerkinModel from =
      implicit::build_galerkin_model(coarse, test_session(), timer);
  const implicit::GalerkinModel to = implicit::build_galerkin_model(fine, test_session(), timer);
  // A smooth field no linear basis holds: its u^h on the old cloud is what is carried.
  const auto field = [](const Vec2& y) {
    return Vec2(1e-3 * std::sin(3.0 * y.x()) * std::cos(2.0 * y.y()), 1e-3 * y.x() * y.x() * y.y());
  };
  const auto nodal_values = [&](const implicit::GalerkinModel& m) {
    std::vector<double> v;
    for (const Vec2& y : m.node_positions()) v.push_back(field(y).x()), v.push_back(field(y).y());
    return v;
  };
  const std::vector<double> d = nodal_values(from), own = nodal_values(to);
  const implicit::CarriedState carried = implicit::carry_state(
      fine, from, implicit::PointStates(from.domain_table.rows()), d, to, test_session());
  // The carried strain against the old one, and the new cloud's own reach: the strain of its
  // nodal values of the field against the old cloud's.
  const std::vector<Vec2> x = implicit::domain_rows(to);
  const implicit::ShapeTable old_at = implicit::shapes_at(from, x, true);
  double misfit = 0.0, reach = 0.0;
  for (int k = 0; k < to.domain_table.rows(); ++k) {
    const Vec3 was = implicit::strain_at(old_at, k, d);
    misfit = std::max(misfit, (implicit::strain_at(to.domain_table, k, carried.d) - was).norm());
    reach = std::max(reach, (implicit::strain_at(to.domain_table, k, own) - was).norm());
  }
  INFO("largest misfit " << misfit << ", the new cloud's own " << reach);
  // The nodal fit: 10 times the new cloud's own on the staircase.
  CHECK(misfit < 2.0 * reach);
}
