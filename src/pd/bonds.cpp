// Building the bonds of a peridynamic body in place: a cell list of the reference positions, a
// pass that counts each owned particle's bonds, a pass that fills the rows, and the class table
// that the bonds of equal geometry and law share.
#include "class_table.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/pd/forces.hpp"
#include "meshfree/pd/model.hpp"
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <unordered_map>

namespace mf::pd {

using detail::ClassTable;

namespace {

/// Fraction of the cube (square in a plane) of side dx centred at offset xi that lies inside the
/// ball of radius delta, from a uniform sub-grid of the cell.
double cell_fraction_inside(const Eigen::Vector3d& xi, double dx, double delta, bool plane) {
  const int k = plane ? 16 : 8;
  const double h = dx / k, d2 = delta * delta;
  int inside = 0, total = 0;
  for (int c = 0; c < (plane ? 1 : k); ++c)
    for (int b = 0; b < k; ++b)
      for (int a = 0; a < k; ++a) {
        const double x = xi.x() + (a + 0.5) * h - 0.5 * dx;
        const double y = xi.y() + (b + 0.5) * h - 0.5 * dx;
        const double z = plane ? 0.0 : xi.z() + (c + 0.5) * h - 0.5 * dx;
        inside += x * x + y * y + z * z <= d2 ? 1 : 0;
        ++total;
      }
  return static_cast<double>(inside) / total;
}

/// Uniform cell list of the reference positions (Hockney & Eastwood), cells of side `size`.
struct CellList {
  double lo[3] = {0, 0, 0}, size = 1.0;
  long dims[3] = {1, 1, 1};
  std::vector<long> start;
  std::vector<int> sorted;

