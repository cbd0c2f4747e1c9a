#pragma once
// Building blocks of the SPH tests.
#include "meshfree/materials/equation_of_state.hpp"
#include "meshfree/materials/strength.hpp"
#include "meshfree/sph/hydro.hpp"
#include "meshfree/sph/particle_fields.hpp"

/// Adds an SPH particle at rest at x with reference volume and density.
inline int add(mf::sph::Hydro& s, const double x[3], double volume, double rho, double e, double h,
               int mat, bool fixed = false) {
  return mf::sph::add_particle(s, mf::Vec3(x[0], x[1], x[2]), volume, rho, e, h, mat, fixed);
}

/// The solid of the wave tests: linear EOS p = K mu with K = 70 GPa, rho = 2700 kg/m^3,
/// G = 26 GPa, and J2 yield sigma_y (<= 0: elastic).
inline mf::sph::Material test_solid(double sigma_y = 0.0) {
  mf::sph::Material al;
  al.name = "solid";
  mf::materials::LinearPolynomial eos;
  eos.rho0 = 2700.0;
  eos.c[1] = 70e9;
  al.eos = eos;
  if (sigma_y > 0.0) {
    mf::materials::VonMises vm;
    vm.shear_modulus = 26e9;
    vm.j2.E = 2.0 * 26e9; // nu = 0: the return uses mu = G
    vm.j2.nu = 0.0;
    vm.j2.sigma0 = sigma_y;
    al.strength = vm;
  } else {
    al.strength = mf::materials::ElasticShear{26e9};
  }
  return al;
}
