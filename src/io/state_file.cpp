#include "meshfree/io/state_file.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/io/output.hpp"
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <hdf5.h>
#include <sys/stat.h>

namespace mf::io {

namespace {

template <class T> hid_t native();
template <> hid_t native<double>() {
  return H5T_NATIVE_DOUBLE;
}
template <> hid_t native<long>() {
  return H5T_NATIVE_LONG;
}
template <> hid_t native<int>() {
  return H5T_NATIVE_INT;
}
template <> hid_t native<char>() {
  return H5T_NATIVE_CHAR;
}
template <> hid_t native<unsigned char>() {
  return H5T_NATIVE_UCHAR;
}

/// A serial file: a checkpoint's files are one per rank.
hid_t serial_access() {
  const hid_t access = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_fapl_sec2(access);
  return access;
}

constexpr const char* kChecksum = "fnv1a64";

/// The checksum of a dataset, stored as an attribute of it.
bool put_checksum(hid_t set, std::uint64_t sum) {
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attr =
      H5Acreate2(set, kChecksum, H5T_NATIVE_UINT64, space, H5P_DEFAULT, H5P_DEFAULT);
  const bool ok = attr >= 0 && H5Awrite(attr, H5T_NATIVE_UINT64, &sum) >= 0;
  if (attr >= 0) H5Aclose(attr);
  H5Sclose(space);
  return ok;
}

/// The number of values in a dataspace (a dataset's or an attribute's), -1 when it has none.
hssize_t values_in(hid_t space) {
  return space >= 0 ? H5Sget_simple_extent_npoints(space) : -1;
}

/// The checksum a dataset was written with; false when it has none or it cannot be read. The
/// attribute must hold one value: a damaged dataspace would have H5Aread write past `sum`.
bool get_checksum(hid_t set, std::uint64_t& sum) {
  if (H5Aexists(set, kChecksum) <= 0) return false;
  const hid_t attr = H5Aopen(set, kChecksum, H5P_DEFAULT);
  const hid_t space = attr >= 0 ? H5Aget_space(attr) : -1;
  const hid_t type = attr >= 0 ? H5Aget_type(attr) : -1;
  const bool ok = values_in(space) == 1 && type >= 0 && H5Tequal(type, H5T_NATIVE_UINT64) > 0 &&
                  H5Aread(attr, H5T_NATIVE_UINT64, &sum) >= 0;
  if (type >= 0) H5Tclose(type);
  if (space >= 0) H5Sclose(space);
  if (attr >= 0) H5Aclose(attr);
  return ok;
}

/// The number of values a dataset of `width`-byte values holds, or -1 where its bytes could not
/// be in the file: more than the file's size, or other than the storage the file gives it (the
/// writer stores every array whole and contiguous). Checked before anything is allocated, since a
/// flipped bit in a dimension would otherwise ask for up to 2^63 values (16 GiB for bit 31 of a
/// double array) before the read fails.
hssize_t bounded_count(hid_t set, hid_t space, std::size_t width, std::uintmax_t file_bytes) {
  const hssize_t n = values_in(space);
  if (n < 0 || width == 0 || static_cast<std::uintmax_t>(n) > file_bytes / width) return -1;
  const std::uintmax_t bytes = static_cast<std::uintmax_t>(n) * width;
  return H5Dget_storage_size(set) == bytes ? n : -1;
}

} // namespace

std::uint64_t checksum(const void* data, std::size_t bytes) {
  // FNV-1a taken a 64-bit word at a time (then the tail byte by byte): one multiply per 8 bytes
  // keeps it well above disk speed, and any change of a bit changes the sum.
  constexpr std::uint64_t prime = 0x100000001b3ULL;
  std::uint64_t h = 0xcbf29ce484222325ULL ^ bytes;
  const auto* p = static_cast<const unsigned char*>(data);
  std::size_t i = 0;
  for (; i + 8 <= bytes; i += 8) {
    std::uint64_t word;
    std::memcpy(&word, p + i, 8);
    h = (h ^ word) * prime;
  }
  for (; i < bytes; ++i) h = (h ^ p[i]) * prime;
  return h;
}

void refuse_checkpoint(const std::string& what) {
  throw CheckpointRefused(what);
}

StateWriter::StateWriter(const std::string& path) : path_(path) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t access = serial_access();
  errno = 0;
  file_ = H5Fcreate(path.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, access);
  const int error = errno;
  H5Pclose(access);
  if (file_ < 0) fail("cannot create ", path, error ? ": " + system_reason(error) : std::string());
}

