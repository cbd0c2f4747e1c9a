#include "meshfree/spec/key_reader.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>

namespace mf::spec {

std::string one_line(const std::string& text, std::size_t limit) {
  std::string out;
  for (const char c : text) {
    std::string shown(1, c);
    if (c == '\n')
      shown = "\\n";
    else if (c == '\r')
      shown = "\\r";
    else if (c == '\t')
      shown = "\\t";
    else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", static_cast<unsigned char>(c));
      shown = hex;
    }
    if (out.size() + shown.size() > limit) {
      out.resize(std::min(out.size(), limit - 3));
      return out + "...";
    }
    out += shown;
  }
  return out;
}

namespace {
std::string show(const YAML::Node& n) {
  if (!n.IsDefined() || n.IsNull()) return "nothing";
  YAML::Emitter e;
  e << YAML::Flow << n;
  return one_line(std::string(e.c_str(), e.size()));
}
} // namespace

KeyReader::KeyReader(YAML::Node node, std::string path)
    : node_(std::move(node)), path_(std::move(path)) {
  if (!node_.IsMap())
    fail(path_.empty() ? "document" : path_, ": expected a map of keys, got ", show(node_));
}

void KeyReader::error(const std::string& key, const std::string& message) const {
  fail(path_of(key), ": ", message);
}

bool KeyReader::has(const std::string& key) const {
  return node_[key].IsDefined() && !node_[key].IsNull();
}

YAML::Node KeyReader::get(const std::string& key) {
  used_.insert(key);
  const YAML::Node n = node_[key];
  if (!n.IsDefined() || n.IsNull()) error(key, "required value is missing");
  return n;
}

YAML::Node KeyReader::raw(const std::string& key) {
  return get(key);
}

YAML::Node KeyReader::raw_map() {
  for (const auto& kv : node_)
    if (kv.first.IsScalar()) used_.insert(kv.first.Scalar());
  return node_;
}

double KeyReader::to_number(const YAML::Node& n, const std::string& key) const {
  if (!n.IsScalar()) error(key, "expected a number, got " + show(n));
  try {
    std::size_t pos = 0;
    const std::string s = n.Scalar();
    const double v = std::stod(s, &pos);
    if (pos != s.size() || !std::isfinite(v)) throw std::invalid_argument(s);
    return v;
  } catch (const std::exception&) {
    error(key, "expected a number, got " + show(n));
  }
}

double KeyReader::number(const std::string& key) {
  return to_number(get(key), key);
}

double KeyReader::number(const std::string& key, double fallback) {
  used_.insert(key);
  return has(key) ? number(key) : fallback;
}

double KeyReader::positive(const std::string& key) {
  const double v = number(key);
  if (!(v > 0.0)) {
    std::ostringstream os;
    os.precision(10);
    os << "expected a positive number, got " << v;
    error(key, os.str());
  }
  return v;
}

double KeyReader::positive(const std::string& key, double fallback) {
  used_.insert(key);
  return has(key) ? positive(key) : fallback;
}

int KeyReader::integer(const std::string& key, int fallback, int lo, int hi) {
  used_.insert(key);
  if (!has(key)) return fallback;
  const double v = number(key);
  if (v < lo || v > hi || v != std::floor(v))
    error(key, "expected an integer from " + std::to_string(lo) + " to " + std::to_string(hi) +
                   ", got " + show(node_[key]));
  return static_cast<int>(v);
}

std::string KeyReader::text(const std::string& key) {
  const YAML::Node n = get(key);
  if (!n.IsScalar()) error(key, "expected a string, got " + show(n));
  return n.Scalar();
}

std::string KeyReader::text(const std::string& key, const std::string& fallback) {
  used_.insert(key);
  return has(key) ? text(key) : fallback;
}

std::string KeyReader::choice(const std::string& key, const std::vector<std::string>& choices,
                              const std::string& fallback) {
  const std::string v = fallback.empty() ? text(key) : text(key, fallback);
  for (const auto& c : choices)
    if (c == v) return v;
  std::string list;
  for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
  error(key, "expected one of [" + list + "], got '" + one_line(v) + "'");
}

Vec2 KeyReader::vec2(const std::string& key) {
  const YAML::Node n = get(key);
  if (!n.IsSequence() || n.size() != 2) error(key, "expected a pair [a, b], got " + show(n));
  return {to_number(n[0], key), to_number(n[1], key)};
}

