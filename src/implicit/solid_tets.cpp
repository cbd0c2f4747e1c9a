#include "meshfree/implicit/solid_tets.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/fem/elements.hpp"
#include <algorithm>
#include <cmath>
#include <numeric>

namespace mf::implicit {

namespace {

double body_size(const geometry::Prism& body) {
  return std::max(body.depth, body.section.bounds().size().maxCoeff());
}

} // namespace

TetElements::TetElements(fem::TetMesh mesh, const geometry::Prism& body)
    : mesh_(std::move(mesh)), body_(body), names_(body.face_names()),
      boundary_(fem::boundary_faces(mesh_)), locator_(std::make_unique<fem::TetLocator>(mesh_)) {
  const double tol = 1e-6 * body_size(body_);
  for (const fem::TetFace& f : boundary_) {
    const int k = face_of(f, tol);
    if (k < 0) {
      const int* n = mesh_.element(f.element);
      const Vec3 c = mesh_.x[n[fem::tet_face_corners(f.local_face)[0]]];
      fail("the tetrahedra of the body have a boundary face at (", c.x(), ", ", c.y(), ", ", c.z(),
           ") on no face of the prism: the mesh does not follow the geometry");
    }
    boundary_name_.push_back(k);
  }
}

int TetElements::face_of(const fem::TetFace& f, double tol) const {
  const int* n = mesh_.element(f.element);
  const int* corners = fem::tet_face_corners(f.local_face);
  const auto all = [&](auto&& on) {
    return on(mesh_.x[n[corners[0]]]) && on(mesh_.x[n[corners[1]]]) && on(mesh_.x[n[corners[2]]]);
  };
  const auto index = [&](const std::string& name) {
    return static_cast<int>(std::find(names_.begin(), names_.end(), name) - names_.begin());
  };
  if (all([&](const Vec3& p) { return std::abs(p.z() - body_.z0) < tol; })) return index("back");
  if (all([&](const Vec3& p) { return std::abs(p.z() - body_.z1()) < tol; })) return index("front");
  for (const geometry::Curve& c : body_.section.boundary())
    if (all([&](const Vec3& p) { return c.distance_to(p.head<2>()) < tol; })) return index(c.name);
  for (const geometry::Sphere& s : body_.spheres)
    if (all([&](const Vec3& p) { return std::abs(s.distance(p)) < tol; })) return index(s.name);
  return -1;
}

std::string TetElements::summary() const {
  return detail::concat("tetrahedra: ", element_count(), " of ", nodes_per_element(), " nodes, ",
                        node_count(), " nodes");
}

void TetElements::add_point(int e, const Vec3& xi, double w, int face, bool gradients,
                            ElementPoints& out) const {
  double N[fem::kTetMaxNodes];
  Vec3 dN[fem::kTetMaxNodes];
  fem::tet_shape_functions(mesh_.quadratic, xi, N, dN);
  const int* n = mesh_.element(e);
  const int npe = mesh_.nodes_per_element();
  Vec3 x = Vec3::Zero();
  Mat3 J = Mat3::Zero(); // columns dx/dxi_k
  for (int a = 0; a < npe; ++a) {
    x += N[a] * mesh_.x[n[a]];
    J += mesh_.x[n[a]] * dN[a].transpose();
  }
  double measure = J.determinant();
  MF_REQUIRE(measure > 0.0, "tetrahedron ", e, " has a non-positive Jacobian at (", x.x(), ", ",
             x.y(), ", ", x.z(), ")");
  Vec3 normal = Vec3::Zero();
  if (face >= 0) {
    Vec3 ds, dt;
    fem::on_tet_face(face, Vec2::Zero(), &ds, &dt);
    const Vec3 c = (J * ds).cross(J * dt);
    measure = c.norm();
    normal = c / measure;
  }
  std::vector<int> order(npe);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return n[a] < n[b]; });
  const Mat3 inverse_transpose = J.inverse().transpose();
  for (int k : order) {
    out.node.push_back(n[k]);
    out.phi.push_back(N[k]);
    if (gradients) out.dphi.push_back(inverse_transpose * dN[k]);
  }
  out.offset.push_back(static_cast<int>(out.node.size()));
  out.points.x.push_back(x);
  out.points.weight.push_back(w * measure);
  if (face >= 0) out.points.normal.push_back(normal);
}

ElementPoints TetElements::body_points(int order) const {
  const fem::TetRule rule = fem::tet_rule(order);
  ElementPoints out;
  for (int e = 0; e < mesh_.element_count(); ++e)
    for (std::size_t q = 0; q < rule.xi.size(); ++q)
      add_point(e, rule.xi[q], rule.weight[q], -1, true, out);
  return out;
}

ElementPoints TetElements::face_points(const std::vector<std::string>& faces, int order,
                                       const std::optional<spec::Box>& box) const {
  const int degree = std::max(order, mesh_.quadratic ? 4 : 2);
  const fem::ReferenceRule rule = fem::domain_rule(fem::ElementType::T3, degree);
  ElementPoints all;
  for (std::size_t b = 0; b < boundary_.size(); ++b) {
    if (std::find(faces.begin(), faces.end(), names_[boundary_name_[b]]) == faces.end()) continue;
    const fem::TetFace& f = boundary_[b];
    for (std::size_t q = 0; q < rule.xi.size(); ++q)
      add_point(f.element, fem::on_tet_face(f.local_face, rule.xi[q]), rule.weight[q], f.local_face,
                false, all);
  }
  return box ? points_in_box(all, *box, 1e-9 * body_size(body_), static_cast<int>(rule.xi.size()),
                             nodes())
             : all;
}

ElementPoints TetElements::shapes_at(const std::vector<Vec3>& x, bool gradients) const {
  ElementPoints out;
  for (const Vec3& p : x) {
    int e = -1;
    Vec3 xi;
    MF_REQUIRE(locator_->locate(p, e, xi), "no element holds the point (", p.x(), ", ", p.y(), ", ",
               p.z(), ")");
    add_point(e, xi, 1.0, -1, gradients, out);
  }
  return out;
}

} // namespace mf::implicit