StateWriter::~StateWriter() {
  if (file_ >= 0) H5Fclose(file_);
}

template <class T> void StateWriter::put(const std::string& name, const std::vector<T>& values) {
  MF_REQUIRE(file_ >= 0, path_, ": written after it was closed");
  const hsize_t size = values.size();
  const hid_t space = H5Screate_simple(1, &size, nullptr);
  errno = 0;
  const hid_t set =
      H5Dcreate2(file_, name.c_str(), native<T>(), space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  bool ok = set >= 0 &&
            (values.empty() ||
             H5Dwrite(set, native<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) >= 0) &&
            put_checksum(set, checksum(values.data(), values.size() * sizeof(T)));
  const int error = errno;
  if (set >= 0) ok = H5Dclose(set) >= 0 && ok;
  H5Sclose(space);
  if (!ok)
    fail(error ? system_reason(error) : std::string("HDF5 failed"), " writing ", path_, " (", name,
         ")");
  bytes_ += values.size() * sizeof(T);
}

void StateWriter::close() {
  if (file_ < 0) return;
  errno = 0;
  const bool flushed = H5Fflush(file_, H5F_SCOPE_LOCAL) >= 0;
  const int error = errno;
  const bool closed = H5Fclose(file_) >= 0;
  file_ = -1;
  if (!flushed || !closed)
    fail(error ? system_reason(error) : std::string("HDF5 failed"), " writing ", path_);
}

StateReader::StateReader(const std::string& path) : path_(path) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  // A checkpoint's files are regular files of the run's own folder: a link or anything else at
  // the name is refused, never followed (and a FIFO would block the open).
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode))
    refuse_checkpoint(path + ": not a regular file (a link, or missing)");
  file_bytes_ = static_cast<std::uintmax_t>(st.st_size);
  const hid_t access = serial_access();
  file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, access);
  H5Pclose(access);
  if (file_ < 0) refuse_checkpoint(path + ": not a readable checkpoint file (truncated or damaged)");
}

StateReader::~StateReader() {
  if (file_ >= 0) H5Fclose(file_);
}

bool StateReader::has(const std::string& name) const {
  return H5Lexists(file_, name.c_str(), H5P_DEFAULT) > 0;
}

template <class T> void StateReader::get(const std::string& name, std::vector<T>& values) const {
  if (!has(name))
    refuse_checkpoint(path_ + ": the checkpoint has no '" + name +
                      "' (written by another version of meshfree?)");
  const hid_t set = H5Dopen2(file_, name.c_str(), H5P_DEFAULT);
  const hid_t space = set >= 0 ? H5Dget_space(set) : -1;
  const hid_t type = set >= 0 ? H5Dget_type(set) : -1;
  const bool same_type = type >= 0 && H5Tequal(type, native<T>()) > 0;
  const hssize_t size = same_type ? bounded_count(set, space, sizeof(T), file_bytes_) : -1;
  bool ok = set >= 0 && same_type && size >= 0;
  if (ok) {
    values.resize(static_cast<std::size_t>(size));
    ok = size == 0 || H5Dread(set, native<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) >= 0;
  }
  std::uint64_t sum = 0;
  const bool summed = ok && get_checksum(set, sum);
  if (type >= 0) H5Tclose(type);
  if (space >= 0) H5Sclose(space);
  if (set >= 0) H5Dclose(set);
  if (!ok)
    refuse_checkpoint(path_ + ": cannot read '" + name + "'" +
                      (same_type ? " (a damaged file?)" : " (another type than expected)"));
  if (!summed || sum != checksum(values.data(), values.size() * sizeof(T)))
    refuse_checkpoint(path_ + ": '" + name + "' does not match its checksum (a damaged file)");
}

