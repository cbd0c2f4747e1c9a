#include "meshfree/implicit/solid_bricks.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/core/gauss_legendre.hpp"
#include "meshfree/fem/elements.hpp"
#include <algorithm>
#include <cmath>
#include <numeric>

namespace mf::implicit {

namespace {

constexpr int kSideFaces = 4, kBack = 4, kFront = 5;

/// The brick shape function of the node at natural coordinates n, and its natural gradient:
/// trilinear (8 nodes) or serendipity (20 nodes: corners, mid-edge nodes where one natural
/// coordinate of the node is 0).
double brick_function(bool serendipity, const Vec3& n, const Vec3& p, Vec3& grad) {
  const double a = 1.0 + p.x() * n.x(), b = 1.0 + p.y() * n.y(), c = 1.0 + p.z() * n.z();
  if (!serendipity) {
    grad = 0.125 * Vec3(n.x() * b * c, a * n.y() * c, a * b * n.z());
    return 0.125 * a * b * c;
  }
  if (n.z() == 0.0) { // vertical mid-edge node
    const double q = 1.0 - p.z() * p.z();
    grad = 0.25 * Vec3(n.x() * b * q, a * n.y() * q, -2.0 * p.z() * a * b);
    return 0.25 * a * b * q;
  }
  if (n.x() == 0.0) { // mid-edge node along xi
    const double q = 1.0 - p.x() * p.x();
    grad = 0.25 * Vec3(-2.0 * p.x() * b * c, q * n.y() * c, q * b * n.z());
    return 0.25 * q * b * c;
  }
  if (n.y() == 0.0) { // mid-edge node along eta
    const double q = 1.0 - p.y() * p.y();
    grad = 0.25 * Vec3(n.x() * q * c, -2.0 * p.y() * a * c, a * q * n.z());
    return 0.25 * a * q * c;
  }
  const double s = p.x() * n.x() + p.y() * n.y() + p.z() * n.z();
  grad = 0.125 * Vec3(n.x() * b * c * (s + p.x() * n.x() - 1.0),
                      n.y() * a * c * (s + p.y() * n.y() - 1.0),
                      n.z() * a * b * (s + p.z() * n.z() - 1.0));
  return 0.125 * a * b * c * (s - 2.0);
}

/// Natural point of parameter s in [-1, 1] along the plane element's local edge k (counter-
/// clockwise: edge 0 from corner 0 to corner 1), and d(xi, eta)/ds.
Vec2 on_edge(int k, double s, Vec2& direction) {
  static const Vec2 from[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  direction = 0.5 * (from[(k + 1) % 4] - from[k]);
  return from[k] + (s + 1.0) * direction;
}

} // namespace

std::string ExtrudedMesh::summary() const {
  return detail::concat("bricks: ", element_count(), " of ", nodes_per_element(), " nodes, ",
                        node_count(), " nodes (", layer_count() + 1, " layers of nodes along z)");
}

ExtrudedMesh::ExtrudedMesh(fem::Mesh plane, const geometry::Prism& body, double spacing,
                           const std::vector<geometry::Refinement>& refinement)
    : plane_(std::move(plane)), body_(body),
      layers_(prism_slabs(body, spacing, spacing, refinement, 0.0)) {
  MF_REQUIRE(plane_.type != fem::ElementType::T3,
             "discretisation.fem.element: model solid_3d extrudes q4 or q8 plane elements into "
             "hex8 or hex20 bricks, not t3");
  const int np = plane_.node_count();
  corner_index_.assign(np, -1);
  if (serendipity())
    for (int e = 0; e < plane_.element_count(); ++e)
      for (int a = 0; a < 4; ++a) {
        int& c = corner_index_[plane_.element(e)[a]];
        if (c < 0) c = corners_++;
      }
  for (int l = 0; l <= layer_count(); ++l) {
    const double z = l < layer_count() ? layers_[l].z(0.0) : layers_.back().z(1.0);
    for (const Vec2& p : plane_.x) x_.emplace_back(p.x(), p.y(), z);
  }
  if (!serendipity()) return;
  std::vector<int> corner_node(corners_);
  for (int p = 0; p < np; ++p)
    if (corner_index_[p] >= 0) corner_node[corner_index_[p]] = p;
  for (const Slab& layer : layers_)
    for (int p : corner_node) x_.emplace_back(plane_.x[p].x(), plane_.x[p].y(), layer.z(0.5));
}

void ExtrudedMesh::brick(int e, int l, int* nodes, Vec3* natural) const {
  const int* n = plane_.element(e);
  const Vec2* ref = fem::reference_nodes(plane_.type);
  const int np = plane_.node_count();
  const int lower = l * np, upper = (l + 1) * np;
  for (int a = 0; a < 4; ++a) {
    nodes[a] = lower + n[a], natural[a] = Vec3(ref[a].x(), ref[a].y(), -1.0);
    nodes[4 + a] = upper + n[a], natural[4 + a] = Vec3(ref[a].x(), ref[a].y(), 1.0);
  }
  if (!serendipity()) return;
  const int middle = (layer_count() + 1) * np + l * corners_;
  for (int a = 0; a < 4; ++a) {
    nodes[8 + a] = lower + n[4 + a], natural[8 + a] = Vec3(ref[4 + a].x(), ref[4 + a].y(), -1.0);
    nodes[12 + a] = upper + n[4 + a], natural[12 + a] = Vec3(ref[4 + a].x(), ref[4 + a].y(), 1.0);
    nodes[16 + a] = middle + corner_index_[n[a]];
    natural[16 + a] = Vec3(ref[a].x(), ref[a].y(), 0.0);
  }
}

void ExtrudedMesh::add_point(int e, int l, const Vec3& xi, double w, int face, bool gradients,
                             ElementPoints& out) const {
  double N2[fem::kMaxElementNodes];
  Vec2 dN2[fem::kMaxElementNodes];
  fem::shape_functions(plane_.type, xi.head<2>(), N2, dN2);
  const int* pn = plane_.element(e);
  Vec2 xy = Vec2::Zero();
  Mat2 J = Mat2::Zero(); // columns d(x, y)/dxi and d(x, y)/deta
  for (int a = 0; a < plane_.nodes_per_element(); ++a) {
    xy += N2[a] * plane_.x[pn[a]];
    J.col(0) += dN2[a].x() * plane_.x[pn[a]];
    J.col(1) += dN2[a].y() * plane_.x[pn[a]];
  }
  const double dz = layers_[l].thickness();
  const double z = layers_[l].z(0.5 * (1.0 + xi.z()));
  Vec3 normal = Vec3::Zero();
  double measure = J.determinant() * 0.5 * dz;
  if (face >= 0 && face < kSideFaces) {
    Vec2 direction;
    on_edge(face, 0.0, direction);
    const Vec2 t = J * direction;
    measure = t.norm() * 0.5 * dz;
    normal = Vec3(t.y(), -t.x(), 0.0) / t.norm();
  } else if (face >= kBack) {
    measure = J.determinant();
    normal = Vec3(0.0, 0.0, face == kBack ? -1.0 : 1.0);
  }
  MF_REQUIRE(measure > 0.0, "brick of element ", e, " in layer ", l,
             " has a non-positive Jacobian at a Gauss point");
  int nodes[20];
  Vec3 natural[20];
  brick(e, l, nodes, natural);
  const int n = nodes_per_element();
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return nodes[a] < nodes[b]; });
  const Mat2 inverse_transpose = J.inverse().transpose();
  for (int k : order) {
    Vec3 g;
    out.node.push_back(nodes[k]);
    out.phi.push_back(brick_function(serendipity(), natural[k], xi, g));
    if (gradients) {
      const Vec2 gxy = inverse_transpose * g.head<2>();
      out.dphi.emplace_back(gxy.x(), gxy.y(), g.z() * 2.0 / dz);
    }
  }
  out.offset.push_back(static_cast<int>(out.node.size()));
  out.points.x.emplace_back(xy.x(), xy.y(), z);
  out.points.weight.push_back(w * measure);
  if (face >= 0) out.points.normal.push_back(normal);
}

