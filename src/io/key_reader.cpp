#include "meshfree/io/key_reader.hpp"
#include <cmath>
#include <set>
#include <sstream>

namespace mf::io {

std::string one_line(const std::string& text, std::size_t limit) {
  std::string out;
  for (const char c : text) {
    if (out.size() == limit) {
      out.replace(limit - 3, 3, "...");
      break;
    }
    out += static_cast<unsigned char>(c) < 0x20 || c == 0x7f ? '?' : c;
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
  error(key, "expected one of [" + list + "], got '" + v + "'");
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
      fail(path_of(key), ": unknown key (known here: ", known, ")");
    }
  }
}

namespace {
/// A list index from an override path, or an error naming the path.
std::size_t list_index(const std::string& part, std::size_t size, const std::string& path) {
  if (part.empty() || part.find_first_not_of("0123456789") != std::string::npos)
    fail("--set ", path, ": '", part, "' indexes a list and must be a number");
  const std::size_t idx = part.size() > 9 ? size : std::stoul(part);
  if (idx >= size)
    fail("--set ", path, ": index ", part.substr(0, 20), " is out of range (the list has ", size,
         " items)");
  return idx;
}
} // namespace

void apply_override(YAML::Node& root, const std::string& assignment) {
  const auto eq = assignment.find('=');
  MF_REQUIRE(eq != std::string::npos && eq > 0, "--set expects key.path=value, got '", assignment,
             "'");
  const std::string path = assignment.substr(0, eq);
  YAML::Node value;
  try {
    value = YAML::Load(assignment.substr(eq + 1));
  } catch (const YAML::Exception& e) {
    fail("--set ", path, ": cannot parse the value: ", e.what());
  }
  std::vector<std::string> parts;
  std::stringstream ss(path);
  for (std::string p; std::getline(ss, p, '.');) parts.push_back(p);
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
      fail("--set ", path, ": '", prefix, "' holds a single value, not a map or a list");
    }
  }
}

} // namespace mf::io
