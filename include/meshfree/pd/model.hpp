#pragma once
// A peridynamic body, bond-based or state-based (LPS): its particles (particles/particle_set.hpp,
// positions z = 0 in a plane), their bonds in compressed rows, and the bond laws of every pair of
// materials. Building it is done once; the bond state that changes during a run (intact flags,
// plastic stretches) lives in BondState, the motion in the particle set.
#include "meshfree/core/types.hpp"
#include "meshfree/distribution/halo.hpp"
#include "meshfree/materials/pd_bonds.hpp"
#include "meshfree/materials/pd_state.hpp"
#include "meshfree/particles/particle_set.hpp"
#include <cstdint>
#include <string>
#include <vector>

namespace mf::pd {

/// How much of a neighbour's volume a bond counts when the neighbour's cell is cut by the
/// horizon:
///  - None: all of it, for neighbours with |xi| <= delta;
///  - Linear: factor (delta + r - xi) / (2 r) for delta - r < xi <= delta, r = dx / 2, and none
///    beyond delta (Madenci & Oterkus 2014, sec. 2.5.1; LAMMPS peri's vfrac_scale);
///  - Exact: the fraction of the neighbour's cell (a square or cube of side dx centred on it)
///    that lies inside the horizon ball, neighbours up to delta + r sqrt(dim) included (the
///    "partial area, analytical calculation" quadrature of Seleson 2014, evaluated on a 16^2 or
///    8^3 sub-grid of the cell). With delta = 3 dx the interior stiffness of a uniform lattice is
///    then 2.2% above the continuum value, against 13% below with Linear and 5% above with None
///    (plane stress, uniaxial strain; it falls to 0.7% at delta = 5 dx).
enum class VolumeCorrection { None, Linear, Exact };

/// What a bond's force needs besides its partner, shared by every bond with the same geometry,
/// weights and law (on a lattice: bonds of the same offset), so that a bond stores a partner and a
/// class index. Classes are deduplicated by exact equality of (law, length, weight,
/// weight_partner and the position-aware factors); the folded constants follow from those and
/// the law (fold_laws).
struct BondClass {
  // The four the force loop reads for every bond first, side by side (pd/bond_rows.cpp).
  double length = 0.0;               // |xi|
  double inv_length = 0.0;           // 1 / |xi|
  double cw = 0.0, cw_partner = 0.0; // folded from the law: c w_ij, c w_ji
  int law = 0;
  double weight = 0.0;         // w_ij = V_j times the volume and surface corrections
  double weight_partner = 0.0; // w_ji = V_i times the same corrections
  // Folded from the law:
  double limit = 0.0;       // critical stretch; +inf where the law never breaks
  double alpha_floor = 0.0; // LAMMPS rule: the limit is max(min(s0_i, s0_j), alpha_floor)
  double s00 = 0.0;         // LAMMPS rule: s0 candidate s00 - alpha s
  double alpha = 0.0;
  double yield = 0.0; // micro-plastic yield stretch; +inf for an elastic law
  // A state-based body's position-aware influence (pd/state_surface.hpp) over the LPS's, 1
  // without it: the dilatation's and the deviatoric part's, of the row particle and the partner.
  double dil = 1.0, dil_partner = 1.0, dev = 1.0, dev_partner = 1.0;
};

/// How the bonds of the owned particles are stored (both in compressed rows, one row per owned
/// particle):
///  - Half: each pair once, in the row of its particle of smaller index (an owned-ghost pair in
///    the owned particle's row); the force loop applies Newton's third law. Rows sorted by
///    partner index.
///  - Full: each bond in the rows of both its owned particles, rows sorted by the partner's
///    global id; each particle sums its own row in that order, so that its force does not depend
///    on the thread count or on which rank holds which particle.
enum class BondLayout { Half, Full };

/// The class of each stored bond, read as `cls[k]`: two bytes a bond while the classes number at
/// most 65,536 (a lattice's bonds fall into tens to hundreds), four beyond (the per-pair factors
/// of a surface correction can make more). The narrow index is a quarter of a bond's steady
/// memory. The force rows are compiled for each width (pd/bond_rows); other loops read through
/// this view, whose test of the width is the same for every bond.
struct ClassView {
  const std::uint16_t* narrow = nullptr;
  const std::uint32_t* wide = nullptr;
  std::uint32_t operator[](long k) const { return narrow ? narrow[k] : wide[k]; }
};

/// The class indices of the stored bonds: narrow until a class past 65,535 is set, then wide.
class ClassIndices {
public:
  /// n bonds of class 0, narrow.
  void resize(long n);
  std::uint32_t operator[](long k) const { return wide_.empty() ? narrow_[k] : wide_[k]; }
  void set(long k, std::uint32_t c) {
    if (wide_.empty() && c > kNarrowLast) widen();
    if (wide_.empty())
      narrow_[k] = static_cast<std::uint16_t>(c);
    else
      wide_[k] = c;
  }
  int bytes_per_bond() const { return wide_.empty() ? 2 : 4; }
  ClassView view() const {
    return wide_.empty() ? ClassView{narrow_.data(), nullptr} : ClassView{nullptr, wide_.data()};
  }

private:
  static constexpr std::uint32_t kNarrowLast = 0xFFFF;
  void widen();
  std::vector<std::uint16_t> narrow_;
  std::vector<std::uint32_t> wide_;
};

struct Bonds {
  BondLayout layout = BondLayout::Half;
  std::vector<long> offset{0};
  std::vector<int> partner;
  ClassIndices cls; // index into classes
  std::vector<BondClass> classes;
  std::vector<materials::BondLaw> folded; // the laws the classes were folded from
  long directed = 0;       // directed bonds: a pair of owned particles counts 2, owned-ghost 1
  double peak_bytes = 0.0; // the most memory building them held (bond arrays and scratch)

