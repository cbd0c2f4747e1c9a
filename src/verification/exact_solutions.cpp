#include "meshfree/verification/exact_solutions.hpp"
#include <cmath>

namespace mf::verification {

namespace {

struct Displacement {
  const materials::IsotropicElastic& m;
  const Vec2& x;

  Vec2 operator()(const TimoshenkoBeam& b) const {
    const double I = b.D * b.D * b.D / 12.0, X = x.x(), Y = x.y(), E = m.E, nu = m.nu;
    const double ux = -b.P * Y / (6.0 * E * I) *
                      ((6.0 * b.L - 3.0 * X) * X + (2.0 + nu) * (Y * Y - b.D * b.D / 4.0));
    const double uy = b.P / (6.0 * E * I) *
                      (3.0 * nu * Y * Y * (b.L - X) + (4.0 + 5.0 * nu) * b.D * b.D * X / 4.0 +
                       (3.0 * b.L - X) * X * X);
    return {ux, uy};
  }
  Vec2 operator()(const KirschPlate& k) const {
    const double mu = m.E / (2.0 * (1.0 + m.nu));
    const double kappa = (3.0 - m.nu) / (1.0 + m.nu); // plane stress
    const double r = x.norm(), th = std::atan2(x.y(), x.x()), a = k.a;
    const double c = a * k.sigma0 / (8.0 * mu);
    const double ra = r / a, ar = a / r, ar3 = ar * ar * ar;
    const double ux = c * (ra * (kappa + 1.0) * std::cos(th) +
                           2.0 * ar * ((1.0 + kappa) * std::cos(th) + std::cos(3.0 * th)) -
                           2.0 * ar3 * std::cos(3.0 * th));
    const double uy = c * (ra * (kappa - 3.0) * std::sin(th) +
                           2.0 * ar * ((1.0 - kappa) * std::sin(th) + std::sin(3.0 * th)) -
                           2.0 * ar3 * std::sin(3.0 * th));
    return {ux, uy};
  }
  Vec2 operator()(const LinearField& f) const { return f.u0 + f.G * x; }
};

struct Stress {
  const materials::IsotropicElastic& m;
  const Vec2& x;

  Vec3 operator()(const TimoshenkoBeam& b) const {
    const double I = b.D * b.D * b.D / 12.0, X = x.x(), Y = x.y();
    return {-b.P * (b.L - X) * Y / I, 0.0, b.P / (2.0 * I) * (b.D * b.D / 4.0 - Y * Y)};
  }
  Vec3 operator()(const KirschPlate& k) const {
    const double r = x.norm(), th = std::atan2(x.y(), x.x());
    const double a2 = k.a * k.a / (r * r), a4 = a2 * a2, s0 = k.sigma0;
    const double c2 = std::cos(2 * th), c4 = std::cos(4 * th), s2 = std::sin(2 * th),
                 s4 = std::sin(4 * th);
    return {s0 * (1.0 - a2 * (1.5 * c2 + c4) + 1.5 * a4 * c4),
            s0 * (-a2 * (0.5 * c2 - c4) - 1.5 * a4 * c4),
            s0 * (-a2 * (0.5 * s2 + s4) + 1.5 * a4 * s4)};
  }
  Vec3 operator()(const LinearField& f) const {
    const Vec3 eps(f.G(0, 0), f.G(1, 1), f.G(0, 1) + f.G(1, 0));
    return materials::elastic_matrix(m, materials::PlaneModel::PlaneStress) * eps;
  }
};

} // namespace

Vec2 exact_displacement(const ExactSolution& s, const materials::IsotropicElastic& m,
                        const Vec2& x) {
  return std::visit(Displacement{m, x}, s);
}

Vec3 exact_stress(const ExactSolution& s, const materials::IsotropicElastic& m, const Vec2& x) {
  return std::visit(Stress{m, x}, s);
}

} // namespace mf::verification