Vec2 KeyReader::scalar_or_vec2(const std::string& key, const Vec2& fallback) {
  used_.insert(key);
  if (!has(key)) return fallback;
  const YAML::Node n = node_[key];
  if (n.IsScalar()) {
    const double v = positive(key);
    return {v, v};
  }
  const Vec2 v = vec2(key);
  if (!(v.x() > 0.0 && v.y() > 0.0)) error(key, "expected positive numbers, got " + show(n));
  return v;
}

std::vector<double> KeyReader::numbers(const std::string& key, int count) {
  const YAML::Node n = get(key);
  if (!n.IsSequence() || static_cast<int>(n.size()) != count)
    error(key, "expected a list of " + std::to_string(count) + " numbers, got " + show(n));
  std::vector<double> out;
  for (const auto& v : n) out.push_back(to_number(v, key));
  return out;
}

std::vector<std::vector<double>> KeyReader::number_lists(const std::string& key, int count) {
  const YAML::Node n = get(key);
  if (!n.IsSequence()) error(key, "expected a list of lists, got " + show(n));
  std::vector<std::vector<double>> out;
  for (std::size_t i = 0; i < n.size(); ++i) {
    const std::string k = key + "[" + std::to_string(i) + "]";
    if (!n[i].IsSequence() || static_cast<int>(n[i].size()) != count)
      error(k, "expected a list of " + std::to_string(count) + " numbers, got " + show(n[i]));
    std::vector<double> row;
    for (const auto& v : n[i]) row.push_back(to_number(v, k));
    out.push_back(row);
  }
  return out;
}

std::vector<Vec2> KeyReader::vec2_list(const std::string& key) {
  const YAML::Node n = get(key);
  if (!n.IsSequence()) error(key, "expected a list of pairs, got " + show(n));
  std::vector<Vec2> out;
  for (std::size_t i = 0; i < n.size(); ++i) {
    const std::string k = key + "[" + std::to_string(i) + "]";
    if (!n[i].IsSequence() || n[i].size() != 2)
      error(k, "expected a pair [x, y], got " + show(n[i]));
    out.emplace_back(to_number(n[i][0], k), to_number(n[i][1], k));
  }
  return out;
}

KeyReader KeyReader::map(const std::string& key) {
  const YAML::Node n = get(key);
  if (!n.IsMap()) error(key, "expected a map of keys, got " + show(n));
  return KeyReader(n, path_of(key));
}

std::optional<KeyReader> KeyReader::optional_map(const std::string& key) {
  used_.insert(key);
  if (!has(key)) return std::nullopt;
  return map(key);
}

std::vector<KeyReader> KeyReader::map_list(const std::string& key) {
  used_.insert(key);
  std::vector<KeyReader> out;
  if (!has(key)) return out;
  const YAML::Node n = node_[key];
  if (!n.IsSequence()) error(key, "expected a list, got " + show(n));
  for (std::size_t i = 0; i < n.size(); ++i) {
    const std::string k = path_of(key) + "[" + std::to_string(i) + "]";
    if (!n[i].IsMap()) fail(k, ": expected a map of keys, got ", show(n[i]));
    out.emplace_back(n[i], k);
  }
  return out;
}

namespace {
/// Levenshtein distance: the edits (insert, delete, replace a character) from a to b.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
      diagonal = up;
    }
  }
  return row[b.size()];
}

/// The known key a misspelt one is nearest to, within two edits and a third of its length
/// ("" when none is that near, or the key is too long to be a slip).
std::string nearest(const std::string& key, const std::set<std::string>& known) {
  if (key.size() > 64) return "";
  std::string best;
  std::size_t best_distance = std::min<std::size_t>(2, std::max<std::size_t>(1, key.size() / 3));
  for (const std::string& k : known) {
    const std::size_t d = edit_distance(key, k);
    if (d <= best_distance && (best.empty() || d < best_distance)) best = k, best_distance = d;
  }
  return best;
}
} // namespace

