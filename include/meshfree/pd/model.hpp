#pragma once
// A bond-based peridynamic body: its particles (particles/particle_set.hpp, positions z = 0 in a
// plane), their bonds in compressed rows, and the bond laws of every pair of materials. Building
// it is done once; the bond state that changes during a run (intact flags, plastic stretches)
// lives in BondState, the motion in the particle set.
#include "meshfree/core/types.hpp"
#include "meshfree/distribution/halo.hpp"
#include "meshfree/materials/pd_bonds.hpp"
#include "meshfree/particles/particle_set.hpp"
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

/// Bonds in compressed rows, each bond stored in both its particles' rows. Per bond: partner,
/// initial length |xi|, weight V_j times the volume and surface corrections, law index.
struct Bonds {
  std::vector<long> offset{0};
  std::vector<int> partner;
  std::vector<double> length;
  std::vector<double> weight;
  std::vector<unsigned char> law;
  long count() const { return static_cast<long>(partner.size()); }
};

/// What changes in a run: intact flags, plastic stretches (micro-plastic laws), and the LAMMPS
/// rule's per-particle critical stretch (the committed value is read, the trial one written by
/// a force evaluation, which then commits it).
struct BondState {
  std::vector<unsigned char> intact;
  std::vector<double> plastic;  // per bond, empty when no law is plastic
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
  std::vector<int> law_of; // law of bonds between materials a and b: law_of[a * materials + b]
  Bonds bonds;
  std::vector<double> weight_sum; // sum of a particle's bond weights at t = 0 (damage)
  /// On a run spread over MPI ranks: the ghosts' copies of other ranks' particles, refreshed
  /// before every force evaluation. Bonds are built for owned particles only.
  distribution::Halo halo;

  bool plane() const { return dimension != materials::PdDimension::Solid3D; }
  bool any_plastic() const;
  bool any_alpha() const;
};

/// law_of[a * materials + b] names the law of bonds between materials a and b (symmetric).
struct LawTable {
  int materials = 0;
  std::vector<materials::BondLaw> laws;
  std::vector<int> law_of;
};

/// Builds the bonds of the owned particles of `m.particles` within m.horizon (a ghost is a
/// partner, never a row) (|xi| <= delta), with the volume correction
/// and the laws of the material pairs; fills bonds, laws and weight_sum.
void build_bonds(Model& m, const LawTable& table, VolumeCorrection correction);

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
