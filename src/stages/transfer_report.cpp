#include "meshfree/stages/transfer_report.hpp"

namespace mf::stages {

io::Json TransferReport::json() const {
  io::Json j;
  j.set("particles", particles)
      .set("plastic_particles", plastic_particles)
      .set("max_displacement", max_u)
      .set("stored_elastic_energy", stored_energy);
  io::Json h;
  for (std::size_t k = 0; k < held.size(); ++k) h.set(std::to_string(k), held[k]);
  j.set("held", h);
  j.set("initial_out_of_balance", out_of_balance);
  if (peridynamic) {
    j.set("residual_at_galerkin_displacement", residual_at_uh)
        .set("equilibrium", relax_method)
        .set("relaxation_iterations", relax_iterations)
        .set("relaxation_linear_iterations", relax_linear_iterations)
        .set("relaxation_iterations_from_zero", relax_iterations_from_zero)
        .set("relaxation_residual_ratio", relax_residual)
        .set("relaxation_seconds", relax_seconds)
        .set("relaxation_seconds_from_zero", relax_seconds_from_zero)
        .set("pd_vs_galerkin_displacement", pd_vs_galerkin);
  } else {
    j.set("balanced_residual", balanced_residual)
        .set("particles_over_yield_surface", over_surface)
        .set("particles_returned_to_yield_surface", returned)
        .set("worst_yield_ratio", worst_yield_ratio)
        .set("density_mismatch", density_mismatch)
        .set("settle_time", settle_time)
        .set("settle_drift", settle_drift);
  }
  j.set("seconds", seconds);
  return j;
}

} // namespace mf::stages
