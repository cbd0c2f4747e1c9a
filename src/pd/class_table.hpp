#pragma once
// The table that gives the bonds of equal law, length, weights and position-aware factors one
// class (pd/model.hpp's BondClass): building the bonds and the corrections that re-class them
// (pd/bonds.cpp, pd/state_surface.cpp) find their classes through it.
#include "meshfree/core/error.hpp"
#include "meshfree/pd/model.hpp"
#include <array>
#include <cstring>
#include <limits>
#include <unordered_map>

namespace mf::pd::detail {

/// What makes two bonds share a class: exact equality of the law and of the seven values.
struct ClassKey {
  int law;
  std::array<double, 7> v; // length, weight, weight_partner, dil, dil_partner, dev, dev_partner
  explicit ClassKey(const BondClass& c)
      : law(c.law), v{c.length,      c.weight, c.weight_partner, c.dil,
                      c.dil_partner, c.dev,    c.dev_partner} {}
  bool operator==(const ClassKey& o) const { return law == o.law && v == o.v; }
};

struct ClassKeyHash {
  std::size_t operator()(const ClassKey& k) const {
    std::uint64_t h = static_cast<std::uint64_t>(k.law) * 0x9E3779B97F4A7C15ull;
    for (double x : k.v) {
      std::uint64_t bits;
      std::memcpy(&bits, &x, sizeof bits);
      h = (h ^ bits) * 0x100000001B3ull + (h >> 29);
    }
    return static_cast<std::size_t>(h);
  }
};

/// Index of a class, added when new.
class ClassTable {
public:
  explicit ClassTable(std::vector<BondClass>& classes) : classes_(classes) {
    for (std::size_t c = 0; c < classes.size(); ++c)
      index_.emplace(ClassKey(classes[c]), static_cast<std::uint32_t>(c));
  }
  /// The class of `like`'s law, length, weights and factors (its folded constants are copied
  /// into a new class; fold_laws sets them anew).
  std::uint32_t find(const BondClass& like) {
    const ClassKey key(like);
    const auto it = index_.find(key);
    if (it != index_.end()) return it->second;
    MF_REQUIRE(classes_.size() < std::numeric_limits<std::uint32_t>::max(),
               "peridynamics: more bond classes than a 32-bit index holds");
    classes_.push_back(like);
    classes_.back().inv_length = 1.0 / like.length;
    const auto k = static_cast<std::uint32_t>(classes_.size() - 1);
    index_.emplace(key, k);
    return k;
  }
  std::uint32_t find(int law, double length, double weight, double weight_partner) {
    BondClass c;
    c.law = law;
    c.length = length;
    c.weight = weight;
    c.weight_partner = weight_partner;
    return find(c);
  }

private:
  std::vector<BondClass>& classes_;
  std::unordered_map<ClassKey, std::uint32_t, ClassKeyHash> index_;
};

} // namespace mf::pd::detail
