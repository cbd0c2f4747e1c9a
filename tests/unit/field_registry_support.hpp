#pragma once
// Tests of the per-particle field registry (particles/field_info.hpp): every registered array of
// a struct filled with values no other array holds, and compared array by array through the
// registry, so that a path that drops or mixes up an array fails naming it.
#include "meshfree/particles/field_info.hpp"
#include <catch2/catch.hpp>
#include <cstddef>
#include <type_traits>

/// Sets every registered array of `s` to n particles, array k holding k * 1000 + 1, k * 1000 + 2,
/// ... (chars wrap, but differ between neighbouring values and arrays).
template <class Fields> void fill_distinct(Fields& s, int n) {
  int k = 0;
  s.for_each_field([&k, n](const mf::particles::FieldInfo& f, auto& a) {
    using T = typename std::decay_t<decltype(a)>::value_type;
    a.resize(static_cast<std::size_t>(f.components) * n);
    for (std::size_t j = 0; j < a.size(); ++j) a[j] = static_cast<T>(1000 * k + 3 * j + 1);
    ++k;
  });
}

/// Particle i of `a` and particle j of `b` hold the same values in every registered array but
/// those with a flag of `except`.
template <class Fields>
void require_same_particle(const Fields& a, int i, const Fields& b, int j, unsigned except = 0) {
  Fields::for_each_member([&](const mf::particles::FieldInfo& f, auto m) {
    if (f.flags & except) return;
    INFO("array " << f.name << ", particles " << i << " and " << j);
    for (int c = 0; c < f.components; ++c)
      REQUIRE((a.*m)[f.components * i + c] == (b.*m)[f.components * j + c]);
  });
}

/// Every registered array of `a` equals that of `b` (lengths included), but those with a flag of
/// `except`.
template <class Fields> void require_same(const Fields& a, const Fields& b, unsigned except = 0) {
  Fields::for_each_member([&](const mf::particles::FieldInfo& f, auto m) {
    if (f.flags & except) return;
    INFO("array " << f.name);
    REQUIRE((a.*m) == (b.*m));
  });
}