  long stored() const { return static_cast<long>(partner.size()); }
  long pairs() const { return layout == BondLayout::Half ? stored() : directed / 2; }
  /// Bytes held in steady state: rows, partners, classes, the intact flags and the plastic state
  /// of BondState (`plastic_per_bond` doubles a stored bond: 1 for micro-plastic laws, 2 for
  /// EPS).
  double bytes(int plastic_per_bond) const;
};

/// What changes in a run: intact flags and plastic stretches (one per stored bond; the plastic
/// ones only with a micro-plastic law), and the LAMMPS rule's per-particle critical stretch (the
/// committed value is read, the trial one written by a force evaluation, which then commits it).
struct BondState {
  std::vector<unsigned char> intact;
  std::vector<double> plastic;  // per stored bond, empty when no law is plastic
  particles::Staged<double> s0; // per particle, empty when no law uses alpha
};

struct Model {
  materials::PdDimension dimension = materials::PdDimension::Solid3D;
  double thickness = 1.0; // 2D only
  double spacing = 0.0;   // particle spacing dx
  double horizon = 0.0;   // delta
  particles::ParticleSet particles;
  std::vector<std::string> material_names;
  std::vector<materials::BondLaw> laws;
  std::vector<int> law_of;    // law of bonds between materials a and b: law_of[a * materials + b]
  bool deterministic = false; // Full bond layout (see BondLayout) instead of Half
  Bonds bonds;
  std::vector<double> weight_sum; // sum of a particle's bond weights at t = 0 (damage)
  /// A state-based body (LPS, pd/state_based.hpp): one law per material, empty for a bond-based
  /// body; the influence function; the weighted volume m_i of every particle, owned and ghosts
  /// (pd::set_weighted_volumes). The bond laws then give the critical stretches and the contact
  /// micromodulus only.
  std::vector<materials::LpsLaw> lps;
  materials::Influence influence = materials::Influence::InverseLength;
  std::vector<double> weighted_volume;
  std::vector<double> yield_value; // EPS: psi0 of every particle (materials::eps_yield_value)
  bool position_aware = false;     // the classes carry pd/state_surface.hpp's factors
  /// On a run spread over MPI ranks: the ghosts' copies of other ranks' particles, refreshed
  /// before every force evaluation. Bonds are built for owned particles only.
  distribution::Halo halo;

