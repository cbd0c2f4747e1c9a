#pragma once
// The registry of per-particle arrays: each struct of them (ParticleSet, sph::ParticleFields)
// lists its arrays once, with what they are (name, values per particle) and what the program
// does with them (flags, output name), in a member function
//   template <class Visit> static constexpr void for_each_member(Visit&& visit) {
//     visit(FieldInfo{"u", 3, kMigrates | kCheckpointed, "displacement"}, &Self::u); ...
//   }
// Rank migration, ghost copies, checkpoints and the field output all walk that one list (through
// for_each_field), so an array added there travels, is kept and is written with its particle;
// an array left out of it is caught at compile time by the size check beside each struct.

namespace mf::particles {

/// What the program does with a per-particle array (bits of FieldInfo::flags).
enum FieldFlags : unsigned {
  /// Travels with its particle to another MPI rank (an array without it starts at zero on the
  /// particles a rank receives).
  kMigrates = 1u << 0,
  /// Kept by a checkpoint and read back on restart.
  kCheckpointed = 1u << 1,
  /// Made by the set-up and never changed by the run: a run that builds the same particles on
  /// the same rank again at restart (peridynamics) takes it from the set-up, not the checkpoint.
  kSetUp = 1u << 2,
};

struct FieldInfo {
  const char* name; // the array's name in a checkpoint
  int components;   // values per particle
  unsigned flags;   // FieldFlags
  /// The field's name in the field output (fields.h5); nullptr: not written. Written fields are
  /// scalars or vectors (1 or 3 components).
  const char* output = nullptr;
  constexpr bool has(unsigned flag) const { return (flags & flag) == flag; }
};

/// The number of arrays a struct registers (its for_each_member), at compile time.
template <class Fields> constexpr int registered_fields() {
  int n = 0;
  Fields::for_each_member([&n](const FieldInfo&, auto) { ++n; });
  return n;
}

/// Calls visit(info, array) for every array of `fields` (a struct with a registry) that a
/// checkpoint keeps, but those with a flag of `except`.
template <class Fields, class Visit>
void for_each_kept(Fields& fields, Visit&& visit, unsigned except = 0) {
  fields.for_each_field([&visit, except](const FieldInfo& f, auto& a) {
    if (f.has(kCheckpointed) && !(f.flags & except)) visit(f, a);
  });
}

} // namespace mf::particles