ElementPoints ExtrudedMesh::body_points(int order) const {
  const GaussRule& g = gauss_legendre(order);
  ElementPoints out;
  for (int l = 0; l < layer_count(); ++l)
    for (int e = 0; e < plane_.element_count(); ++e)
      for (std::size_t k = 0; k < g.points.size(); ++k)
        for (std::size_t j = 0; j < g.points.size(); ++j)
          for (std::size_t i = 0; i < g.points.size(); ++i)
            add_point(e, l, Vec3(g.points[i], g.points[j], g.points[k]),
                      g.weights[i] * g.weights[j] * g.weights[k], -1, true, out);
  return out;
}

ElementPoints ExtrudedMesh::shapes_at(const std::vector<Vec3>& x, bool gradients) const {
  const fem::PointLocator locator(plane_);
  ElementPoints out;
  for (const Vec3& p : x) {
    int e = -1;
    Vec2 xi;
    MF_REQUIRE(locator.locate(p.head<2>(), e, xi), "no element holds the point (", p.x(), ", ",
               p.y(), ", ", p.z(), ")");
    // The layer that holds z (the first or last past the ends), and z's place t across it; on
    // a level between two layers, the one whose t rounds into [0, 1) (the upper but at the top).
    const auto above = std::upper_bound(layers_.begin(), layers_.end(), p.z(),
                                        [](double z, const Slab& s) { return z < s.z(0.0); });
    int l = std::clamp(static_cast<int>(above - layers_.begin()) - 1, 0, layer_count() - 1);
    const auto across = [&](int k) {
      const Level& lo = layers_[k].lo;
      return (p.z() - lo.origin) / lo.step - lo.index;
    };
    double t = across(l);
    if (t >= 1.0 && l + 1 < layer_count())
      t = across(++l);
    else if (t < 0.0 && l > 0)
      t = across(--l);
    add_point(e, l, Vec3(xi.x(), xi.y(), 2.0 * t - 1.0), 1.0, -1, gradients, out);
  }
  return out;
}

