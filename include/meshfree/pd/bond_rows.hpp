#pragma once
// The rows of the bond-force loop (pd/forces.hpp): what a thread runs over its range of rows,
// for an instruction set (SimdTarget) chosen once per call: scalar rows, each bond in one pass
// (bond_rows.cpp), or packed rows (AVX2, AVX-512: bond_rows_packed.cpp), each row in groups of
// four bonds whose stretches and force factors are computed four lanes at a time and then summed
// in bond order. Both give the same numbers bit for bit.
#include "meshfree/core/simd_target.hpp"
#include "meshfree/pd/model.hpp"
#include <cstdint>
#include <vector>

namespace mf::pd {

namespace rows {

/// What the loops read and write, as raw arrays.
struct Arrays {
  const double* y; // positions, four doubles a point (x, y, z, 0) from a 32-byte boundary
                   // (owned and ghosts): a point is one load of a packed register
  const long* offset;
  const int* partner;
  ClassView cls;
  const BondClass* classes;
  unsigned char* intact;
  double* plastic;
  const double* s0; // committed s0 of the LAMMPS rule
  const double* volume;
  int owned;
  int points;           // positions in y (owned and ghosts)
  const BondClass* law; // the law constants of every class where they are all equal, else null
};

/// Where rows write force, energy density and trial s0, element 0 at row `base` (the half
/// layout's threads past the first write buffers of their own from their first row on).
struct Output {
  double* f; // half layout: four doubles a point (x, y, z, unused) from a 32-byte boundary, so
             // that a reaction on a partner is one packed load and store; full layout: three
  double* w;
  double* s0n;
  int base;
};

/// Which law terms the bonds have: micro-plastic, the LAMMPS alpha rule, energies asked for.
struct Terms {
  bool plastic = false, alpha = false, energy = false;
};

struct Sums {
  long broken = 0;     // directed bonds broken
  double energy = 0.0; // sum of V W over the rows' particles (half layout only)
};

/// The first row of each of T threads for an equal share of the bonds each (T + 1 entries, the
/// last `owned`), rows ending at offset[i + 1].
std::vector<int> rows_of_threads(const long* offset, int owned, int T);

/// Half layout, rows [lo, hi): each stored pair once, the reaction on an owned partner added to
/// `out` (Newton's third law). Adds to `out`.
Sums half(const Arrays& a, Terms terms, SimdTarget target, int lo, int hi, const Output& out);
/// Full layout, rows [lo, hi): each row its own sums, written to `out` (base 0).
Sums full(const Arrays& a, Terms terms, SimdTarget target, int lo, int hi, const Output& out);

/// The packed rows of either layout for the AVX2 or AVX-512 target (x86-64 only).
Sums packed(const Arrays& a, Terms terms, bool half, SimdTarget target, int lo, int hi,
            const Output& out);

} // namespace rows
} // namespace mf::pd
