#pragma once
// What a transfer from a preload to the particles of an explicit stage did and found: the
// numbers summary.json's "transfer" section and the log give.
#include "meshfree/io/output.hpp"
#include <string>
#include <vector>

namespace mf::stages {

struct TransferReport {
  bool peridynamic = false; // which of the sections below applies
  int particles = 0;
  int plastic_particles = 0;     // yielding in the preload's last increment
  double max_u = 0.0;            // largest |u^h| at the particles
  double stored_energy = 0.0;    // elastic strain energy of the transferred stress
  std::vector<std::string> held; // how each held condition acts on the particles
  // SPH: particles over their yield surface (and returned to it), the largest q / Y, and
  // max |p_EOS(rho, e) + tr(sigma)/3| / max |sigma|.
  int over_surface = 0, returned = 0;
  double worst_yield_ratio = 0.0, density_mismatch = 0.0;
  // The initial out-of-balance: max_i |m_i a_i| / max_i |f_i| over the free particles, f the
  // held surface and body forces, with the transfer's balancing forces on (SPH), and before
  // them: the residual of the SPH sums of the transferred state that those forces take.
  double out_of_balance = 0.0;
  double balanced_residual = 0.0;
  double settle_time = 0.0, settle_drift = 0.0; // max |u - u^h| / max |u^h| after settling
  // Peridynamics: the residual ratio at u^h, adaptive dynamic relaxation from u^h (and from
  // zero) to the body's own equilibrium, where its run starts (out_of_balance: the relaxation's
  // residual ratio), and how far that lies from the Galerkin displacement, |u_PD - u^h| / |u^h|.
  double residual_at_uh = 0.0;
  std::string relax_method; // "newton (its linear solver)" or "adr"
  int relax_linear_iterations = 0;
  int relax_iterations = 0, relax_iterations_from_zero = -1;
  double relax_residual = 0.0, relax_seconds = 0.0, relax_seconds_from_zero = 0.0;
  double pd_vs_galerkin = 0.0;
  double seconds = 0.0; // wall time of the transfer

  io::Json json() const;
};

} // namespace mf::stages
