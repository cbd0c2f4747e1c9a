// The steps of an explicit stage that do not depend on its particles' kind
// (stages/explicit_stage.hpp).
#include "meshfree/stages/explicit_stage.hpp"
#include "meshfree/core/error.hpp"
#include <algorithm>
#include <limits>

namespace mf::stages {

io::History take_rows(io::History& h) {
  io::History rows = std::move(h);
  h = io::History(rows.columns());
  return rows;
}

io::History staged_history(const io::History& preload, const io::History& run, int from, int index,
                           const std::vector<std::string>& gauges) {
  std::vector<std::string> columns = run.columns();
  columns.insert(columns.begin() + 1, "stage");
  io::History out(columns);
  const auto is_gauge = [&gauges](const std::string& c) {
    for (const auto& g : gauges)
      if (c.rfind(g + "_", 0) == 0) return true;
    return false;
  };
  std::vector<char> keep(run.columns().size());
  for (std::size_t c = 0; c < keep.size(); ++c) keep[c] = c == 0 || is_gauge(run.columns()[c]);
  for (const auto& row : preload.rows()) {
    std::vector<double> r{row[0], static_cast<double>(from)};
    for (std::size_t c = 1; c < row.size(); ++c)
      r.push_back(keep[c] ? row[c] : std::numeric_limits<double>::quiet_NaN());
    out.append_with_gaps(std::move(r));
  }
  for (const auto& row : run.rows()) {
    std::vector<double> r = row;
    r.insert(r.begin() + 1, static_cast<double>(index));
    out.append(std::move(r));
  }
  return out;
}

void begin_stage_history(ExplicitStage& st, const io::History& replay, io::History& run,
                         const std::vector<spec::GaugeSpec>& gauges, int from, int index) {
  std::vector<std::string> names;
  for (const auto& g : gauges) names.push_back(g.name);
  st.history = staged_history(replay, run, from, index, names);
  io::History* staged = &st.history;
  run.also_to([staged, index](const std::vector<double>& row) {
    std::vector<double> r = row;
    r.insert(r.begin() + 1, static_cast<double>(index));
    staged->append(std::move(r));
  });
}

void record_stage(ExplicitStage& st, const std::string& status, const std::string& stop_reason,
                  const PhaseTimer& timer) {
  st.status = status;
  st.stop_reason = stop_reason;
  st.timer = timer;
}

double stored_energy(const Preload& preload, const PreloadAtParticles& pa,
                     const std::vector<double>& volume) {
  // sigma : C^-1 sigma = [(s11^2 + s22^2 + s33^2) - 2 nu (s11 s22 + s22 s33 + s33 s11)
  //                       + 2 (1 + nu) (s23^2 + s13^2 + s12^2)] / E  (isotropic compliance).
  double w = 0.0;
  for (std::size_t i = 0; i < pa.image.size(); ++i) {
    const materials::IsotropicElastic law = preload.elasticity_at(pa.image[i].x);
    const double nu = law.nu;
    const materials::Vec6& s = pa.final_stress()[i];
    const double normal = s[0] * s[0] + s[1] * s[1] + s[2] * s[2] -
                          2.0 * nu * (s[0] * s[1] + s[1] * s[2] + s[2] * s[0]);
    const double shear = 2.0 * (1.0 + nu) * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]);
    w += 0.5 * volume[i] * (normal + shear) / law.E;
  }
  return w;
}

std::vector<Vec3> reference_positions(const particles::ParticleSet& P, int n) {
  std::vector<Vec3> X(n);
  for (int i = 0; i < n; ++i) X[i] = P.reference(i);
  return X;
}

void describe_preload(TransferReport& t, const Preload& preload, const PreloadAtParticles& pa,
                      const std::vector<double>& volume) {
  const int n = static_cast<int>(pa.final_u().size());
  t.particles = n;
  for (int i = 0; i < n; ++i) {
    t.plastic_particles += pa.plastic[i];
    t.max_u = std::max(t.max_u, pa.final_u()[i].norm());
  }
  t.stored_energy = stored_energy(preload, pa, volume);
}

std::string vector_text(const Vec3& v, const Preload& preload) {
  return preload.dimension() == 2 ? detail::concat("(", v.x(), ", ", v.y(), ")")
                                  : detail::concat("(", v.x(), ", ", v.y(), ", ", v.z(), ")");
}

} // namespace mf::stages
