#include "meshfree/implicit/solid_lines.hpp"
#include "meshfree/implicit/solid_forms.hpp"
#include "meshfree/materials/j2_plasticity.hpp"

namespace mf::implicit {

SolidLineSampler::SolidLineSampler(const spec::ProblemSpec& spec, const SolidModel& m,
                                   const materials::ConstitutiveModel& law)
    : law_(law) {
  for (const spec::SolidLineSpec& s : spec.solid().lines) {
    Line l;
    l.file = "line_" + s.name;
    l.from = s.from;
    for (int k = 0; k < s.points; ++k) {
      const Vec3 x = s.from + (s.to - s.from) * (static_cast<double>(k) / (s.points - 1));
      if (m.body.contains(x, 1e-9)) l.x.push_back(x);
    }
    add(std::move(l), m);
  }
  for (const spec::SolidFaceSampleSpec& s : spec.solid().faces) {
    Line l;
    l.file = "face_" + s.name;
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
      const materials::StressUpdate3D r = carry_point(l.table, k, d, law_, l.committed[k]);
      const Vec3 u = solid_displacement_at(l.table, k, d);
      const Vec3& x = l.x[k];
      std::vector<double> row{static_cast<double>(state),
                              (x - l.from).norm(),
                              x.x(),
                              x.y(),
                              x.z(),
                              u.x(),
                              u.y(),
                              u.z(),
                              r.stress(0),
                              r.stress(1),
                              r.stress(2),
                              r.stress(3),
                              r.stress(4),
                              r.stress(5),
                              materials::von_mises_3d(r.stress),
                              r.state.alpha};
      if (!l.along) row.erase(row.begin() + 1);
      l.rows.push_back(std::move(row));
    }
}

namespace {

const std::vector<std::string> kColumns{"increment", "s",         "x",         "y",
                                        "z",         "ux",        "uy",        "uz",
                                        "stress_xx", "stress_yy", "stress_zz", "stress_yz",
                                        "stress_xz", "stress_xy", "von_mises", "plastic_strain"};

/// Values `c` of every node, `stride` a node.
std::vector<double> column(const std::vector<double>& values, int stride, int c) {
  std::vector<double> v;
  for (std::size_t i = 0; i + stride <= values.size(); i += stride) v.push_back(values[i + c]);
  return v;
}

/// A face's rows (without s) as a point series for ParaView: one step per state, the
/// displacement as a vector, the stress components, von Mises and the plastic strain as scalars.
void write_point_series(io::OutputDirectory& out, const std::string& stem,
                        const std::vector<Vec3>& x, const std::vector<std::vector<double>>& rows) {
  std::vector<double> xyz;
  for (const Vec3& p : x) xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
  io::FieldSeries series(out, stem, xyz);
  const std::size_t n = x.size();
  for (std::size_t first = 0; n > 0 && first + n <= rows.size(); first += n) {
    io::FieldStep step;
    step.time = rows[first][0];
    std::vector<double> u;
    for (std::size_t k = 0; k < n; ++k)
      u.insert(u.end(), rows[first + k].begin() + 4, rows[first + k].begin() + 7);
    step.vectors3.emplace_back("displacement", std::move(u));
    for (std::size_t c = 7; c < kColumns.size() - 1; ++c) {
      std::vector<double> v;
      for (std::size_t k = 0; k < n; ++k) v.push_back(rows[first + k][c]);
      step.scalars.emplace_back(kColumns[c + 1], std::move(v));
    }
    series.add_step(step);
  }
  series.close();
}

} // namespace

void SolidLineSampler::write(io::OutputDirectory& out) const {
  for (const Line& l : lines_) {
    std::vector<std::string> columns = kColumns;
    if (!l.along) columns.erase(columns.begin() + 1);
    out.write_csv(l.file + ".csv", columns, l.rows);
    if (!l.along) write_point_series(out, l.file, l.x, l.rows);
  }
}

void add_node_stress_fields(io::FieldOutput& fields, const std::vector<double>& values,
                            int stride) {
  // kColumns's stress names, in Voigt order, then von_mises and plastic_strain.
  for (int c = 0; c < 6; ++c)
    fields.scalar(kColumns[8 + c],
                  [&values, stride, c](std::vector<double>& v) { v = column(values, stride, c); });
  fields.scalar("von_mises", [&values, stride](std::vector<double>& v) {
    v.clear();
    for (std::size_t i = 0; i + stride <= values.size(); i += stride)
      v.push_back(materials::von_mises_3d(Eigen::Map<const Vec6>(values.data() + i)));
  });
  if (stride > 6)
    fields.scalar("plastic_strain",
                  [&values, stride](std::vector<double>& v) { v = column(values, stride, 6); });
}

} // namespace mf::implicit