  CellList(const std::vector<double>& x, double cell) : size(cell) {
    const int n = static_cast<int>(x.size() / 3);
    double hi[3] = {x[0], x[1], x[2]};
    for (int d = 0; d < 3; ++d) lo[d] = x[d];
    for (int i = 0; i < n; ++i)
      for (int d = 0; d < 3; ++d) {
        lo[d] = std::min(lo[d], x[3 * i + d]);
        hi[d] = std::max(hi[d], x[3 * i + d]);
      }
    for (int d = 0; d < 3; ++d)
      dims[d] = std::max(1L, static_cast<long>(std::floor((hi[d] - lo[d]) / size)) + 1);
    const long cells = dims[0] * dims[1] * dims[2];
    MF_REQUIRE(cells < 4L * n + 1000000L, "peridynamics: the particles span ", cells,
               " cells of the horizon; is the horizon far too small?");
    start.assign(cells + 1, 0);
    for (int i = 0; i < n; ++i) ++start[cell_of(&x[3 * i]) + 1];
    for (long c = 0; c < cells; ++c) start[c + 1] += start[c];
    sorted.resize(n);
    std::vector<long> fill(start.begin(), start.end() - 1);
    for (int i = 0; i < n; ++i) sorted[fill[cell_of(&x[3 * i])]++] = i;
  }
  long coord(double v, int d) const {
    return std::min(dims[d] - 1, static_cast<long>(std::floor((v - lo[d]) / size)));
  }
  long cell_of(const double* p) const {
    return (coord(p[2], 2) * dims[1] + coord(p[1], 1)) * dims[0] + coord(p[0], 0);
  }
  /// Calls f(j) for every point in the cells around point p.
  template <class F> void around(const double* p, F&& f) const {
    const long c0 = coord(p[0], 0), c1 = coord(p[1], 1), c2 = coord(p[2], 2);
    for (long cz = std::max(0L, c2 - 1); cz <= std::min(dims[2] - 1, c2 + 1); ++cz)
      for (long cy = std::max(0L, c1 - 1); cy <= std::min(dims[1] - 1, c1 + 1); ++cy)
        for (long cx = std::max(0L, c0 - 1); cx <= std::min(dims[0] - 1, c0 + 1); ++cx) {
          const long c = (cz * dims[1] + cy) * dims[0] + cx;
          for (long k = start[c]; k < start[c + 1]; ++k) f(sorted[k]);
        }
  }
  double bytes() const { return 8.0 * start.size() + 4.0 * sorted.size(); }
};

} // namespace

void ClassIndices::resize(long n) {
  wide_.clear();
  wide_.shrink_to_fit();
  narrow_.assign(n, 0);
}

void ClassIndices::widen() {
  wide_.assign(narrow_.begin(), narrow_.end());
  narrow_.clear();
  narrow_.shrink_to_fit();
}

double Bonds::bytes(int plastic_per_bond) const {
  const double s = static_cast<double>(stored());
  return 8.0 * offset.size() + (4.0 + cls.bytes_per_bond() + 1.0 + 8.0 * plastic_per_bond) * s +
         static_cast<double>(sizeof(BondClass)) * classes.size();
}

void fold_laws(std::vector<BondClass>& classes, const std::vector<materials::BondLaw>& laws) {
  const double inf = std::numeric_limits<double>::infinity();
  for (BondClass& c : classes) {
    const materials::BondLaw& law = laws[c.law];
    c.cw = law.c * c.weight;
    c.cw_partner = law.c * c.weight_partner;
    c.limit = law.breaks() ? law.critical_stretch : inf;
    c.alpha_floor = law.breaks() ? -inf : inf;
    c.s00 = law.critical_stretch;
    c.alpha = law.alpha;
    c.yield = law.plastic() ? law.yield_stretch : inf;
  }
}

void fold_laws(Model& m) {
  fold_laws(m.bonds.classes, m.laws);
  m.bonds.folded = m.laws;
}

double bond_reach(const Model& m, VolumeCorrection correction) {
  // Exact partial volumes reach neighbours whose cells only touch the horizon.
  return correction == VolumeCorrection::Exact
             ? m.horizon + 0.5 * m.spacing * std::sqrt(m.plane() ? 2.0 : 3.0)
             : m.horizon;
}

namespace {

/// A bond's reference length and partial-volume factor beta.
struct Geometry {
  double length, beta;
};

/// A bond's length is |X_j - X_i| evaluated as the force loop evaluates |y_j - y_i|, so that
/// the reference configuration is free of force to the last bit; on a lattice the lengths of
/// an offset then differ only by the round-off of the positions, and the classes stay few. The
/// exact partial volume depends only on the offset in spacings there: computed once per offset.
class PartialVolumes {
public:
  PartialVolumes(const Model& m, VolumeCorrection correction)
      : p_(m.particles), horizon_(m.horizon), dx_(m.spacing), r_(0.5 * m.spacing),
        plane_(m.plane()), inner_(m.horizon - r_ * std::sqrt(plane_ ? 2.0 : 3.0)),
        correction_(correction) {}

  Geometry operator()(int i, int j) {
    const double ex = p_.X[3 * j] - p_.X[3 * i], ey = p_.X[3 * j + 1] - p_.X[3 * i + 1],
                 ez = p_.X[3 * j + 2] - p_.X[3 * i + 2];
    const double xi = std::sqrt(ex * ex + ey * ey + ez * ez);
    double beta = 1.0;
    if (correction_ == VolumeCorrection::Linear && xi > horizon_ - r_) {
      beta = (horizon_ + r_ - xi) / (2.0 * r_);
    } else if (correction_ == VolumeCorrection::Exact && xi > inner_) {
      const Eigen::Vector3d d(ex, ey, ez);
      const Eigen::Vector3d spacings = d / dx_;
      const Eigen::Vector3d rounded = spacings.array().round();
      if ((spacings - rounded).cwiseAbs().maxCoeff() > 1e-6)
        return Geometry{xi, cell_fraction_inside(d, dx_, horizon_, plane_)};
      const long long key = ((static_cast<long long>(rounded.x()) + 1000) * 2001 +
                             (static_cast<long long>(rounded.y()) + 1000)) *
                                2001 +
                            (static_cast<long long>(rounded.z()) + 1000);
      const auto it = fraction_of_offset_.find(key);
      if (it != fraction_of_offset_.end()) return Geometry{xi, it->second};
      beta = cell_fraction_inside(d, dx_, horizon_, plane_);
      fraction_of_offset_.emplace(key, beta);
    }
    return Geometry{xi, beta};
  }

private:
  const particles::ParticleSet& p_;
  double horizon_, dx_, r_;
  bool plane_;
  double inner_;
  VolumeCorrection correction_;
  std::unordered_map<long long, double> fraction_of_offset_;
};

/// The bonds a row stores: the partners within reach with a nonzero partial volume (Half: a
/// pair in the row of its smaller index).
class BondRows {
public:
  BondRows(const Model& m, const CellList& cells, double reach, bool half, PartialVolumes& geometry)
      : p_(m.particles), cells_(cells), reach2_(reach * reach), half_(half), geometry_(geometry) {}

