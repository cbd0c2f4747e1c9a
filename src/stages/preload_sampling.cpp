#include "meshfree/stages/preload_sampling.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/implicit/elasticity.hpp"
#include "meshfree/implicit/elastoplastic_system.hpp"
#include <type_traits>

namespace mf::stages {

Mirrored mirror_into(const Vec3& x, const std::vector<spec::MirrorPlane>& mirror,
                     const Vec3& inside) {
  Mirrored m;
  Vec3 y = x;
  for (const spec::MirrorPlane& p : mirror) {
    const double side = inside[p.axis] - p.at;
    if ((y[p.axis] - p.at) * side < 0.0) {
      y[p.axis] = 2.0 * p.at - y[p.axis];
      m.flip[p.axis] = !m.flip[p.axis];
    }
  }
  m.x = y;
  return m;
}

std::vector<Mirrored> mirror_into(const std::vector<Vec3>& x,
                                  const std::vector<spec::MirrorPlane>& mirror,
                                  const Vec3& inside) {
  std::vector<Mirrored> out;
  out.reserve(x.size());
  for (const Vec3& p : x) out.push_back(mirror_into(p, mirror, inside));
  return out;
}

std::vector<double> flat(const std::vector<Vec3>& u) {
  std::vector<double> out(3 * u.size());
  for (std::size_t i = 0; i < u.size(); ++i)
    for (int d = 0; d < 3; ++d) out[3 * i + d] = u[i][d];
  return out;
}

PreloadAtParticles select_particles(const PreloadAtParticles& pa, const std::vector<long>& ids) {
  const auto pick = [&ids](const auto& all) {
    std::decay_t<decltype(all)> out;
    out.reserve(ids.size());
    for (long i : ids) out.push_back(all[static_cast<std::size_t>(i)]);
    return out;
  };
  PreloadAtParticles out;
  out.pseudo_time = pa.pseudo_time;
  for (std::size_t k = 0; k < pa.u.size(); ++k) {
    out.u.push_back(pick(pa.u[k]));
    out.stress.push_back(pick(pa.stress[k]));
    out.alpha.push_back(pick(pa.alpha[k]));
  }
  out.history = pick(pa.history);
  out.plastic = pick(pa.plastic);
  out.image = pick(pa.image);
  return out;
}

Vec3 mirrored(const Vec3& v, const Mirrored& m) {
  Vec3 w = v;
  for (int a = 0; a < 3; ++a)
    if (m.flip[a]) w[a] = -w[a];
  return w;
}

Vec6 mirrored(const Vec6& s, const Mirrored& m) {
  // A reflection reverses axis a: a tensor component ij changes sign when exactly one of i, j
  // is a reversed axis. Voigt order xx yy zz yz xz xy.
  static const int pair[6][2] = {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};
  Vec6 t = s;
  for (int k = 3; k < 6; ++k)
    if (m.flip[pair[k][0]] != m.flip[pair[k][1]]) t[k] = -t[k];
  return t;
}

namespace {

Vec6 stress_3d(const materials::StressUpdate2D& r) {
  Vec6 s;
  s << r.stress(0), r.stress(1), r.stress_zz, 0.0, 0.0, r.stress(2);
  return s;
}

} // namespace

materials::MaterialState mirrored(const materials::MaterialState& h, const Mirrored& m) {
  materials::MaterialState out = h;
  out.plastic_strain = mirrored(h.plastic_strain, m);
  out.back_stress = mirrored(h.back_stress, m);
  return out;
}

std::vector<Mirrored> mirror_images(const Vec3& x, const std::vector<spec::MirrorPlane>& mirror,
                                    int dims) {
  std::vector<Mirrored> out{Mirrored{x, {}}};
  for (const spec::MirrorPlane& m : mirror) {
    if (m.axis >= dims) continue;
    const std::size_t n = out.size();
    for (std::size_t k = 0; k < n; ++k) {
      Mirrored how = out[k];
      how.x[m.axis] = 2.0 * m.at - how.x[m.axis];
      how.flip[m.axis] = !how.flip[m.axis];
      out.push_back(how);
    }
  }
  return out;
}

PreloadAtParticles unloaded_preload(int N, std::vector<Mirrored> image) {
  const std::size_t np = image.size();
  PreloadAtParticles out;
  out.image = std::move(image);
  out.pseudo_time.resize(N + 1);
  for (int n = 0; n <= N; ++n) out.pseudo_time[n] = static_cast<double>(n) / N - 1.0;
  out.u.assign(N + 1, std::vector<Vec3>(np, Vec3::Zero()));
  out.stress.assign(N + 1, std::vector<Vec6>(np, Vec6::Zero()));
  out.alpha.assign(N + 1, std::vector<double>(np, 0.0));
  out.history.resize(np);
  out.plastic.assign(np, 0);
  return out;
}

PreloadAtParticles sample_preload(const spec::ProblemSpec& preload,
                                  const implicit::ElastoplasticResult& r,
                                  const std::vector<Vec3>& x,
                                  const std::vector<spec::MirrorPlane>& mirror,
                                  const std::string& key_path) {
  const implicit::GalerkinModel& model = *r.state.model;
  const int np = static_cast<int>(x.size());
  const int N = static_cast<int>(r.increments.size()) - 1;
  MF_REQUIRE(N >= 1, key_path, ": the preload has no converged increment to start from");
  for (int n = 1; n <= N; ++n)
    MF_REQUIRE(r.increments[n].parameters.size() == r.state.parameters.size(), key_path,
               ": the preload did not record its increments");

  Vec2 centre = Vec2::Zero();
  for (const Vec2& p : model.node_positions()) centre += p;
  centre /= static_cast<double>(model.node_count());
  PreloadAtParticles out =
      unloaded_preload(N, mirror_into(x, mirror, Vec3(centre.x(), centre.y(), 0.0)));
  const std::vector<Mirrored>& image = out.image;
  std::vector<Vec2> points(np);
  for (int p = 0; p < np; ++p) points[p] = image[p].x.head<2>();
  implicit::ShapeTable table;
  try {
    table = implicit::shapes_at(model, points, true);
  } catch (const Error& e) {
    fail(key_path, ": a particle lies outside the preload's body (", e.what(), ")");
  }
  const std::vector<double> zero(r.state.parameters.size(), 0.0);

#pragma omp parallel for schedule(dynamic, 64)
  for (int p = 0; p < np; ++p) {
    const implicit::PointLaw law = implicit::point_law(preload, points[p]);
    materials::MaterialState committed;
    for (int n = 0; n <= N; ++n) {
      const std::vector<double>& d = n == 0 ? zero : r.increments[n].parameters;
      const materials::StressUpdate2D res =
          implicit::update_point(preload, law, implicit::strain_at(table, p, d), committed);
      committed = res.state;
      const Vec2 u = implicit::displacement_at(table, p, d);
      out.u[n][p] = mirrored(Vec3(u.x(), u.y(), 0.0), image[p]);
      out.stress[n][p] = mirrored(stress_3d(res), image[p]);
      out.alpha[n][p] = res.state.alpha;
      if (n == N) out.plastic[p] = res.plastic;
    }
    out.history[p] = mirrored(committed, image[p]);
  }
  return out;
}

} // namespace mf::stages
