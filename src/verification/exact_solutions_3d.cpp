#include "meshfree/verification/exact_solutions_3d.hpp"
#include <cmath>

namespace mf::verification {

namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;

/// Hooke's law in 3D on an engineering-shear strain.
Vec6 hooke(const materials::IsotropicElastic& m, const Mat3& grad) {
  const Mat3 eps = 0.5 * (grad + grad.transpose());
  const double mu = m.E / (2.0 * (1.0 + m.nu));
  const double lambda = m.E * m.nu / ((1.0 + m.nu) * (1.0 - 2.0 * m.nu));
  const Mat3 s = lambda * eps.trace() * Mat3::Identity() + 2.0 * mu * eps;
  Vec6 out;
  out << s(0, 0), s(1, 1), s(2, 2), s(1, 2), s(0, 2), s(0, 1);
  return out;
}

struct Lame {
  double A, B;
  explicit Lame(const ThickCylinder& c) {
    const double d = c.b * c.b - c.a * c.a;
    A = c.p * c.a * c.a / d;
    B = c.p * c.a * c.a * c.b * c.b / d;
  }
};

} // namespace

Vec3 exact_displacement_3d(const ExactSolution3D& s, const materials::IsotropicElastic& m,
                           const Vec3& x) {
  if (const auto* f = std::get_if<LinearField3D>(&s)) return f->u0 + f->G * x;
  const auto& c = std::get<ThickCylinder>(s);
  const Lame L(c);
  const double r = std::hypot(x.x(), x.y());
  const double ur = (1.0 + m.nu) / m.E * ((1.0 - 2.0 * m.nu) * L.A * r + L.B / r);
  return Vec3(ur * x.x() / r, ur * x.y() / r, 0.0);
}

Eigen::Matrix<double, 6, 1> exact_stress_3d(const ExactSolution3D& s,
                                            const materials::IsotropicElastic& m, const Vec3& x) {
  if (const auto* f = std::get_if<LinearField3D>(&s)) return hooke(m, f->G);
  const auto& c = std::get<ThickCylinder>(s);
  const Lame L(c);
  const double r2 = x.x() * x.x() + x.y() * x.y();
  const double srr = L.A - L.B / r2, stt = L.A + L.B / r2;
  const double cc = x.x() * x.x() / r2, ss = x.y() * x.y() / r2, cs = x.x() * x.y() / r2;
  Vec6 out;
  out << srr * cc + stt * ss, srr * ss + stt * cc, 2.0 * m.nu * L.A, 0.0, 0.0, (srr - stt) * cs;
  return out;
}

} // namespace mf::verification
