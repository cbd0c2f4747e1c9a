#pragma once
// Strict reading of a YAML map: every value is fetched by key with its type checked, every
// error names the full key path (e.g. "material.E: expected a positive number, got -2e5"), and
// finish() rejects keys that nothing read.
#include "meshfree/core/error.hpp"
#include "meshfree/core/types.hpp"
#include <optional>
#include <set>
#include <string>
#include <vector>
#include <yaml-cpp/yaml.h>

namespace mf::spec {

/// Text as messages quote it: on one line (line breaks and other control characters, a NUL
/// among them, shown escaped: \n, \t, \x00) and at most `limit` characters, cut with "...".
std::string one_line(const std::string& text, std::size_t limit = 80);

class KeyReader {
public:
  KeyReader(YAML::Node node, std::string path);

  const std::string& path() const { return path_; }
  /// The key's path for messages: one line, the key cut to 80 characters.
  std::string path_of(const std::string& key) const {
    return path_.empty() ? one_line(key) : path_ + "." + one_line(key);
  }
  bool has(const std::string& key) const;
  /// Marks an optional key as known without reading it.
  void allow(const std::string& key) { used_.insert(key); }

  double number(const std::string& key);
  double number(const std::string& key, double fallback);
  double positive(const std::string& key);
  double positive(const std::string& key, double fallback);
  int integer(const std::string& key, int fallback, int lo, int hi);
  std::string text(const std::string& key);
  std::string text(const std::string& key, const std::string& fallback);
  /// One of `choices`; the error lists them.
  std::string choice(const std::string& key, const std::vector<std::string>& choices,
                     const std::string& fallback);
  Vec2 vec2(const std::string& key);
  /// A scalar s read as (s, s), or a pair.
  Vec2 scalar_or_vec2(const std::string& key, const Vec2& fallback);
  std::vector<Vec2> vec2_list(const std::string& key);
  /// A list of exactly `count` numbers.
  std::vector<double> numbers(const std::string& key, int count);
  /// A list of lists of exactly `count` numbers each.
  std::vector<std::vector<double>> number_lists(const std::string& key, int count);

  KeyReader map(const std::string& key);
  std::optional<KeyReader> optional_map(const std::string& key);
  /// A list of maps; each element's path is key[i].
  std::vector<KeyReader> map_list(const std::string& key);
  /// The raw node (marks the key as read).
  YAML::Node raw(const std::string& key);
  /// The whole map (marks every key as read).
  YAML::Node raw_map();

  /// Throws if the map has a key that was never read.
  void finish() const;

  [[noreturn]] void error(const std::string& key, const std::string& message) const;

private:
  YAML::Node get(const std::string& key);
  double to_number(const YAML::Node& n, const std::string& key) const;
  YAML::Node node_;
  std::string path_;
  std::set<std::string> used_;
};

/// Applies "a.b.0.c=value" to a YAML tree (value parsed as YAML; list indices by number).
void apply_override(YAML::Node& root, const std::string& assignment);

} // namespace mf::spec