  bool plane() const { return dimension != materials::PdDimension::Solid3D; }
  bool state_based() const { return !lps.empty(); }
  /// Whether a state-based body has elastic-plastic (EPS) materials.
  bool state_plastic() const;
  bool any_plastic() const;
  bool any_alpha() const;
};

/// law_of[a * materials + b] names the law of bonds between materials a and b (symmetric).
struct LawTable {
  int materials = 0;
  std::vector<materials::BondLaw> laws;
  std::vector<int> law_of;
};

/// Builds the bonds of the owned particles of `m.particles` (partners may be ghosts) within
/// m.horizon (|xi| <= delta), with the volume correction and the laws of the material pairs, in
/// the layout m.deterministic asks for; fills bonds, laws and weight_sum. The rows are built in
/// place (a counting pass, then a filling pass over a cell list), so that building holds no
/// more than the bonds themselves and per-particle scratch.
void build_bonds(Model& m, const LawTable& table, VolumeCorrection correction);

/// The farthest a bond reaches: the horizon, or with exact partial volumes the horizon plus half
/// a cell diagonal (neighbours whose cells only touch the horizon ball).
double bond_reach(const Model& m, VolumeCorrection correction);

/// Folds m.laws into the bond classes. Call it after changing m.laws: bond_forces otherwise
/// folds the changed laws into a copy of the classes at every call.
void fold_laws(Model& m);
void fold_laws(std::vector<BondClass>& classes, const std::vector<materials::BondLaw>& laws);

/// Calls f(i, j, k, w, c) for every directed bond i -> j of an owned particle i: k its stored
/// index, w its weight seen from i (w_ij), c its class. In the Half layout a pair of owned
/// particles is visited from both ends (the second time with w = c.weight_partner). Serial.
template <class F> void for_each_directed_bond(const Model& m, F&& f) {
  const Bonds& b = m.bonds;
  const int owned = m.particles.owned_count();
  const bool half = b.layout == BondLayout::Half;
  for (int i = 0; i < owned; ++i)
    for (long k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const int j = b.partner[k];
      const BondClass& c = b.classes[b.cls[k]];
      f(i, j, k, c.weight, c);
      if (half && j < owned) f(j, i, k, c.weight_partner, c);
    }
}

/// A crack present at t = 0: the bonds whose segment crosses it are broken. In a plane the crack
/// is a segment from a to b; in 3D it is the parallelogram a + s (b - a) + t (c - a), s, t in [0,
/// 1].
struct PreCrack {
  Eigen::Vector3d a{0, 0, 0}, b{0, 0, 0}, c{0, 0, 0};
};

/// A fresh state with every bond intact (and `cracks` cut), zero plastic stretch, and the
/// LAMMPS rule's s0 at s00.
BondState initial_state(const Model& m, const std::vector<PreCrack>& cracks);

/// Surface correction (Madenci & Oterkus 2014, sec. 4.2, energy method): each particle's strain
/// energy density under a uniform stretch along each axis is compared with the classical value,
/// and every bond's weight is scaled by the resulting direction-weighted factor of its two
/// particles. Changes m.bonds.weight and weight_sum.
void apply_surface_correction(Model& m);

/// Damage phi_i = 1 - (sum of intact bond weights) / (sum of all) (paper 000 eq. 8, with the
/// volume each bond counts).
void damage(const Model& m, const BondState& s, std::vector<double>& phi);

/// Silling & Askari (2005, eq. 26) stable time step of velocity Verlet:
/// dt_i = sqrt(2 rho_i / sum_j c_ij w_ij / |xi_ij|); returns the smallest and its particle.
double stable_time_step(const Model& m, int* limiting_particle = nullptr);

} // namespace mf::pd