namespace {
struct VerifyVisit {
  hid_t file;
  std::uintmax_t file_bytes;
  std::string bad;         // the first dataset that cannot be read or fails its checksum
  bool unreadable = false; // which of the two
};

herr_t verify_one(hid_t, const char* name, const H5L_info_t*, void* data) {
  auto& v = *static_cast<VerifyVisit*>(data);
  const hid_t set = H5Dopen2(v.file, name, H5P_DEFAULT);
  const hid_t space = set >= 0 ? H5Dget_space(set) : -1;
  const hid_t stored = set >= 0 ? H5Dget_type(set) : -1;
  const hid_t type = stored >= 0 ? H5Tget_native_type(stored, H5T_DIR_ASCEND) : -1;
  const std::size_t width = type >= 0 ? H5Tget_size(type) : 0;
  const hssize_t n = bounded_count(set, space, stored >= 0 ? H5Tget_size(stored) : 0, v.file_bytes);
  std::uint64_t sum = 0;
  bool ok = n >= 0 && width > 0;
  v.unreadable = !ok;
  if (ok && get_checksum(set, sum)) {
    std::vector<unsigned char> bytes(static_cast<std::size_t>(n) * width);
    ok = n == 0 || H5Dread(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()) >= 0;
    ok = ok && sum == checksum(bytes.data(), bytes.size());
  } else {
    ok = false;
  }
  for (const hid_t t : {type, stored})
    if (t >= 0) H5Tclose(t);
  if (space >= 0) H5Sclose(space);
  if (set >= 0) H5Dclose(set);
  if (ok) return 0;
  v.bad = name;
  return 1; // stops the iteration
}
} // namespace

void StateReader::verify() const {
  VerifyVisit v{file_, file_bytes_, {}};
  hsize_t at = 0;
  const herr_t r = H5Literate(file_, H5_INDEX_NAME, H5_ITER_NATIVE, &at, verify_one, &v);
  if (!v.bad.empty())
    refuse_checkpoint(path_ + ": '" + v.bad +
                      (v.unreadable ? "' cannot be read (a damaged file?)"
                                    : "' does not match its checksum (a damaged file)"));
  if (r < 0) refuse_checkpoint(path_ + ": cannot list its arrays (a damaged file)");
}

void Unpacker::short_of(const std::string& name) {
  refuse_checkpoint("checkpoint: the packed records end before '" + name + "' (a damaged file?)");
}

std::string Loader::folder() const {
  const std::size_t slash = in.path().find_last_of('/');
  return slash == std::string::npos ? "." : in.path().substr(0, slash);
}

void StateReader::wrong_size(const std::string& name, std::size_t size) const {
  refuse_checkpoint(path_ + ": '" + name + "' holds " + std::to_string(size) +
                    " values where one was expected");
}

void StateReader::other_length(const std::string& name, std::size_t size, std::size_t built) const {
  refuse_checkpoint("checkpoint holds " + std::to_string(size) + " values of '" + name +
                    "', this run has " + std::to_string(built) + " (" + path_ + ")");
}

void StateReader::not_whole(const std::string& name, std::size_t size, int components) const {
  refuse_checkpoint("checkpoint holds " + std::to_string(size) + " values of '" + name +
                    "', not a whole number of particles of " + std::to_string(components) +
                    " values (" + path_ + ")");
}

template void StateWriter::put(const std::string&, const std::vector<double>&);
template void StateWriter::put(const std::string&, const std::vector<long>&);
template void StateWriter::put(const std::string&, const std::vector<int>&);
template void StateWriter::put(const std::string&, const std::vector<char>&);
template void StateWriter::put(const std::string&, const std::vector<unsigned char>&);
template void StateReader::get(const std::string&, std::vector<double>&) const;
template void StateReader::get(const std::string&, std::vector<long>&) const;
template void StateReader::get(const std::string&, std::vector<int>&) const;
template void StateReader::get(const std::string&, std::vector<char>&) const;
template void StateReader::get(const std::string&, std::vector<unsigned char>&) const;

} // namespace mf::io