ElementPoints ExtrudedMesh::face_points(const std::vector<std::string>& faces, int order,
                                        const std::optional<spec::Box>& box) const {
  const auto named = [&](const std::string& n) {
    return std::find(faces.begin(), faces.end(), n) != faces.end();
  };
  const double size = std::max(body_.depth, body_.section.bounds().size().maxCoeff());
  const GaussRule& g = gauss_legendre(order);
  ElementPoints all;
  std::vector<geometry::Curve> sides;
  for (const geometry::Curve& c : body_.section.boundary())
    if (named(c.name)) sides.push_back(c);
  for (const fem::BoundaryEdge& edge : fem::boundary_edges(plane_)) {
    Vec2 direction;
    const Vec2 middle =
        fem::map_to_physical(plane_, edge.element, on_edge(edge.local_edge, 0.0, direction));
    const bool on = std::any_of(sides.begin(), sides.end(), [&](const geometry::Curve& c) {
      return c.distance_to(middle) < 1e-6 * size;
    });
    if (!on) continue;
    for (int l = 0; l < layer_count(); ++l)
      for (std::size_t k = 0; k < g.points.size(); ++k)
        for (std::size_t i = 0; i < g.points.size(); ++i) {
          const Vec2 xi = on_edge(edge.local_edge, g.points[i], direction);
          add_point(edge.element, l, Vec3(xi.x(), xi.y(), g.points[k]), g.weights[i] * g.weights[k],
                    edge.local_edge, false, all);
        }
  }
  for (const int face : {kBack, kFront}) {
    if (!named(face == kBack ? "back" : "front")) continue;
    const int l = face == kBack ? 0 : layer_count() - 1;
    for (int e = 0; e < plane_.element_count(); ++e)
      for (std::size_t j = 0; j < g.points.size(); ++j)
        for (std::size_t i = 0; i < g.points.size(); ++i)
          add_point(e, l, Vec3(g.points[i], g.points[j], face == kBack ? -1.0 : 1.0),
                    g.weights[i] * g.weights[j], face, false, all);
  }
  return box ? points_in_box(all, *box, 1e-9 * size,
                             static_cast<int>(g.points.size() * g.points.size()), x_)
             : all;
}

} // namespace mf::implicit
