#include "meshfree/io/output.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/io/state_file.hpp"
#include "meshfree/spec/key_reader.hpp"
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <hdf5.h>
#include <iomanip>
#include <sstream>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/statvfs.h>

namespace mf::io {

namespace fs = std::filesystem;

std::string csv_line(const std::vector<std::string>& names) {
  std::string line;
  for (std::size_t i = 0; i < names.size(); ++i) line += (i ? "," : "") + names[i];
  return line + "\n";
}

std::string csv_line(const std::vector<double>& values) {
  std::ostringstream os;
  os << std::setprecision(12);
  for (std::size_t i = 0; i < values.size(); ++i) os << (i ? "," : "") << values[i];
  os << "\n";
  return os.str();
}

void OutputDirectory::write_csv(const std::string& file, const std::vector<std::string>& header,
                                const std::vector<std::vector<double>>& rows) {
  std::string text = csv_line(header);
  for (const auto& row : rows) {
    MF_ASSERT(row.size() == header.size());
    text += csv_line(row);
  }
  write_text(file, text);
}

namespace {
bool write_failed = false;
} // namespace

bool hdf5_write_failed() {
  return write_failed;
}

namespace {

/// Stops with what failed in an HDF5 file: the system's reason when the call left one (no space,
/// file too large), and the file's path.
[[noreturn]] void hdf5_failure(hid_t file, const std::string& what, int error) {
  char name[4096] = {};
  if (file < 0 || H5Fget_name(file, name, sizeof name - 1) < 0) std::strcpy(name, "an HDF5 file");
  write_failed = true;
  fail(error ? system_reason(error) : std::string("HDF5 failed"), " writing ", name, " (", what,
       ")");
}

/// An HDF5 object closed on every way out of a scope, a failed write's included: an object left
/// open keeps its file open after the file is closed, and HDF5 then writes it again while MPI
/// finalises, after the failure was recorded (a crash at exit under a file-size limit).
struct Closing {
  hid_t id;
  herr_t (*close)(hid_t);
  Closing(hid_t i, herr_t (*c)(hid_t)) : id(i), close(c) {}
  Closing(const Closing&) = delete;
  Closing& operator=(const Closing&) = delete;
  ~Closing() {
    if (id >= 0) close(id);
  }
};

/// A rows x cols dataset (1-D when cols is 1), creating the groups on its path. With a slice,
/// `rows` are this rank's rows offset .. offset + rows of slice.total, written collectively.
template <class T>
void write_dataset(hid_t file, const std::string& name, const T* data, hsize_t rows, hsize_t cols,
                   hid_t type, const PointSlice* slice = nullptr) {
  hsize_t dims[2] = {slice ? slice->total : rows, cols};
  const int rank = cols > 1 ? 2 : 1;
  const Closing space(H5Screate_simple(rank, dims, nullptr), H5Sclose);
  const Closing lcpl(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  H5Pset_create_intermediate_group(lcpl.id, 1);
  errno = 0;
  Closing set(H5Dcreate2(file, name.c_str(), type, space.id, lcpl.id, H5P_DEFAULT, H5P_DEFAULT),
              H5Dclose);
  if (set.id < 0) hdf5_failure(file, "creating dataset " + name, errno);
  herr_t status;
  if (!slice) {
    status = H5Dwrite(set.id, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
  } else {
    const hsize_t start[2] = {slice->offset, 0}, count[2] = {rows, cols};
    const Closing memory(H5Screate_simple(rank, count, nullptr), H5Sclose);
    if (rows == 0) {
      H5Sselect_none(space.id);
      H5Sselect_none(memory.id);
    } else {
      H5Sselect_hyperslab(space.id, H5S_SELECT_SET, start, nullptr, count, nullptr);
    }
    const Closing transfer(H5Pcreate(H5P_DATASET_XFER), H5Pclose);
    H5Pset_dxpl_mpio(transfer.id, H5FD_MPIO_COLLECTIVE);
    status = H5Dwrite(set.id, type, memory.id, space.id, transfer.id, data);
  }
  if (status < 0) hdf5_failure(file, "dataset " + name, errno);
  const hid_t written = set.id;
  set.id = -1; // closed here, where its failure is reported
  if (H5Dclose(written) < 0) hdf5_failure(file, "dataset " + name, errno);
}

void write_dataset(hid_t file, const std::string& name, const std::vector<double>& data,
                   hsize_t rows, hsize_t cols, const PointSlice* slice = nullptr) {
  write_dataset(file, name, data.data(), rows, cols, H5T_NATIVE_DOUBLE, slice);
}

std::string data_item(const std::string& h5, const std::string& set, std::size_t rows, int cols) {
  std::ostringstream os;
  os << "<DataItem Dimensions=\"" << rows;
  if (cols > 1) os << " " << cols;
  os << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << h5 << ":" << set
     << "</DataItem>";
  return os.str();
}

} // namespace

void OutputDirectory::write_fields(const std::vector<Vec2>& points,
                                   const std::vector<FieldStep>& steps, const GridCells& cells) {
  FieldSeries series(*this, "fields", points, cells);
  for (const FieldStep& step : steps) series.add_step(step);
  series.close();
}

namespace {

void write_int_dataset(hid_t file, const std::string& name, const std::vector<int>& data,
                       hsize_t rows, hsize_t cols, const PointSlice* slice = nullptr) {
  write_dataset(file, name, data.data(), rows, cols, H5T_NATIVE_INT, slice);
}

} // namespace

FieldSeries::FieldSeries(OutputDirectory& out, const std::string& stem,
                         const std::vector<Vec2>& points, const GridCells& cells)
    : out_(&out), stem_(stem), points_(points.size()) {
  const std::size_t n = points.size();
  std::vector<double> xyz(3 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) xyz[3 * i] = points[i].x(), xyz[3 * i + 1] = points[i].y();
  open(xyz, cells);
}

FieldSeries::FieldSeries(OutputDirectory& out, const std::string& stem,
                         const std::vector<double>& xyz)
    : out_(&out), stem_(stem), points_(xyz.size() / 3) {
  open(xyz, {});
}

FieldSeries::FieldSeries(OutputDirectory* out, const std::string& stem,
                         const std::vector<double>& xyz, const PointSlice& slice)
    : out_(out), slice_(slice), stem_(stem), points_(xyz.size() / 3) {
  open(xyz, {});
}

void FieldSeries::open(const std::vector<double>& xyz, const GridCells& cells) {
  // The rank with the output directory names the file; a spread series shares that name.
  std::string h5_temp = out_ ? out_->temp_path(stem_ + ".h5") : std::string();
  h5_ = out_ ? out_->name_of(stem_ + ".h5") : std::string();
  const PointSlice* slice = slice_.spread() ? &slice_ : nullptr;
  if (slice) {
    for (std::string* s : {&h5_temp, &h5_}) {
      int length = static_cast<int>(s->size());
      MPI_Bcast(&length, 1, MPI_INT, 0, slice->comm);
      s->resize(length);
      MPI_Bcast(s->data(), length, MPI_CHAR, 0, slice->comm);
    }
  }
  h5_temp_ = h5_temp;
  create_file();
  write_grid("/geometry", xyz, cells);
}

void FieldSeries::write_grid(const std::string& group, const std::vector<double>& xyz,
                             const GridCells& cells) {
  const std::string& h5 = h5_;
  const PointSlice* slice = slice_.spread() ? &slice_ : nullptr;
  const hid_t file = file_;
  const std::size_t n = points_, total = slice ? slice->total : n;
  write_dataset(file, group + "/coordinates", xyz, n, 3, slice);
  std::ostringstream g;
  if (cells.nodes_per_cell == 0) { // Polyvertex: point i is vertex i
    const std::size_t first = slice ? slice->offset : 0;
    std::vector<int> vertex(n);
    for (std::size_t i = 0; i < n; ++i) vertex[i] = static_cast<int>(first + i);
    write_int_dataset(file, group + "/vertices", vertex, n, 1, slice);
    g << "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << total
      << "\" NodesPerElement=\"1\">"
      << "<DataItem Dimensions=\"" << total
      << "\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">" << h5 << ":" << group
      << "/vertices</DataItem></Topology>\n";
  } else {
    MF_REQUIRE(!slice, stem_, ".h5: cells are written by one rank");
    const std::size_t ne = cells.connectivity.size() / cells.nodes_per_cell;
    write_int_dataset(file, group + "/cells", cells.connectivity, ne, cells.nodes_per_cell);
    g << "    <Topology TopologyType=\"" << cells.xdmf_type << "\" NumberOfElements=\"" << ne
      << "\">"
      << "<DataItem Dimensions=\"" << ne << " " << cells.nodes_per_cell
      << "\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">" << h5 << ":" << group
      << "/cells</DataItem></Topology>\n";
  }
  topology_ = g.str();
  reference_ = data_item(h5, group + "/coordinates", total, 3);
}

void FieldSeries::regrid(const std::vector<Vec2>& points, const GridCells& cells) {
  MF_REQUIRE(file_ >= 0, stem_, ".h5: the series is closed");
  MF_REQUIRE(!slice_.spread(), stem_, ".h5: a series spread over ranks keeps its points");
  points_ = points.size();
  std::vector<double> xyz(3 * points_, 0.0);
  for (std::size_t i = 0; i < points_; ++i)
    xyz[3 * i] = points[i].x(), xyz[3 * i + 1] = points[i].y();
  ++grids_;
  write_grid("/geometry_" + std::to_string(grids_), xyz, cells);
}

void FieldSeries::create_file() {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); // our messages say what failed, not HDF5's stack
  const hid_t access = H5Pcreate(H5P_FILE_ACCESS);
  if (slice_.spread()) H5Pset_fapl_mpio(access, slice_.comm, MPI_INFO_NULL);
  // Closing the file closes whatever of it is still open, so that nothing of a file whose write
  // failed is left for HDF5 to flush again when the library shuts down.
  H5Pset_fclose_degree(access, H5F_CLOSE_STRONG);
  // Exclusive: the staging folder is this run's own, so a file already there is an error.
  errno = 0;
  const hid_t file = H5Fcreate(h5_temp_.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, access);
  const int error = errno;
  H5Pclose(access);
  if (file < 0)
    fail("cannot create ", h5_temp_, error ? ": " + system_reason(error) : std::string());
  file_ = file;
}

FieldSeries::~FieldSeries() {
  if (file_ >= 0 && !broken_) H5Fclose(file_);
}

namespace {
std::string attribute(const std::string& name, const char* type, const std::string& item) {
  return "    <Attribute Name=\"" + name + "\" AttributeType=\"" + type + "\" Center=\"Node\">" +
         item + "</Attribute>\n";
}

std::string geometry(const std::string& item) {
  return "    <Geometry GeometryType=\"XYZ\">" + item + "</Geometry>\n";
}

/// A step of `bytes` must fit under the file-size limit (ulimit -f) and in the free space of the
/// disk before HDF5 writes it: HDF5 1.10 cannot close a file whose write failed, so the two
/// usual failures are found here, while the file is still whole (it is kept, closed, in failed/).
/// The margin holds HDF5's metadata and what closing the file writes.
void require_room(hid_t file, const std::string& path, double bytes) {
  const double need = 1.05 * bytes + 1024.0 * 1024.0;
  hsize_t size = 0;
  H5Fget_filesize(file, &size);
  rlimit limit{};
  if (getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY &&
      static_cast<double>(size) + need > static_cast<double>(limit.rlim_cur))
    fail(system_reason(EFBIG), " writing ", path, " (the next step, about ", need,
         " bytes, would pass the file-size limit of ", limit.rlim_cur, " bytes)");
  struct statvfs disk {};
  if (statvfs(path.c_str(), &disk) == 0 &&
      need > static_cast<double>(disk.f_bavail) * static_cast<double>(disk.f_frsize))
    fail(system_reason(ENOSPC), " writing ", path, " (the next step, about ", need, " bytes)");
}

/// Stops the run at a field value that is not a number, naming the field, the point and the time.
void require_finite(const std::string& stem, const std::string& field, const double* v,
                    std::size_t count, int per_point, double time) {
  for (std::size_t k = 0; k < count; ++k)
    MF_REQUIRE(std::isfinite(v[k]), stem, ": field ", field, " is ", v[k], " at point ",
               k / per_point, " at t = ", time);
}
} // namespace

void FieldSeries::add_step(const FieldStep& step) {
  MF_REQUIRE(file_ >= 0, stem_, ".h5: the series is closed");
  for (const auto& [name, v] : step.scalars)
    require_finite(stem_, name, v.data(), v.size(), 1, step.time);
  for (const auto& [name, v] : step.vectors)
    require_finite(stem_, name, v.empty() ? nullptr : v[0].data(), 2 * v.size(), 2, step.time);
  for (const auto& [name, v] : step.vectors3)
    require_finite(stem_, name, v.data(), v.size(), 3, step.time);
  require_finite(stem_, "position", step.positions.data(), step.positions.size(), 3, step.time);
  {
    std::size_t per_point =
        step.scalars.size() + 3 * step.vectors.size() + 3 * step.vectors3.size();
    if (!step.positions.empty()) per_point += 3;
    const double total = static_cast<double>(slice_.spread() ? slice_.total : points_);
    require_room(file_, h5_temp_, 8.0 * total * static_cast<double>(per_point));
  }
  const std::string& h5 = h5_;
  const std::size_t n = points_;
  const PointSlice* slice = slice_.spread() ? &slice_ : nullptr;
  const std::size_t total = slice ? slice->total : n;
  std::ostringstream group;
  group << "/step_" << std::setw(6) << std::setfill('0') << steps_;
  // A dataset of this step, 1 or 3 values per point, as an XDMF data item.
  const auto put = [&](const std::string& name, const FieldValues& v, int per) {
    MF_ASSERT(v.size() == per * n);
    try {
      write_dataset(file_, group.str() + "/" + name, v.data(), n, per, H5T_NATIVE_DOUBLE, slice);
    } catch (const Error&) {
      broken_ = true;
      throw;
    }
    return data_item(h5, group.str() + "/" + name, total, per);
  };
  std::ostringstream x;
  x << "   <Grid Name=\"step_" << steps_ << "\" GridType=\"Uniform\">\n"
    << "    <Time Value=\"" << std::setprecision(12) << step.time << "\"/>\n"
    << topology_;
  if (step.positions.empty()) {
    x << geometry(reference_);
  } else {
    const auto& xyz = step.positions;
    x << geometry(put("coordinates", FieldValues::in_place(xyz.data(), xyz.size()), 3));
    x << attribute("reference_position", "Vector", reference_);
  }
  for (const auto& [name, v] : step.scalars) x << attribute(name, "Scalar", put(name, v, 1));
  for (const auto& [name, v] : step.vectors) {
    std::vector<double> d(3 * v.size(), 0.0);
    for (std::size_t i = 0; i < v.size(); ++i) d[3 * i] = v[i].x(), d[3 * i + 1] = v[i].y();
    x << attribute(name, "Vector", put(name, FieldValues(std::move(d)), 3));
  }
  for (const auto& [name, v] : step.vectors3) x << attribute(name, "Vector", put(name, v, 3));
  x << "   </Grid>\n";
  xml_ += x.str();
  ++steps_;
}

void FieldSeries::close_file() {
  // The data reach the disk here at the latest, so this is where a full disk shows.
  errno = 0;
  if (H5Fflush(file_, H5F_SCOPE_GLOBAL) < 0) {
    broken_ = true;
    hdf5_failure(file_, "flushing", errno);
  }
  char name[4096] = {};
  H5Fget_name(file_, name, sizeof name - 1);
  errno = 0;
  const herr_t closed = H5Fclose(file_);
  file_ = -1;
  if (closed < 0)
    fail(errno ? system_reason(errno) : std::string("HDF5 failed"), " writing ", name,
         " (closing)");
}

void FieldSeries::renew_file(const std::string& keep_as) {
  MF_REQUIRE(file_ >= 0, stem_, ".h5: the series is closed");
  close_file();
  if (out_) { // the rank that names the file moves or drops it
    std::error_code ec;
    if (keep_as.empty())
      std::filesystem::remove(h5_temp_, ec);
    else
      std::filesystem::rename(h5_temp_, keep_as, ec);
    MF_REQUIRE(!ec, keep_as, ": cannot keep the field steps so far: ", ec.message());
  }
  if (slice_.spread()) MPI_Barrier(slice_.comm);
  create_file();
}

std::string FieldSeries::parts_in(const std::string& parts, const std::string& folder) {
  std::istringstream in(parts);
  std::string found;
  for (std::string line; std::getline(in, line);) {
    const std::string name = std::filesystem::path(line).filename().string();
    const std::size_t at = name.rfind(".part-");
    const std::string k = at == std::string::npos ? "" : name.substr(at + 6);
    const bool named = at != std::string::npos && at > 0 && ends_with(k, ".h5") &&
                       std::all_of(k.begin(), k.end() - 3, [](char c) { return std::isdigit(c); });
    const std::string path = (std::filesystem::path(folder) / name).string();
    struct stat st {};
    if (!named || ::lstat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode))
      refuse_checkpoint("the checkpoint's field steps name " + spec::one_line(line, 80) +
                        ", not a file of " + folder);
    found += path + "\n";
  }
  return found;
}

void FieldSeries::split(const std::string& part) {
  renew_file(part);
  parts_ += part + "\n";
}

namespace {

/// Copies every step group of `from` into `to`, and its geometry when `to` has none yet.
void copy_steps(hid_t to, const std::string& from) {
  const hid_t source = H5Fopen(from.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  MF_REQUIRE(source >= 0, from, ": cannot read the field steps it holds");
  std::vector<std::string> names;
  H5Literate(
      source, H5_INDEX_NAME, H5_ITER_INC, nullptr,
      [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
        static_cast<std::vector<std::string>*>(data)->emplace_back(name);
        return 0;
      },
      &names);
  for (const std::string& name : names) {
    if (name.rfind("geometry", 0) != 0 && name.rfind("step_", 0) != 0) continue;
    if (name == "geometry" && H5Lexists(to, name.c_str(), H5P_DEFAULT) > 0) continue;
    errno = 0;
    if (H5Ocopy(source, name.c_str(), to, name.c_str(), H5P_DEFAULT, H5P_DEFAULT) < 0) {
      const int error = errno;
      H5Fclose(source);
      hdf5_failure(to, "copying /" + name + " from " + from, error);
    }
  }
  H5Fclose(source);
}

} // namespace

void FieldSeries::merge_parts() {
  // On the rank that names the file; the others have closed theirs.
  if (!out_) return;
  const std::string last = h5_temp_ + ".last";
  std::error_code ec;
  std::filesystem::rename(h5_temp_, last, ec);
  MF_REQUIRE(!ec, h5_temp_, ": cannot merge the field steps: ", ec.message());
  errno = 0;
  const Closing access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  H5Pset_fclose_degree(access.id, H5F_CLOSE_STRONG); // as create_file's
  const hid_t merged = H5Fcreate(h5_temp_.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, access.id);
  if (merged < 0) hdf5_failure(merged, "creating " + h5_temp_, errno);
  std::istringstream parts(parts_);
  for (std::string part; std::getline(parts, part);) copy_steps(merged, part);
  copy_steps(merged, last);
  file_ = merged;
  close_file();
  std::filesystem::remove(last, ec);
}

void FieldSeries::close() {
  if (file_ < 0) return;
  close_file();
  if (!parts_.empty()) {
    if (slice_.spread()) MPI_Barrier(slice_.comm);
    merge_parts();
  }
  std::ostringstream x;
  x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
    << "  <Grid Name=\"" << stem_ << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n"
    << xml_ << "  </Grid>\n </Domain>\n</Xdmf>\n";
  if (out_) out_->write_text(stem_ + ".xmf", x.str());
}

namespace {
std::string encode(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\')
      out += '\\', out += c;
    else if (c == '\n')
      out += "\\n";
    else if (static_cast<unsigned char>(c) < 0x20)
      out += ' ';
    else
      out += c;
  }
  return out + "\"";
}
std::string encode(double v) {
  if (!std::isfinite(v)) return "null";
  std::ostringstream os;
  os << std::setprecision(12) << v;
  return os.str();
}
} // namespace

Json& Json::set(const std::string& key, double v) {
  items_.emplace_back(key, encode(v));
  order_.emplace_back(key, 0);
  return *this;
}
Json& Json::set(const std::string& key, long v) {
  items_.emplace_back(key, std::to_string(v));
  order_.emplace_back(key, 0);
  return *this;
}
Json& Json::set(const std::string& key, const std::string& v) {
  items_.emplace_back(key, encode(v));
  order_.emplace_back(key, 0);
  return *this;
}
Json& Json::set(const std::string& key, bool v) {
  items_.emplace_back(key, v ? "true" : "false");
  order_.emplace_back(key, 0);
  return *this;
}
Json& Json::set(const std::string& key, const std::vector<double>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + encode(v[i]);
  items_.emplace_back(key, s + "]");
  order_.emplace_back(key, 0);
  return *this;
}
Json& Json::set(const std::string& key, const Json& object) {
  objects_.emplace_back(key, object);
  order_.emplace_back(key, 1);
  return *this;
}

Json& Json::merge(const Json& other) {
  std::size_t si = 0, oi = 0;
  for (const auto& [key, kind] : other.order_) {
    if (kind == 0)
      items_.push_back(other.items_[si++]);
    else
      objects_.push_back(other.objects_[oi++]);
    order_.emplace_back(key, kind);
  }
  return *this;
}

std::string Json::str(int indent) const {
  const std::string pad(indent + 2, ' ');
  std::string out = "{\n";
  std::size_t si = 0, oi = 0;
  for (std::size_t k = 0; k < order_.size(); ++k) {
    out += pad + encode(order_[k].first) + ": ";
    out += order_[k].second == 0 ? items_[si++].second : objects_[oi++].second.str(indent + 2);
    out += k + 1 < order_.size() ? ",\n" : "\n";
  }
  return out + std::string(indent, ' ') + "}";
}

} // namespace mf::io