void KeyReader::finish() const {
  std::set<std::string> seen;
  for (const auto& kv : node_) {
    if (!kv.first.IsScalar())
      fail(path_.empty() ? "document" : path_, ": keys must be plain names, got ", show(kv.first));
    const std::string key = kv.first.Scalar();
    // YAML reads the first of two equal keys and drops the other without a word; a slip such as
    // a second E further down a material is refused instead.
    if (!seen.insert(key).second) fail(path_of(key), ": given twice");
    if (!used_.count(key)) {
      std::string known;
      for (const auto& u : used_) known += (known.empty() ? "" : ", ") + u;
      const std::string near = nearest(key, used_);
      fail(path_of(key), ": unknown key (known here: ", known, ")",
           near.empty() ? "" : "; did you mean '" + near + "'?");
    }
  }
}

namespace {
/// A list index from an override path, or an error naming the path.
std::size_t list_index(const std::string& part, std::size_t size, const std::string& path) {
  if (part.empty() || part.find_first_not_of("0123456789") != std::string::npos)
    fail("--set ", one_line(path), ": '", one_line(part), "' indexes a list and must be a number");
  const std::size_t idx = part.size() > 9 ? size : std::stoul(part);
  if (idx >= size)
    fail("--set ", one_line(path), ": index ", part.substr(0, 20),
         " is out of range (the list has ", size, " items)");
  return idx;
}
} // namespace

namespace {
/// The keys and list indices of an override path, "a.1.b" or "a[1].b" (the style messages print
/// keys in); an empty key (".name", "a..b", "a[]") is refused with the path.
std::vector<std::string> override_path(const std::string& path) {
  std::vector<std::string> parts;
  std::string part;
  const auto end_part = [&](bool after_bracket) {
    if (part.empty() && !after_bracket)
      fail("--set ", one_line(path), ": an empty key in the path (expected key.path=value)");
    if (!part.empty()) parts.push_back(part);
    part.clear();
  };
  bool after_bracket = false; // "a[1].b": the '.' after ']' ends no key of its own
  for (std::size_t i = 0; i < path.size(); ++i) {
    const char c = path[i];
    if (c == '.') {
      end_part(after_bracket);
      after_bracket = false;
    } else if (c == '[') {
      end_part(false);
      const std::size_t close = path.find(']', i);
      if (close == std::string::npos || close == i + 1)
        fail("--set ", one_line(path), ": expected a list index in brackets, as in boundary[1].x");
      parts.push_back(path.substr(i + 1, close - i - 1));
      i = close;
      after_bracket = true;
    } else {
      if (after_bracket) fail("--set ", one_line(path), ": expected '.' or '[' after ']'");
      part += c;
    }
  }
  if (!after_bracket) end_part(false);
  return parts;
}
} // namespace

void apply_override(YAML::Node& root, const std::string& assignment) {
  const auto eq = assignment.find('=');
  MF_REQUIRE(eq != std::string::npos && eq > 0, "--set expects key.path=value, got '",
             one_line(assignment), "'");
  const std::string path = assignment.substr(0, eq);
  YAML::Node value;
  try {
    value = YAML::Load(assignment.substr(eq + 1));
  } catch (const YAML::Exception& e) {
    fail("--set ", one_line(path), ": cannot parse the value: ", e.what());
  }
  const std::vector<std::string> parts = override_path(path);
  // Walk with fresh handles (yaml-cpp node assignment rebinds, so keep a chain of copies).
  std::vector<YAML::Node> chain{root};
  for (std::size_t i = 0; i < parts.size(); ++i) {
    YAML::Node cur = chain.back();
    const std::string& p = parts[i];
    const bool last = i + 1 == parts.size();
    if (cur.IsSequence()) {
      const std::size_t idx = list_index(p, cur.size(), path);
      if (last)
        cur[idx] = value;
      else
        chain.push_back(cur[idx]);
    } else if (cur.IsMap() || cur.IsNull() || !cur.IsDefined()) {
      if (last) {
        cur[p] = value;
      } else {
        if (!cur[p].IsDefined() || cur[p].IsNull()) cur[p] = YAML::Node(YAML::NodeType::Map);
        chain.push_back(cur[p]);
      }
    } else {
      std::string prefix;
      for (std::size_t k = 0; k < i; ++k) prefix += (k ? "." : "") + parts[k];
      fail("--set ", one_line(path), ": '", one_line(prefix),
           "' holds a single value, not a map or a list");
    }
  }
}

} // namespace mf::spec
