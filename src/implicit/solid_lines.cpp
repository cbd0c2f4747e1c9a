#include "meshfree/implicit/solid_lines.hpp"
#include "meshfree/implicit/solid_forms.hpp"

namespace mf::implicit {

SolidLineSampler::SolidLineSampler(const spec::ProblemSpec& spec, const SolidModel& m,
                                   const materials::J2Parameters& law)
    : law_(law) {
  for (const spec::SolidLineSpec& s : spec.solid().lines) {
    Line l;
    l.file = "line_" + s.name + ".csv";
    l.from = s.from;
    for (int k = 0; k < s.points; ++k) {
      const Vec3 x = s.from + (s.to - s.from) * (static_cast<double>(k) / (s.points - 1));
      if (m.body.contains(x, 1e-9)) l.x.push_back(x);
    }
    add(std::move(l), m);
  }
  for (const spec::SolidFaceSampleSpec& s : spec.solid().faces) {
    Line l;
    l.file = "face_" + s.name + ".csv";
    l.along = false;
    l.x = s.box ? geometry::plane_sample_points(m.body, s.box->lo, s.box->hi, s.spacing)
                : geometry::face_sample_points(m.body, s.face, s.spacing);
    add(std::move(l), m);
  }
}

void SolidLineSampler::add(Line l, const SolidModel& m) {
  l.table = solid_shapes_at(m, l.x, true);
  l.committed.resize(l.x.size());
  lines_.push_back(std::move(l));
}

void SolidLineSampler::record(int state, const std::vector<double>& d) {
  for (Line& l : lines_)
    for (int k = 0; k < static_cast<int>(l.x.size()); ++k) {
      const materials::J2Result3D r = carry_point(l.table, k, d, law_, l.committed[k]);
      const Vec3 u = solid_displacement_at(l.table, k, d);
      const Vec3& x = l.x[k];
      std::vector<double> row{static_cast<double>(state), (x - l.from).norm(), x.x(), x.y(),
                              x.z(), u.x(), u.y(), u.z(), r.stress(0), r.stress(1), r.stress(2),
                              r.stress(3), r.stress(4), r.stress(5),
                              materials::von_mises_3d(r.stress), r.state.alpha};
      if (!l.along) row.erase(row.begin() + 1);
      l.rows.push_back(std::move(row));
    }
}

void SolidLineSampler::write(io::OutputDirectory& out) const {
  for (const Line& l : lines_) {
    std::vector<std::string> columns{"increment", "s",         "x",         "y",
                                     "z",         "ux",        "uy",        "uz",
                                     "stress_xx", "stress_yy", "stress_zz", "stress_yz",
                                     "stress_xz", "stress_xy", "von_mises", "plastic_strain"};
    if (!l.along) columns.erase(columns.begin() + 1);
    out.write_csv(l.file, columns, l.rows);
  }
}

} // namespace mf::implicit
