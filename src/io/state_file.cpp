#include "meshfree/io/state_file.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/io/output.hpp"
#include <cerrno>
#include <hdf5.h>

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

} // namespace

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
  bool ok = set >= 0 && (values.empty() || H5Dwrite(set, native<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT,
                                                    values.data()) >= 0);
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
  const hid_t access = serial_access();
  file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, access);
  H5Pclose(access);
  MF_REQUIRE(file_ >= 0, path, ": not a readable checkpoint file");
}

StateReader::~StateReader() {
  if (file_ >= 0) H5Fclose(file_);
}

bool StateReader::has(const std::string& name) const {
  return H5Lexists(file_, name.c_str(), H5P_DEFAULT) > 0;
}

template <class T> void StateReader::get(const std::string& name, std::vector<T>& values) const {
  MF_REQUIRE(has(name), path_, ": the checkpoint has no '", name,
             "' (written by another version of meshfree?)");
  const hid_t set = H5Dopen2(file_, name.c_str(), H5P_DEFAULT);
  const hid_t space = set >= 0 ? H5Dget_space(set) : -1;
  const hid_t type = set >= 0 ? H5Dget_type(set) : -1;
  const bool same_type = type >= 0 && H5Tequal(type, native<T>()) > 0;
  const hssize_t size = space >= 0 ? H5Sget_simple_extent_npoints(space) : -1;
  bool ok = set >= 0 && same_type && size >= 0;
  if (ok) {
    values.resize(static_cast<std::size_t>(size));
    ok = size == 0 || H5Dread(set, native<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) >= 0;
  }
  if (type >= 0) H5Tclose(type);
  if (space >= 0) H5Sclose(space);
  if (set >= 0) H5Dclose(set);
  MF_REQUIRE(ok, path_, ": cannot read '", name, "'",
             same_type ? std::string() : std::string(" (another type than expected)"));
}

void Unpacker::short_of(const std::string& name) {
  fail("checkpoint: the packed records end before '", name, "' (a damaged file?)");
}

void StateReader::wrong_size(const std::string& name, std::size_t size) const {
  fail(path_, ": '", name, "' holds ", size, " values where one was expected");
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
