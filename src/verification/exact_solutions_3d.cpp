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

/// The hollow sphere's constants as A and A b^3, written with q = (a / b)^3 so that b may be
/// infinite: A = p q / (1 - q), A b^3 = p a^3 / (1 - q).
struct LameSphere {
  double A, Ab3;
  explicit LameSphere(const ThickSphere& s) {
    const double q = std::pow(s.a / s.b, 3);
    A = s.p * q / (1.0 - q);
    Ab3 = s.p * s.a * s.a * s.a / (1.0 - q);
  }
};

Vec3 sphere_displacement(const ThickSphere& s, const materials::IsotropicElastic& m,
                         const Vec3& x) {
  const LameSphere L(s);
  const double r = x.norm();
  const double ur = ((1.0 - 2.0 * m.nu) * L.A * r + 0.5 * (1.0 + m.nu) * L.Ab3 / (r * r)) / m.E;
  return ur * x / r;
}

/// sigma = sigma_tt I + (sigma_rr - sigma_tt) n n^T, n = x / r.
Vec6 sphere_stress(const ThickSphere& s, const Vec3& x) {
  const LameSphere L(s);
  const double r3 = std::pow(x.norm(), 3);
  const double srr = L.A - L.Ab3 / r3, stt = L.A + 0.5 * L.Ab3 / r3;
  const Mat3 sig = stt * Mat3::Identity() + (srr - stt) * x * x.transpose() / x.squaredNorm();
  Vec6 out;
  out << sig(0, 0), sig(1, 1), sig(2, 2), sig(1, 2), sig(0, 2), sig(0, 1);
  return out;
}

} // namespace

Vec3 exact_displacement_3d(const ExactSolution3D& s, const materials::IsotropicElastic& m,
                           const Vec3& x) {
  if (const auto* f = std::get_if<LinearField3D>(&s)) return f->u0 + f->G * x;
  if (const auto* h = std::get_if<ThickSphere>(&s)) return sphere_displacement(*h, m, x);
  const auto& c = std::get<ThickCylinder>(s);
  const Lame L(c);
  const double r = std::hypot(x.x(), x.y());
  const double ur = (1.0 + m.nu) / m.E * ((1.0 - 2.0 * m.nu) * L.A * r + L.B / r);
  return Vec3(ur * x.x() / r, ur * x.y() / r, 0.0);
}

Eigen::Matrix<double, 6, 1> exact_stress_3d(const ExactSolution3D& s,
                                            const materials::IsotropicElastic& m, const Vec3& x) {
  if (const auto* f = std::get_if<LinearField3D>(&s)) return hooke(m, f->G);
  if (const auto* h = std::get_if<ThickSphere>(&s)) return sphere_stress(*h, x);
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
