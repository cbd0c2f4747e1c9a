#include "meshfree/implicit/solid_lines.hpp"
#include "meshfree/implicit/solid_forms.hpp"

namespace mf::implicit {

SolidLineSampler::SolidLineSampler(const spec::ProblemSpec& spec, const SolidModel& m,
                                   const materials::J2Parameters& law)
    : law_(law) {
  for (const spec::SolidLineSpec& s : spec.solid().lines) {
    Line l;
    l.name = s.name;
    l.from = s.from;
    for (int k = 0; k < s.points; ++k) {
      const Vec3 x = s.from + (s.to - s.from) * (static_cast<double>(k) / (s.points - 1));
      if (m.body.contains(x, 1e-9)) l.x.push_back(x);
    }
    l.table = solid_shapes_at(m, l.x, true);
    l.committed.resize(l.x.size());
    lines_.push_back(std::move(l));
  }
}

void SolidLineSampler::record(int state, const std::vector<double>& d) {
  for (Line& l : lines_)
    for (int k = 0; k < static_cast<int>(l.x.size()); ++k) {
      const materials::J2Result3D r = carry_point(l.table, k, d, law_, l.committed[k]);
      const Vec3 u = solid_displacement_at(l.table, k, d);
      const Vec3& x = l.x[k];
      l.rows.push_back({static_cast<double>(state), (x - l.from).norm(), x.x(), x.y(), x.z(), u.x(),
                        u.y(), u.z(), r.stress(0), r.stress(1), r.stress(2), r.stress(3),
                        r.stress(4), r.stress(5), materials::von_mises_3d(r.stress),
                        r.state.alpha});
    }
}

void SolidLineSampler::write(io::OutputDirectory& out) const {
  for (const Line& l : lines_)
    out.write_csv("line_" + l.name + ".csv",
                  {"increment", "s", "x", "y", "z", "ux", "uy", "uz", "stress_xx", "stress_yy",
                   "stress_zz", "stress_yz", "stress_xz", "stress_xy", "von_mises",
                   "plastic_strain"},
                  l.rows);
}

} // namespace mf::implicit
