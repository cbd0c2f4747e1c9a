#include "meshfree/sph/condition.hpp"
#include <algorithm>

namespace mf::sph {

namespace {
std::vector<std::unique_ptr<Condition>> clones(const std::vector<std::unique_ptr<Condition>>& a) {
  std::vector<std::unique_ptr<Condition>> out;
  out.reserve(a.size());
  for (const auto& c : a) out.push_back(c->clone());
  return out;
}
} // namespace

OwnedEntries owned_entries(const particles::ParticleSet& P, const std::vector<int>& ids) {
  // Owned particles are kept in increasing global id.
  const auto begin = P.id.begin(), end = P.id.begin() + P.owned_count();
  OwnedEntries out;
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const auto it = std::lower_bound(begin, end, static_cast<long>(ids[k]));
    if (it == end || *it != ids[k]) continue;
    out.entries.push_back(k);
    out.local.push_back(static_cast<int>(it - begin));
  }
  return out;
}

Conditions::Conditions(const Conditions& other)
    : list_(clones(other.list_)), whole_(clones(other.whole_)) {}

Conditions& Conditions::operator=(const Conditions& other) {
  if (this != &other) list_ = clones(other.list_), whole_ = clones(other.whole_);
  return *this;
}

Condition& Conditions::insert(std::unique_ptr<Condition> c) {
  const int order = c->order();
  const auto at = std::find_if(list_.begin(), list_.end(),
                               [order](const auto& x) { return x->order() > order; });
  return **list_.insert(at, std::move(c));
}

Conditions Conditions::take_event_loads() {
  Conditions out;
  std::vector<std::unique_ptr<Condition>> rest;
  for (auto& c : list_) (c->part_of_event() ? out.list_ : rest).push_back(std::move(c));
  list_ = std::move(rest);
  return out;
}

void Conditions::add_all(Conditions&& other) {
  for (auto& c : other.list_) insert(std::move(c));
  other.list_.clear();
}

void Conditions::keep_whole(const particles::ParticleSet& P) {
  whole_ = std::move(list_);
  list_.clear();
  cut(P);
}

void Conditions::cut(const particles::ParticleSet& P) {
  if (whole_.empty()) return;
  list_.clear();
  for (const auto& c : whole_) list_.push_back(c->owned_part(P));
}

} // namespace mf::sph
