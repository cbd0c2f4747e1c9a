#pragma once
// One rank's share of a checkpoint (io/checkpoint.hpp): named flat arrays and numbers in an HDF5
// file, written exactly as held in memory (the doubles bit for bit), so that a restart reads back
// the state the run had. The modules that hold state say what it is by a visitor,
//   template <class Visit> void for_each_state(Visit&& visit) { visit("name", member); ... }
// visiting vectors, scalars and fixed-size Eigen vectors by name, and per-particle arrays by
// their registry entry (visit(particles::FieldInfo, array): ParticleSet::for_each_state); the
// writer and the reader below are such visitors (Saver, Loader), so a state is listed once.
//
// Every dataset carries a 64-bit checksum of its values (attribute "fnv1a64"), verified when it is
// read: a flipped bit that leaves the file readable is refused like a truncated file, and so is an
// array whose length differs from the one the run built (CheckpointRefused, exit 2).
#include "meshfree/core/error.hpp"
#include "meshfree/core/types.hpp"
#include "meshfree/particles/field_info.hpp"
#include <algorithm>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

namespace mf::io {

/// A checkpoint that is not this run's, or is damaged: refused as input (exit 2, nothing written)
/// with one line naming what differs.
class CheckpointRefused : public Error {
public:
  explicit CheckpointRefused(const std::string& what) : Error(what) {}
};
[[noreturn]] void refuse_checkpoint(const std::string& what);

/// FNV-1a over 64-bit words (the tail byte by byte), seeded with the length.
std::uint64_t checksum(const void* data, std::size_t bytes);

/// A new HDF5 file of named arrays. Created exclusively; every call is checked and a failure
/// names the file and the reason ("no space left on device writing …").
class StateWriter {
public:
  explicit StateWriter(const std::string& path);
  ~StateWriter();
  StateWriter(const StateWriter&) = delete;
  StateWriter& operator=(const StateWriter&) = delete;
  /// T: double, long, int, char or unsigned char.
  template <class T> void put(const std::string& name, const std::vector<T>& values);
  template <class T> void put(const std::string& name, T value) {
    put(name, std::vector<T>{value});
  }
  void put_text(const std::string& name, const std::string& text) {
    put(name, std::vector<char>(text.begin(), text.end()));
  }
  /// Flushes the file to disk and closes it.
  void close();
  /// Bytes of the arrays written so far.
  std::size_t bytes() const { return bytes_; }

private:
  std::string path_;
  long file_ = -1; // hid_t
  std::size_t bytes_ = 0;
};

/// A state file read back; a missing or mistyped array is an error naming the file and the array.
class StateReader {
public:
  explicit StateReader(const std::string& path);
  ~StateReader();
  StateReader(const StateReader&) = delete;
  StateReader& operator=(const StateReader&) = delete;
  bool has(const std::string& name) const;
  template <class T> void get(const std::string& name, std::vector<T>& values) const;
  template <class T> void get(const std::string& name, T& value) const {
    std::vector<T> v;
    get(name, v);
    if (v.size() != 1) wrong_size(name, v.size());
    value = v[0];
  }
  std::string text(const std::string& name) const {
    std::vector<char> v;
    get(name, v);
    return {v.begin(), v.end()};
  }
  const std::string& path() const { return path_; }
  /// Whether the file is large enough to hold `count` records (each at least one byte): a count
  /// read from the file is checked so before a list is sized by it.
  bool can_hold(long count) const {
    return count >= 0 && static_cast<std::uintmax_t>(count) <= file_bytes_;
  }
  /// Reads every dataset of the file and checks it against its checksum.
  void verify() const;
  [[noreturn]] void wrong_size(const std::string& name, std::size_t size) const;
  [[noreturn]] void other_length(const std::string& name, std::size_t size,
                                 std::size_t built) const;
  [[noreturn]] void not_whole(const std::string& name, std::size_t size, int components) const;

private:
  std::string path_;
  long file_ = -1;                // hid_t
  std::uintmax_t file_bytes_ = 0; // no dataset can hold more
};

/// A visitor that writes each visited value under prefix + name.
struct Saver {
  static constexpr bool loads = false;
  StateWriter& out;
  std::string prefix;
  template <class T> void operator()(const std::string& name, const std::vector<T>& v) const {
    out.put(prefix + name, v);
  }
  void operator()(const std::string& name, const std::vector<bool>&) const = delete;
  template <class T> void operator()(const std::string& name, const T& v) const {
    out.put(prefix + name, v);
  }
  void operator()(const std::string& name, const bool& v) const {
    out.put(prefix + name, static_cast<char>(v));
  }
  void operator()(const std::string& name, const std::string& v) const {
    out.put_text(prefix + name, v);
  }
  template <int R, int C, int O, int MR, int MC>
  void operator()(const std::string& name, const Eigen::Matrix<double, R, C, O, MR, MC>& m) const {
    out.put(prefix + name, std::vector<double>(m.data(), m.data() + R * C));
  }
  template <class T> void operator()(const particles::FieldInfo& f, const std::vector<T>& v) const {
    (*this)(f.name, v);
  }
  Saver operator/(const std::string& part) const { return {out, prefix + part + "."}; }
  /// See Loader::resizing.
  Saver resizing() const { return *this; }
};

/// A visitor that reads each visited value back from prefix + name. An array the run built
/// before the restart (not empty) must come back with the same length, unless `resizes` (the
/// arrays of particles that move between MPI ranks).
struct Loader {
  static constexpr bool loads = true;
  const StateReader& in;
  std::string prefix;
  bool resizes = false;
  template <class T> void operator()(const std::string& name, std::vector<T>& v) const {
    const std::size_t built = v.size();
    in.get(prefix + name, v);
    if (built > 0 && v.size() != built && !resizes) in.other_length(prefix + name, v.size(), built);
  }
  template <class T> void operator()(const std::string& name, T& v) const {
    in.get(prefix + name, v);
  }
  void operator()(const std::string& name, bool& v) const {
    char c = 0;
    in.get(prefix + name, c);
    v = c != 0;
  }
  void operator()(const std::string& name, std::string& v) const { v = in.text(prefix + name); }
  template <int R, int C, int O, int MR, int MC>
  void operator()(const std::string& name, Eigen::Matrix<double, R, C, O, MR, MC>& m) const {
    std::vector<double> v;
    in.get(prefix + name, v);
    if (v.size() != static_cast<std::size_t>(R * C)) in.wrong_size(prefix + name, v.size());
    std::copy(v.begin(), v.end(), m.data());
  }
  /// A per-particle array must hold whole particles: a multiple of its values per particle.
  template <class T> void operator()(const particles::FieldInfo& f, std::vector<T>& v) const {
    (*this)(f.name, v);
    if (v.size() % static_cast<std::size_t>(f.components) != 0)
      in.not_whole(prefix + f.name, v.size(), f.components);
  }
  Loader operator/(const std::string& part) const { return {in, prefix + part + ".", resizes}; }
  /// For arrays whose length changes as a run goes (neighbour lists, the bonds broken in the
  /// last step): read back at the length kept.
  Loader resizing() const { return {in, prefix, true}; }
  /// The checkpoint folder the state is read from.
  std::string folder() const;
  bool can_hold(long count) const { return in.can_hold(count); }
};

/// A visitor that packs the visited values, names aside, into one byte array: many small
/// records (a run's increments) become one dataset instead of thousands.
struct Packer {
  static constexpr bool loads = false;
  std::vector<char>& bytes;
  template <class T> void operator()(const std::string&, const std::vector<T>& v) const {
    static_assert(std::is_arithmetic_v<T>, "numbers only");
    const long n = static_cast<long>(v.size());
    raw(&n, sizeof n);
    raw(v.data(), v.size() * sizeof(T));
  }
  void operator()(const std::string& name, const std::string& s) const {
    (*this)(name, std::vector<char>(s.begin(), s.end()));
  }
  template <class T> void operator()(const std::string&, const T& v) const {
    static_assert(std::is_arithmetic_v<T>, "numbers only");
    raw(&v, sizeof v);
  }
  template <int R, int C, int O, int MR, int MC>
  void operator()(const std::string&, const Eigen::Matrix<double, R, C, O, MR, MC>& m) const {
    raw(m.data(), R * C * sizeof(double));
  }
  Packer operator/(const std::string&) const { return *this; }
  void raw(const void* p, std::size_t n) const {
    const char* c = static_cast<const char*>(p);
    bytes.insert(bytes.end(), c, c + n);
  }
};

/// Reads back what a Packer packed, in the same order.
struct Unpacker {
  static constexpr bool loads = true;
  const std::vector<char>& bytes;
  std::size_t& at;
  template <class T> void operator()(const std::string& name, std::vector<T>& v) const {
    long n = 0;
    raw(name, &n, sizeof n);
    if (n < 0 || static_cast<std::size_t>(n) > (bytes.size() - at) / sizeof(T)) short_of(name);
    v.resize(static_cast<std::size_t>(n));
    raw(name, v.data(), v.size() * sizeof(T));
  }
  void operator()(const std::string& name, std::string& s) const {
    std::vector<char> v;
    (*this)(name, v);
    s.assign(v.begin(), v.end());
  }
  template <class T> void operator()(const std::string& name, T& v) const {
    raw(name, &v, sizeof v);
  }
  template <int R, int C, int O, int MR, int MC>
  void operator()(const std::string& name, Eigen::Matrix<double, R, C, O, MR, MC>& m) const {
    raw(name, m.data(), R * C * sizeof(double));
  }
  Unpacker operator/(const std::string&) const { return *this; }
  void raw(const std::string& name, void* p, std::size_t n) const {
    if (n > bytes.size() - at) short_of(name);
    std::copy(bytes.data() + at, bytes.data() + at + n, static_cast<char*>(p));
    at += n;
  }
  [[noreturn]] static void short_of(const std::string& name);
  /// Whether the bytes left hold `count` records (each packs at least one byte).
  bool can_hold(long count) const {
    return count >= 0 && static_cast<std::size_t>(count) <= bytes.size() - at;
  }
};

/// Visits the number of `what` (particles, nodes) the run has over every rank: a checkpoint that
/// holds another number is refused, naming both.
template <class Visit> void visit_count(Visit&& visit, const std::string& what, long count) {
  long kept = count;
  visit("count." + what, kept);
  if (kept != count)
    refuse_checkpoint("checkpoint holds " + std::to_string(kept) + " " + what + ", this run has " +
                      std::to_string(count));
}

/// Visits a list of records: its length as `name`.count, then record k under `name`.k through
/// each(visitor, record). Loading fills an empty list with the records kept; a list the set-up
/// made (impactors) must have kept as many.
template <class Visit, class T, class Each>
void visit_list(Visit&& visit, const std::string& name, std::vector<T>& list, Each&& each) {
  const long had = static_cast<long>(list.size());
  long count = had;
  visit(name + ".count", count);
  bool fits = count >= 0;
  if constexpr (std::decay_t<Visit>::loads) fits = visit.can_hold(count);
  if (!fits || (had != 0 && count != had))
    refuse_checkpoint("checkpoint holds " + std::to_string(count) + " " + name + ", this run has " +
                      std::to_string(had));
  list.resize(static_cast<std::size_t>(count));
  for (std::size_t k = 0; k < list.size(); ++k)
    each(visit / (name + "." + std::to_string(k)), list[k]);
}

/// Visits an array of fixed-size records of doubles (Eigen vectors and matrices, structs of them)
/// as one flat array of doubles, in both directions: the records are copied out, visited, and
/// copied back (a Loader resizes them to what the file holds).
template <class T, class Visit>
void visit_flat(Visit&& visit, const std::string& name, std::vector<T>& records) {
  // Fixed-size Eigen objects hold their coefficients in place, so the records are doubles one
  // after another (with the padding a 16-byte alignment may add, copied along unread).
  static_assert(sizeof(T) % sizeof(double) == 0, "records of doubles only");
  constexpr std::size_t per = sizeof(T) / sizeof(double);
  const auto doubles = [&records] { return reinterpret_cast<double*>(records.data()); };
  std::vector<double> flat(doubles(), doubles() + records.size() * per);
  visit(name, flat);
  records.resize(flat.size() / per);
  std::copy(flat.begin(), flat.end(), doubles());
}

} // namespace mf::io