  /// Calls f(j, geometry) for every bond of owned particle i that its row stores.
  template <class F> void each(int i, F&& f) const {
    cells_.around(&p_.X[3 * i], [&](int j) {
      if (j == i || (half_ && j < i)) return;
      const double ex = p_.X[3 * j] - p_.X[3 * i], ey = p_.X[3 * j + 1] - p_.X[3 * i + 1],
                   ez = p_.X[3 * j + 2] - p_.X[3 * i + 2];
      if (ex * ex + ey * ey + ez * ez > reach2_) return;
      const Geometry g = geometry_(i, j);
      if (g.beta > 0.0) f(j, g);
    });
  }

private:
  const particles::ParticleSet& p_;
  const CellList& cells_;
  double reach2_;
  bool half_;
  PartialVolumes& geometry_;
};

/// Counting pass: the row offsets.
void count_rows(const BondRows& rows, int owned, Bonds& b) {
  b.offset.assign(owned + 1, 0);
  for (int i = 0; i < owned; ++i) {
    long count = 0;
    rows.each(i, [&](int, const Geometry&) { ++count; });
    b.offset[i + 1] = b.offset[i] + count;
  }
}

/// Filling pass: partners and classes, each row sorted (Half: by partner index, Full: by the
/// partner's global id). Returns the capacity of the row buffer, for the peak memory.
std::size_t fill_rows(const BondRows& rows, const particles::ParticleSet& p, const LawTable& table,
                      bool half, Bonds& b) {
  const int owned = p.owned_count();
  b.partner.resize(b.offset[owned]);
  b.cls.resize(b.offset[owned]);
  ClassTable classes(b.classes);
  std::vector<std::pair<int, std::uint32_t>> entries;
  const auto law_of = [&](int i, int j) {
    return table.law_of[p.material[i] * table.materials + p.material[j]];
  };
  for (int i = 0; i < owned; ++i) {
    entries.clear();
    rows.each(i, [&](int j, const Geometry& g) {
      const std::uint32_t c =
          classes.find(law_of(i, j), g.length, p.volume[j] * g.beta, p.volume[i] * g.beta);
      entries.emplace_back(j, c);
    });
    if (half) {
      std::sort(entries.begin(), entries.end());
    } else {
      std::sort(entries.begin(), entries.end(), [&](const auto& a, const auto& c) {
        return p.id[a.first] != p.id[c.first] ? p.id[a.first] < p.id[c.first] : a.first < c.first;
      });
    }
    long k = b.offset[i];
    for (const auto& [j, c] : entries) b.partner[k] = static_cast<int>(j), b.cls.set(k++, c);
  }
  return entries.capacity();
}

/// Directed bonds: a Half pair of two owned particles counts at both ends.
long directed_bonds(const Bonds& b, int owned, bool half) {
  long directed = 0;
  for (int i = 0; i < owned; ++i)
    for (long k = b.offset[i]; k < b.offset[i + 1]; ++k)
      directed += half && b.partner[k] < owned ? 2 : 1;
  return directed;
}

} // namespace

void build_bonds(Model& m, const LawTable& table, VolumeCorrection correction) {
  MF_REQUIRE(m.horizon > 0.0 && m.spacing > 0.0, "peridynamics: horizon and spacing must be set");
  MF_REQUIRE(!table.laws.empty() && table.laws.size() < 256, "peridynamics: 1 to 255 bond laws");
  const particles::ParticleSet& p = m.particles;
  const bool half = !m.deterministic;
  const double reach = bond_reach(m, correction);
  const int owned = p.owned_count();
  m.laws = table.laws;
  m.law_of = table.law_of;
  Bonds b;
  b.layout = half ? BondLayout::Half : BondLayout::Full;
  if (p.size() == 0) {
    m.bonds = std::move(b);
    m.weight_sum.clear();
    return;
  }
  const CellList cells(p.X, reach);
  PartialVolumes geometry(m, correction);
  const BondRows rows(m, cells, reach, half, geometry);
  count_rows(rows, owned, b);
  const std::size_t entries = fill_rows(rows, p, table, half, b);
  b.directed = directed_bonds(b, owned, half);
  b.peak_bytes = b.bytes(0) - 1.0 * b.stored() + cells.bytes() +
                 8.0 * static_cast<double>(entries) + 48.0 * b.classes.size();
  m.bonds = std::move(b);
  fold_laws(m);
  m.weight_sum.assign(p.size(), 0.0);
  for_each_directed_bond(
      m, [&](int i, int, long, double w, const BondClass&) { m.weight_sum[i] += w; });
}

void apply_surface_correction(Model& m) {
  const particles::ParticleSet& p = m.particles;
  const int n = p.size();
  const int dims = m.plane() ? 2 : 3;
  const int materials = static_cast<int>(m.material_names.size());
  // Strain energy density of a uniaxial strain eps along an axis in the continuum limit of a
  // full horizon, from the bond law itself (small strain, s = eps cos^2):
  //   3D:  W = pi c delta^4 eps^2 / 20,   2D:  W = pi c t delta^3 eps^2 / 16,
  // which is (lambda + 2 mu) eps^2 / 2 with the calibration of c (E / (1 - nu^2) in plane stress).
  const double eps = 1e-3;
  const auto classical = [&](int material) {
    const double c = m.laws[m.law_of[material * materials + material]].c;
    return m.plane() ? M_PI * c * m.thickness * std::pow(m.horizon, 3) * eps * eps / 16.0
                     : M_PI * c * std::pow(m.horizon, 4) * eps * eps / 20.0;
  };
  // The factors are those of the elastic bonds: the laws without breaking and plasticity.
  const std::vector<materials::BondLaw> laws = m.laws;
  for (auto& law : m.laws) law.critical_stretch = 0.0, law.yield_stretch = 0.0, law.alpha = 0.0;
  fold_laws(m);
  BondState intact;
  intact.intact.assign(m.bonds.stored(), 1);
  std::vector<std::vector<double>> factor(dims, std::vector<double>(n, 1.0));
  for (int d = 0; d < dims; ++d) {
    std::vector<double> y = p.X, f, w;
    for (int i = 0; i < n; ++i) y[3 * i + d] *= 1.0 + eps;
    bond_forces(m, intact, y, f, true, &w);
    for (int i = 0; i < n; ++i)
      if (w[i] > 0.0) factor[d][i] = classical(p.material[i]) / w[i];
    m.halo.exchange(factor[d]); // a bond to a ghost takes its owner's factor
  }
  m.laws = laws;
  // Each bond takes the mean factor of its ends along each axis, combined by its direction
  // (Madenci & Oterkus 2014, eq. 4.12). The factor is symmetric in the two ends, so a stored
  // bond scales both of its weights. Bonds of different factors get different classes.
  Bonds& b = m.bonds;
  const std::vector<BondClass> before = std::move(b.classes);
  b.classes.clear();
  ClassTable classes(b.classes);
  for (int i = 0; i < p.owned_count(); ++i)
    for (long k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const int j = b.partner[k];
      const BondClass& c = before[b.cls[k]];
      const Eigen::Vector3d e = (p.reference(j) - p.reference(i)) / c.length;
      double sum = 0.0;
      for (int d = 0; d < dims; ++d) {
        const double g = 0.5 * (factor[d][i] + factor[d][j]);
        sum += e(d) * e(d) / (g * g);
      }
      const double root = std::sqrt(sum);
      BondClass scaled = c;
      scaled.weight /= root, scaled.weight_partner /= root;
      b.cls.set(k, classes.find(scaled));
    }
  fold_laws(m);
  m.weight_sum.assign(n, 0.0);
  for_each_directed_bond(
      m, [&](int i, int, long, double w, const BondClass&) { m.weight_sum[i] += w; });
}

} // namespace mf::pd
