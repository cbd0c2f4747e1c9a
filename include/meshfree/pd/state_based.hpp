#pragma once
// The forces of a state-based peridynamic body (the linear peridynamic solid, LPS; constants and
// formulas in materials/pd_state.hpp) on the bonds of a bond-based one (pd/model.hpp): the same
// rows, classes, intact flags, breaking rules and layouts, evaluated in two passes, as LAMMPS
// peri/lps does (PairPeriLPS::compute): the dilatation theta_i of every owned particle, which the
// halo then gives the ghosts, and the forces
//   F_i = sum_j (t_i<xi_ij> + t_j<xi_ji>) w_ij (y_j - y_i) / |y_j - y_i|,
// t_i = omega [p_i |xi| + b_i e], p_i = (d kappa_i - a mu_i / d) theta_i / m_i, b_i = a mu_i / m_i,
// with w_ij the volume V_j a bond counts (volume corrections included) and e = |y_j - y_i| - |xi|.
// Each particle's state takes its own material's constants (LAMMPS takes particle i's for both
// terms; one material gives the same). A bond breaks after its force has counted (critical
// stretch, or LAMMPS's alpha rule), as in pd/forces.hpp; the weighted volumes m_i stay those of
// the family at the start (LAMMPS computes them once, FixPeriNeigh::setup). An elastic-plastic
// material (EPS, Mitchell 2011; materials::eps_yield_value) adds a pass between the two: the
// norm of each particle's trial deviatoric force state, whose radial return to the yield surface
// scales its deviatoric part; every stored bond keeps both ends' plastic deviatoric extension.
#include "meshfree/pd/forces.hpp"
#include "meshfree/pd/model.hpp"
#include <vector>

namespace mf::pd {

/// m_i = sum_j omega |xi|^2 w_ij over the bonds intact in `s` (after pre-cracks), for every
/// owned particle, given to the ghosts by the halo (collective). Call once the state is built.
void set_weighted_volumes(Model& m, const BondState& s);

/// Fills `force` (3 per particle, force per unit volume) at positions `y` (3 per particle;
/// ghosts' refreshed), breaking bonds as bond_forces does; `energy_density` (optional) gets
/// W_i. `theta` (optional) gets every particle's dilatation. Collective on a run over ranks (the
/// ghosts' dilatation is exchanged).
ForceReport state_forces(const Model& m, BondState& s, const std::vector<double>& y,
                         std::vector<double>& force, bool with_energy = false,
                         std::vector<double>* energy_density = nullptr,
                         std::vector<double>* theta = nullptr);

/// The forces and energy densities at y of the body whose intact bonds are `intact` and whose
/// plastic deviatoric extensions are `plastic` (empty: elastic), none broken and the plastic
/// state left as it is: what the fracture account (pd/fracture_energy.hpp) compares before and
/// after a break. Collective.
void state_forces_kept(const Model& m, const std::vector<unsigned char>& intact,
                       const std::vector<double>& plastic, const std::vector<double>& y,
                       std::vector<double>& force, std::vector<double>& energy_density);

/// The fictitious density of every component (3 a particle) for adaptive dynamic relaxation at a
/// unit step (Kilic & Madenci 2010): a quarter of the absolute row sum of the linearised LPS
/// stiffness, bounded as Gershgorin's theorem needs: the deviatoric bonds 2 sum_j omega (b_i +
/// b_j) w_ij |e_d| (|e_x| + |e_y| + |e_z|), the particle's own dilatation 2 sqrt(3) |A_i| d S_i^2
/// / m_i and its partners' 2 sqrt(3) sum_j omega |xi| w_ij |A_j| d S_j / m_j, where A_i = (d kappa
/// - a mu / d) / m_i and S_i = sum_j omega |xi| w_ij, over the bonds intact in s.
std::vector<double> state_fictitious_density(const Model& m, const BondState& s);

/// The velocity-Verlet stability limit 2 / omega_max of an LPS body, omega_max^2 the highest
/// eigenvalue of its linearised stiffness over density, by `iterations` steps of power iteration
/// (the estimate approaches the limit from above: the tests bound its excess on small bodies).
/// A row-sum (Gershgorin) bound of the Silling-Askari kind is safe but, with the dilatation's
/// coupling of every partner's partners, 0.38-0.56 of the limit (measured on lattices at
/// nu = 0.2-0.45), which would refuse LAMMPS's own time steps. Collective.
double state_stable_time_step(const Model& m, int iterations = 60);

} // namespace mf::pd
