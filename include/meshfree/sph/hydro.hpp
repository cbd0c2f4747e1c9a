#pragma once
// Smoothed-particle hydrodynamics of compressible media in 1, 2 or 3 dimensions (the thesis'
// chapter 3, after Monaghan 1992 and Liu & Liu 2003): continuity-equation density (eq. 3-41),
// the symmetric momentum and energy equations (eqs. 3-48 and 3-64) with Monaghan's artificial
// viscosity (alpha = beta = 1, phi = 0.1 h), smoothing lengths that follow the density, a
// midpoint predictor-corrector step under the CFL bound, equations of state per material,
// programmed burn of explosives (lighting time = distance / D_CJ) or a ZND front lit by its own
// shock, solid strength, symmetry planes (mirror particles), transmitting boundaries, and the
// optional kernel-gradient correction and artificial stress.
#include "meshfree/kernels/sph_kernel.hpp"
#include "meshfree/loads/blast.hpp"
#include "meshfree/materials/eos.hpp"
#include "meshfree/materials/geomaterials.hpp"
#include "meshfree/materials/j2_plasticity.hpp"
#include "meshfree/neighbors/pair_list.hpp"
#include <string>
#include <vector>

namespace mf::sph {

/// A material's equation of state; the kind selects which member is used. Compaction and HJC
/// depend on the largest density a particle has reached (its rho_max).
struct Eos {
  enum class Kind { IdealGas, Jwl, MieGruneisen, LinearPolynomial, Compaction, Hjc };
  Kind kind = Kind::IdealGas;
  materials::IdealGas ideal_gas;
  materials::Jwl jwl;
  materials::MieGruneisen mie_gruneisen;
  materials::LinearPolynomial linear_polynomial;
  materials::Compaction compaction;
  /// Optional for JWL: the unreacted explosive (Mie-Grueneisen on the JWL's rho0). It carries
  /// the pressure share 1 - F of the burn fraction F, particles light when the shock has
  /// compressed them (Settings::ignition_compression) and burn over burn_width h / D_CJ, so the
  /// front is a ZND wave whose speed and CJ state follow from the equations of state.
  bool has_unreacted = false;
  materials::MieGruneisen unreacted;
};

/// Strength of a solid: the deviatoric stress S follows the Jaumann rate
/// dS/dt = 2 G (D - tr(D) I / 3) + W S - S W (D, W: symmetric and skew parts of grad v) and is
/// returned radially to the yield surface of its model after each update:
///  - VonMises: the shared J2 layer (materials/j2_plasticity) with its hardening;
///  - Granular: a pressure-dependent yield Y(p) and a shear modulus G(rho) (soil);
///  - Hjc: the Holmquist-Johnson-Cook surface with damage (concrete).
/// The pressure comes from the equation of state. A particle fails when its plastic strain
/// reaches failure_strain (> 0) or its HJC damage reaches 1: it then carries no deviatoric
/// stress and no tension (it flows as a crushed, cohesionless material).
struct Strength {
  enum class Model { Elastic, VonMises, Granular, Hjc };
  bool enabled = false;
  Model model = Model::Elastic;
  double shear_modulus = 0.0;    // G; a granular G(rho) table, when given, is used instead
  materials::J2Parameters yield; // sigma0 and hardening; E = 2G and nu = 0 give mu = G
  materials::GranularStrength granular;
  double failure_strain = 0.0; // 0: no failure by plastic strain
  bool plastic() const { return model != Model::Elastic; }
};

struct Material {
  std::string name;
  Eos eos;
  Strength strength;
  materials::Hjc hjc; // the HJC equation of state and strength share one parameter set
};

/// Pressure and squared sound speed of a particle of material m.
materials::PressureAndSound evaluate(const Material& m, double rho, double e, double rho_max,
                                     double damage);

/// The shear modulus of material m at density rho.
double shear_modulus(const Material& m, double rho);

/// The current yield stress of a particle (0 for a material without plasticity).
double current_yield(const Material& m, double pressure, double alpha, double damage,
                     double strain_rate);

/// Particle arrays (structure of arrays; vectors have 3 components per particle, the unused ones
/// zero in 1D and 2D).
struct Particles {
  int dim = 3;
  std::vector<double> x, v;
  std::vector<double> mass, rho, e, h;
  std::vector<double> rho_ref, h_ref; // h = h_ref (rho_ref / rho)^(1/dim)
  std::vector<int> material;
  std::vector<double> light_time; // programmed burn: when the particle is lit (< 0: never burns)
  /// Fixed (wall) particles: they do not move, but their density and energy evolve, so that they
  /// push back on approaching particles (dynamic boundary particles, Crespo et al. 2007).
  std::vector<char> fixed;
  std::vector<double> p, c;        // from the equation of state, per step
  std::vector<double> S;           // deviatoric stress, 6 per particle: xx yy zz yz xz xy
  std::vector<double> alpha;       // equivalent plastic strain
  std::vector<double> rho_max;     // largest density reached (compaction history)
  std::vector<double> damage;      // HJC damage, 0..1
  std::vector<double> strain_rate; // equivalent deviatoric strain rate sqrt(2/3 D':D') [1/s]
  std::vector<char> failed;        // no deviatoric stress and no tension once set
  int size() const { return static_cast<int>(mass.size()); }
  /// Appends a copy of particle i (a mirror image starts as one).
  void append_copy(int i);
  /// Drops every particle from index n on.
  void truncate(int n);
  /// Appends a particle at rest.
  void add(const double position[3], double mass, double rho, double e, double h, int material,
           bool fixed = false);
};

struct Settings {
  kernels::SphKernel kernel = kernels::SphKernel::CubicSpline;
  double alpha = 1.0, beta = 1.0;    // Monaghan artificial viscosity
  double phi = 0.1;                  // singularity guard of the viscosity, times h
  double courant = 0.3;              // dt = courant * min h / (c + |v|)
  double skin = 0.5;                 // neighbour-list margin: pairs within (h_i + h_j)(1 + skin)
  double burn_width = 2.0;           // programmed burn: the burn fraction rises over this many h
  bool gradient_correction = false;  // kernel-gradient correction (Bonet & Lok 1999)
  double ignition_compression = 0.1; // rho / rho0 - 1 that lights an explosive with an
                                     // unreacted equation of state
  /// Artificial stress against the tensile instability of solids (Monaghan 2000; Gray,
  /// Monaghan & Swift 2001): each particle's tensile principal stresses give
  /// R = -epsilon sigma_tensile / rho^2, and a pair adds f^n (R_i + R_j) to its stress term with
  /// f = W(r) / W(initial spacing). epsilon = 0 switches it off; Gray et al. use 0.3 and n = 4.
  double artificial_stress = 0.0;
  int artificial_stress_exponent = 4;
  /// Inter-material penalty force (the thesis' eqs. 3-29 and 3-30, after Liu et al. 2003):
  /// particles of different materials closer than r0 = distance x their mean initial spacing
  /// repel with F = pressure a^(dim-1) [(r0/r)^n1 - (r0/r)^n2] along the line of centres,
  /// a = the mean spacing. The thesis activates it at (h_i + h_j) / (2 r) >= 1; with
  /// h = 1.5 spacing that would push nearest neighbours apart at rest, so r0 is taken from the
  /// spacing instead. pressure = 0 switches it off.
  struct Penalty {
    double pressure = 0.0;
    int n1 = 12, n2 = 6;
    double distance = 1.0;
  } penalty;
};

struct Rates {
  std::vector<double> dv, drho, de, dS;
  std::vector<double> grad_v;     // 9 per particle (solids): L_ab = d v_a / d x_b
  std::vector<double> correction; // 9 per particle: the kernel-gradient correction matrix
  std::vector<double> art_stress; // 6 per particle: the artificial stress R (Voigt, like S)
  std::vector<double> spacing;    // initial spacing per particle (artificial stress, penalty)
};

/// A pressure history on a surface layer of particles (an empirical blast load): particle k of
/// the layer takes the force pulses[k](t) area[k] along `direction` (the inward normal).
struct SurfaceLoad {
  std::string name;
  std::vector<int> particles;
  std::vector<double> area;
  std::vector<loads::Friedlander> pulses;
  double direction[3] = {0.0, 0.0, 0.0};
};

/// A transmitting (non-reflecting) boundary on a surface layer: Lysmer & Kuhlemeyer (1969)
/// dashpots, a traction -rho c_p (v.n) n - rho c_s (v - (v.n) n) on each particle's face area,
/// which absorbs plane waves arriving along the normal.
struct TransmittingBoundary {
  std::string name;
  std::vector<int> particles;
  std::vector<double> area, normal_impedance, shear_impedance; // A, rho c_p, rho c_s per particle
  double normal[3] = {0.0, 0.0, 0.0};                          // unit, outward
};

/// A symmetry plane x_axis = at (Libersky & Petschek 1991, the thesis' type-II virtual particles):
/// the particles within reach of the plane are mirrored across it, with the normal velocity and
/// the shear stresses on the plane reversed, so that the body behaves as half of a symmetric
/// whole: no normal motion through the plane and no shear on it.
struct SymmetryPlane {
  int axis = 0;
  double at = 0.0;
};

/// A run's state: particles, materials, settings, time and the neighbour list with its margin.
struct Hydro {
  Particles particles;
  std::vector<Material> materials;
  Settings settings;
  double time = 0.0;
  long step = 0;
  neighbors::PairList pairs;
  std::vector<double> x_at_build, h_at_build; // positions and h when the list was built
  double build_radius = 0.0;
  int rebuilds = 0;
  std::vector<SurfaceLoad> loads;
  std::vector<TransmittingBoundary> transmitting;
  double external_work = 0.0; // work of the surface loads and boundaries so far
  std::vector<SymmetryPlane> symmetry;
  /// Particles [0, real) are the body; [real, size) are mirror images of ghost_of[k - real],
  /// rebuilt with the neighbour list and refreshed from their sources at every stage.
  int real = -1;
  std::vector<int> ghost_of;
  std::vector<int> ghost_planes; // bit p set: mirrored across symmetry[p]
  int real_count() const { return real < 0 ? particles.size() : real; }
};

/// Copies every mirror particle's state from its source, mirrored.
void refresh_ghosts(Hydro& s);

/// Lighting times for a detonation at point `at` (distance / D_CJ) of every particle of an
/// explosive (JWL) material; other particles never burn. An explosive with an unreacted
/// equation of state is lit on schedule only within 2 h of the point (the booster); the shock
/// lights the rest.
void light_from_point(Hydro& s, const double at[3]);

/// The same for a detonation plane through `at` with unit normal `normal`: lighting time =
/// distance to the plane / D_CJ (a plane wave generator).
void light_from_plane(Hydro& s, const double at[3], const double normal[3]);

/// Smoothing lengths, pressures and sound speeds from density and energy at time t; the
/// pressure of an explosive particle is the JWL pressure times its burn fraction
/// F = clamp((t - t_l) D / (burn_width h), 0, 1).
void update_state(Hydro& s);

/// Rebuilds the neighbour list when a pair closer than 2 h could be missing from it.
void refresh_neighbours(Hydro& s);

/// Rates of velocity, density and energy at the current state.
void compute_rates(const Hydro& s, Rates& r);

/// The CFL step courant * min_i h_i / (c_i + |v_i|) and the particle that sets it.
double stable_step(const Hydro& s, int* limiting = nullptr);

/// One midpoint predictor-corrector step of length dt (second order).
void advance(Hydro& s, double dt);

/// Kinetic and internal energy of all particles.
struct Energies {
  double kinetic = 0.0, internal = 0.0;
  double total() const { return kinetic + internal; }
};
Energies energies(const Hydro& s);

} // namespace mf::sph
