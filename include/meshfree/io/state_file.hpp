#pragma once
// One rank's share of a checkpoint (io/checkpoint.hpp): named flat arrays and numbers in an HDF5
// file, written exactly as held in memory (the doubles bit for bit), so that a restart reads back
// the state the run had. The modules that hold state say what it is by a visitor,
//   template <class Visit> void for_each_state(Visit&& visit) { visit("name", member); ... }
// visiting vectors and scalars by name, as ParticleSet::for_each_array does for migration; the
// writer and the reader below are such visitors (Saver, Loader), so a state is listed once.
#include <string>
#include <vector>

namespace mf::io {

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

private:
  [[noreturn]] void wrong_size(const std::string& name, std::size_t size) const;
  std::string path_;
  long file_ = -1; // hid_t
};

/// A visitor that writes each visited value under prefix + name.
struct Saver {
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
  Saver operator/(const std::string& part) const { return {out, prefix + part + "."}; }
};

/// A visitor that reads each visited value back from prefix + name.
struct Loader {
  const StateReader& in;
  std::string prefix;
  template <class T> void operator()(const std::string& name, std::vector<T>& v) const {
    in.get(prefix + name, v);
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
  Loader operator/(const std::string& part) const { return {in, prefix + part + "."}; }
};

} // namespace mf::io
