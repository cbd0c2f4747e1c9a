#include "meshfree/implicit/point_law.hpp"
#include "meshfree/materials/elastic.hpp"
#include <algorithm>
#include <cmath>

namespace mf::implicit {

std::pair<Vec3, double> PointLaws::elastic_stress(materials::PlaneModel model, int k,
                                                  const Vec3& strain) const {
  const int m = material[k];
  const Vec3 stress = elastic[m] * strain;
  return {stress, materials::out_of_plane_stress(materials::elasticity(params[m]), model, stress)};
}

namespace {

/// Tolerance of region membership: a point on a region's boundary belongs to it.
double region_tolerance(const spec::ProblemSpec& spec) {
  return 1e-9 * spec.domain.bounds().size().maxCoeff();
}

/// Where the vertical line through x crosses a circle (none if it misses it).
void add_circle_crossings(double x, const Vec2& center, double radius, std::vector<double>& ys) {
  const double dx = x - center.x();
  if (std::abs(dx) >= radius) return;
  const double h = std::sqrt(radius * radius - dx * dx);
  ys.push_back(center.y() - h);
  ys.push_back(center.y() + h);
}

void add_region_crossings(double x, const spec::Region& g, std::vector<double>& ys) {
  const auto c2 = [](const spec::Point& p) { return Vec2(p.x(), p.y()); };
  if (g.box) {
    ys.push_back(g.box->lo.y());
    ys.push_back(g.box->hi.y());
  }
  if (g.circle) add_circle_crossings(x, c2(g.circle->center), g.circle->radius, ys);
  if (g.ring) {
    add_circle_crossings(x, c2(g.ring->center), g.ring->inner_radius, ys);
    add_circle_crossings(x, c2(g.ring->center), g.ring->outer_radius, ys);
  }
  for (const spec::Circle& h : g.holes) add_circle_crossings(x, c2(h.center), h.radius, ys);
  for (const geometry::OutlineHole& h : g.outline_holes)
    for (const geometry::Curve& c : h.loop()) geometry::vertical_crossings(c, x, ys);
  if (g.part) {
    g.part->outline_crossings(x, ys);
    g.part->hole_crossings(x, ys);
  }
}

/// The 3D compliance applied to [xx, yy, xy, zz]: the elastic strain of a stress, engineering
/// shear (Hooke's law, e.g. Timoshenko & Goodier 1970, eq. 3).
Vec4 compliance(const materials::IsotropicElastic& p, const Vec4& s) {
  const double E = p.E, nu = p.nu;
  return {(s(0) - nu * (s(1) + s(3))) / E, (s(1) - nu * (s(0) + s(3))) / E,
          2.0 * (1.0 + nu) / E * s(2), (s(3) - nu * (s(0) + s(1))) / E};
}

bool is_zero(const Vec4& v) {
  return (v.array() == 0.0).all();
}

} // namespace

int material_at(const spec::ProblemSpec& spec, const Vec2& x) {
  auto& galerkin = spec.galerkin();
  const spec::Point p(x.x(), x.y(), 0.0);
  const double tol = region_tolerance(spec);
  for (auto r = galerkin.material_regions.rbegin(); r != galerkin.material_regions.rend(); ++r)
    if (r->region.contains(p, tol)) return r->material;
  return galerkin.material_index;
}

materials::ConstitutiveModel material_parameters(const spec::ProblemSpec& spec, int material) {
  const spec::MaterialSpec& m = spec.materials.at(static_cast<std::size_t>(material));
  materials::ConstitutiveModel p = m.plasticity.value_or(materials::J2Parameters{});
  materials::set_elasticity(p, {m.E, m.nu});
  return p;
}

Vec4 initial_stress_at(const spec::ProblemSpec& spec, const Vec2& x) {
  auto& galerkin = spec.galerkin();
  if (!galerkin.initial_stress) return Vec4::Zero();
  const spec::GeostaticStress& g = *galerkin.initial_stress;
  const double top = g.surface;
  if (!(x.y() < top)) return Vec4::Zero();
  // The breaks of the column: where it crosses a region's, a hole's or the outline's boundary.
  std::vector<double> ys{x.y(), top};
  for (const spec::MaterialRegion& mr : galerkin.material_regions)
    add_region_crossings(x.x(), mr.region, ys);
  spec.domain.hole_crossings(x.x(), ys);
  spec.domain.outline_crossings(x.x(), ys);
  std::sort(ys.begin(), ys.end());
  double weight = 0.0; // int_y^top rho dz
  for (std::size_t i = 0; i + 1 < ys.size(); ++i) {
    const double lo = std::max(ys[i], x.y()), hi = std::min(ys[i + 1], top);
    if (!(hi > lo)) continue;
    const Vec2 mid(x.x(), 0.5 * (lo + hi));
    if (!spec.domain.contains(mid)) continue; // a hole or outside the outline: no weight
    weight += spec.materials[material_at(spec, mid)].density * (hi - lo);
  }
  const double sv = -weight * galerkin.gravity.norm();
  const double szz = spec.model == materials::PlaneModel::PlaneStrain ? g.k0 * sv : 0.0;
  return {g.k0 * sv, sv, 0.0, szz};
}

PointLaw point_law(const spec::ProblemSpec& spec, const Vec2& x) {
  PointLaw law;
  law.material = material_at(spec, x);
  law.params = material_parameters(spec, law.material);
  law.plastic = spec.materials[law.material].plasticity.has_value();
  law.initial_stress = initial_stress_at(spec, x);
  return law;
}

Vec2 body_force_at(const spec::ProblemSpec& spec, const Vec2& x) {
  auto& galerkin = spec.galerkin();
  if (!has_gravity(spec)) return galerkin.body_force;
  return galerkin.body_force + spec.materials[material_at(spec, x)].density * galerkin.gravity;
}

materials::StressUpdate2D update_law(materials::PlaneModel model,
                                     const materials::ConstitutiveModel& law, bool plastic,
                                     const Vec4& sigma0, const Vec3& strain,
                                     const materials::MaterialState& committed) {
  const bool plane_strain = model == materials::PlaneModel::PlaneStrain;
  const bool initial = !is_zero(sigma0);
  const materials::IsotropicElastic e = materials::elasticity(law);
  if (!plastic) {
    // sigma = sigma0 + C (eps - eps_p), eps_p = 0 at an elastic point.
    materials::StressUpdate2D r;
    r.tangent = materials::elastic_matrix(e, model);
    r.stress = r.tangent * strain;
    r.stress_zz = materials::out_of_plane_stress(e, model, r.stress);
    r.strain_zz = plane_strain ? 0.0 : -e.nu / (1.0 - e.nu) * (strain(0) + strain(1));
    if (initial) {
      r.stress += sigma0.head<3>();
      r.stress_zz += sigma0(3);
    }
    r.state = committed;
    return r;
  }
  if (!initial) return materials::stress_update_plane(law, model, strain, committed);
  // The initial elastic strain eps0 = C^-1 sigma0 added to the strain of the displacement.
  const Vec4 e0 = compliance(e, sigma0);
  const Vec3 total(strain(0) + e0(0), strain(1) + e0(1), strain(2) + e0(2));
  if (!plane_strain) {
    // sigma0_zz = 0 in plane stress; the return finds eps_zz with sigma_zz = 0 itself.
    materials::StressUpdate2D r = materials::stress_update_plane(law, model, total, committed);
    r.strain_zz -= e0(3);
    return r;
  }
  materials::Vec6 e3;
  e3 << total(0), total(1), e0(3), 0.0, 0.0, total(2);
  return materials::voigt::reduce(materials::stress_update_3d(law, e3, committed), 0.0);
}

materials::StressUpdate2D update_point(const spec::ProblemSpec& spec, const PointLaw& law,
                                       const Vec3& strain,
                                       const materials::MaterialState& committed) {
  return update_law(spec.model, law.params, law.plastic, law.initial_stress, strain, committed);
}

PointLaws point_laws(const spec::ProblemSpec& spec, const std::vector<Vec2>& x) {
  auto& galerkin = spec.galerkin();
  PointLaws L;
  const std::size_t nm = spec.materials.size();
  L.params.resize(nm);
  L.plastic.assign(nm, 0);
  L.elastic.assign(nm, Mat3::Zero());
  std::vector<char> used(nm, 0);
  L.material.resize(x.size());
  for (std::size_t k = 0; k < x.size(); ++k) {
    L.material[k] = material_at(spec, x[k]);
    used[L.material[k]] = 1;
  }
  std::vector<double> density(nm, 0.0);
  for (std::size_t m = 0; m < nm; ++m) {
    if (!used[m]) continue;
    const int i = static_cast<int>(m);
    L.params[m] = material_parameters(spec, i);
    L.plastic[m] = spec.materials[m].plasticity.has_value();
    L.elastic[m] = materials::elastic_matrix(materials::elasticity(L.params[m]), spec.model);
    density[m] = spec.materials[m].density;
    L.any_plastic = L.any_plastic || L.plastic[m];
  }
  L.one_material = std::count(used.begin(), used.end(), 1) <= 1;
  if (has_body_force(spec)) {
    L.body_force.resize(x.size());
    for (std::size_t k = 0; k < x.size(); ++k)
      L.body_force[k] = !has_gravity(spec)
                            ? galerkin.body_force
                            : Vec2(galerkin.body_force + density[L.material[k]] * galerkin.gravity);
  }
  if (galerkin.initial_stress) {
    L.initial_stress.resize(x.size());
    for (std::size_t k = 0; k < x.size(); ++k) L.initial_stress[k] = initial_stress_at(spec, x[k]);
  }
  return L;
}

} // namespace mf::implicit
