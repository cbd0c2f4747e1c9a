#pragma once
// Run outputs (docs/architecture.md, "The run contract"): fields.h5 + fields.xmf (for ParaView),
// history.csv, line_<name>.csv and summary.json, written into a staging folder and put in place
// only when the run has completed, so a failed or killed run never replaces a good result.
#include "meshfree/core/types.hpp"
#include <map>
#include <memory>
#include <mpi.h>
#include <string>
#include <type_traits>
#include <vector>

namespace mf::io {

/// One field's values at a step (x, y, z of each point in turn for a vector): held by the step,
/// or read where they lie in an array that outlives the write (a particle field of an explicit
/// run), so that a step of a large body copies none of its arrays.
class FieldValues {
public:
  // Implicit: a step is often given its values as a vector.
  FieldValues(std::vector<double> values) : own_(std::move(values)) {} // NOLINT
  static FieldValues in_place(const double* data, std::size_t size) {
    FieldValues v({});
    v.view_ = data, v.size_ = size;
    return v;
  }
  const double* data() const { return view_ ? view_ : own_.data(); }
  std::size_t size() const { return view_ ? size_ : own_.size(); }
  /// The values held, for filling.
  std::vector<double>& held() { return own_; }

private:
  std::vector<double> own_;
  const double* view_ = nullptr;
  std::size_t size_ = 0;
};

/// Point fields of one output step: scalars (one value per point) and 2D vectors (written as
/// 3-component vectors with z = 0 so that ParaView can warp by them). With `positions` the step's
/// geometry is those points (the deformed configuration: x, y, z of each point in turn) and the
/// series' own points, the reference configuration, are the vector field reference_position.
struct FieldStep {
  double time = 0.0;
  std::vector<double> positions; // empty: the step's geometry is the series' points
  std::vector<std::pair<std::string, FieldValues>> scalars;
  std::vector<std::pair<std::string, std::vector<Vec2>>> vectors;
  std::vector<std::pair<std::string, FieldValues>> vectors3; // 3 values per point
};

/// Cells of the grid a field series lives on: none (the points alone, an XDMF Polyvertex grid),
/// or the elements of a finite-element mesh, one XDMF topology type ("Triangle",
/// "Quadrilateral", "Quadrilateral_8") with `nodes_per_cell` point indices per cell.
struct GridCells {
  std::string xdmf_type;
  int nodes_per_cell = 0;
  std::vector<int> connectivity;
};

/// This rank's share of a series' points when a run is spread over MPI ranks: the points
/// offset .. offset + (its count) of `total`, written collectively into one file (parallel HDF5
/// through MPI-IO), so that ParaView reads one fields.h5 whatever the number of ranks.
struct PointSlice {
  MPI_Comm comm = MPI_COMM_NULL;
  std::size_t offset = 0, total = 0;
  bool spread() const { return comm != MPI_COMM_NULL; }
};

class FieldSeries;

/// A file written piece by piece (history.csv as a run goes): created exclusively (never
/// through an existing name or link), each append() written out at once and checked, close()
/// flushing it to disk; a failed write stops with "<reason> writing <file>".
class OutputStream {
public:
  OutputStream(const std::string& path, std::string shown);
  ~OutputStream();
  OutputStream(const OutputStream&) = delete;
  OutputStream& operator=(const OutputStream&) = delete;
  void append(const std::string& text);
  void close();

private:
  int fd_ = -1;
  std::string shown_; // the name messages give
};

/// One CSV line (with its newline) of names, or of values with 12 significant digits.
std::string csv_line(const std::vector<std::string>& names);
std::string csv_line(const std::vector<double>& values);

/// The system's reason for an error number (strerror), lower-case, to stand in a sentence:
/// "no space left on device writing DIR/fields.h5".
std::string system_reason(int error);

/// Whether a write into an HDF5 file failed in this process. HDF5 1.10 cannot close a file whose
/// write failed: closing it, or the library's shutdown in MPI_Finalize, crashes (exit 139 after
/// the failure was recorded). A process where this is true ends without that shutdown.
bool hdf5_write_failed();
/// True when `name` is longer than `tail` and ends with it (".h5" of "fields.h5").
inline bool ends_with(const std::string& name, const std::string& tail) {
  return name.size() > tail.size() &&
         name.compare(name.size() - tail.size(), tail.size(), tail) == 0;
}

/// The output folder DIR of a run. Files are written into a staging folder of this run inside
/// DIR (`.meshfree-staging-<host>-<pid>`, created fresh and private), each created exclusively
/// and every write checked; commit() moves them into DIR only when the run has completed, so
/// the previous result stays whole until then (and DIR/failed, DIR/stopped of earlier runs go
/// then). A manifest (`.meshfree-manifest`) lists what a run put in DIR: the next run removes
/// or replaces those files and no others. A run that
/// failed or stopped keeps its files under DIR/failed or DIR/stopped instead (keep_unfinished).
/// Staging folders of earlier runs that were killed are removed on start, with a line saying so.
/// DIR is locked (flock on the folder) for the object's whole life: a second run into DIR while
/// one goes is refused. No link inside DIR is followed: manifests are read only as regular
/// files, and a listed file is removed only while it is the regular file (name, size, inode) its
/// run wrote.
class OutputDirectory {
public:
  /// DIR must be, or be creatable as, a directory this user can write into, and not locked by a
  /// live run (refusals name `option`, --out or --restart). Nothing is created until the first
  /// file is written (or open()), so a run that stops in its set-up leaves nothing behind.
  explicit OutputDirectory(std::string dir, std::string option = "--out");
  ~OutputDirectory();
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;
  const std::string& dir() const { return dir_; }
  /// Creates DIR if need be and this run's staging folder in it, where its files are until
  /// commit(); earlier runs' staging folders that were left by killed runs go.
  void open();
  bool opened() const { return !staging_.empty(); }
  /// Files written from now on are named prefix + file (a staged run's stages keep their own
  /// files side by side: preload_fields.h5 beside fields.h5).
  void set_prefix(std::string prefix) { prefix_ = std::move(prefix); }
  /// The name `file` is written under.
  std::string name_of(const std::string& file) const { return prefix_ + file; }
  /// DIR/name_of(file), as messages show it.
  std::string shown(const std::string& file) const;

  /// fields.h5 + fields.xmf with every step at once.
  void write_fields(const std::vector<Vec2>& points, const std::vector<FieldStep>& steps,
                    const GridCells& cells = {});
  /// CSV with a header row; every row has header.size() values.
  void write_csv(const std::string& file, const std::vector<std::string>& header,
                 const std::vector<std::vector<double>>& rows);
  void write_text(const std::string& file, const std::string& text);
  /// A file of this run written piece by piece; it is put in place with the others.
  std::unique_ptr<OutputStream> open_stream(const std::string& file);
  /// summary.json written again (a run that fails after writing it records the failure).
  void replace_summary(const std::string& text);
  /// The run completed: its files replace the previous result in DIR (summary.json last).
  void commit();
  /// The run failed or stopped: its files go to DIR/<status> (replacing an earlier run's kept
  /// files there, and nothing else), or stay in the staging folder when that name is taken.
  /// Returns where they are.
  std::string keep_unfinished(const std::string& status);
  /// The run was refused after it began writing (a checkpoint found not to be its own): its
  /// staging folder goes, and DIR is left as it was.
  void discard();

private:
  void lock();
  friend class FieldSeries;
  std::string temp_path(const std::string& file);
  void write_manifest(const std::string& folder) const;
  std::string dir_;
  std::string staging_;
  std::string prefix_;
  std::vector<std::string> pending_; // final file names
  bool finished_ = false;            // committed or kept
  std::string option_;               // the option that named DIR
  int lock_ = -1;                    // DIR, locked while this run goes
};

/// Fields written step by step as a run goes (long runs do not keep every step in memory):
/// <stem>.h5 holds the data, <stem>.xmf (written by close()) makes it a ParaView time series.
class FieldSeries {
public:
  FieldSeries(OutputDirectory& out, const std::string& stem, const std::vector<Vec2>& points,
              const GridCells& cells = {});
  /// Points in space: x, y, z of each point in turn.
  FieldSeries(OutputDirectory& out, const std::string& stem, const std::vector<double>& xyz);
  /// This rank's points of a series spread over the ranks of slice.comm; every rank constructs
  /// it, writes each step and closes it together. `out` is the output directory on the rank
  /// that has one (rank 0: it names the file and writes the .xmf), null on the others.
  FieldSeries(OutputDirectory* out, const std::string& stem, const std::vector<double>& xyz,
              const PointSlice& slice);
  ~FieldSeries();
  FieldSeries(const FieldSeries&) = delete;
  FieldSeries& operator=(const FieldSeries&) = delete;
  void add_step(const FieldStep& step);
  /// The steps from now on are on other points (and cells): an adapted cloud. The new grid is
  /// written as /geometry_<k>, and each step's grid in the .xmf names its own. One rank's series.
  void regrid(const std::vector<Vec2>& points, const GridCells& cells = {});
  /// Writes the .xmf; a series that was split is merged into one file first.
  void close();
  int steps() const { return steps_; }
  /// The steps so far become a file of their own, moved to `part` (a checkpoint keeps it), and
  /// the series goes on in a new file; close() merges the parts. Collective.
  void split(const std::string& part);
  /// What split() and the steps left: the parts' paths, the step count and the .xmf entries.
  /// Taken back on a restart, they replace whatever steps the series had written since it was
  /// opened (a staged run's replayed preload, which the parts hold already).
  /// The parts are found again by name in the folder of the checkpoint read back (the folder may
  /// have moved), and must be files of it.
  template <class Visit> void for_each_state(Visit&& visit) {
    visit("parts", parts_), visit("steps", steps_), visit("xdmf", xml_);
    if constexpr (std::decay_t<Visit>::loads) {
      parts_ = parts_in(parts_, visit.folder());
      renew_file({});
    }
  }

private:
  static std::string parts_in(const std::string& parts, const std::string& folder);
  void open(const std::vector<double>& xyz, const GridCells& cells);
  /// Writes the points (and cells) as `group` and makes them the grid of the next steps.
  void write_grid(const std::string& group, const std::vector<double>& xyz, const GridCells& cells);
  void create_file();
  void close_file();
  /// Closes the file, moves it to `keep_as` (drops it when empty) and opens a new one. Collective.
  void renew_file(const std::string& keep_as);
  void merge_parts();
  OutputDirectory* out_;
  PointSlice slice_;
  std::string stem_;
  std::string h5_;      // the data file as the .xmf names it
  std::string h5_temp_; // where it is written
  std::string parts_;   // paths of the parts split off, one per line
  long file_ = -1;      // hid_t
  // A write into the file failed all the same (an I/O error the room check cannot foresee):
  // HDF5 1.10 cannot close such a file, so it is not closed again here (hdf5_write_failed()).
  bool broken_ = false;
  std::size_t points_ = 0;
  int steps_ = 0;
  int grids_ = 0;         // grids written after the first (regrid)
  std::string topology_;  // the XDMF topology of every step
  std::string reference_; // the XDMF data item of the series' points
  std::string xml_;
};

/// Minimal JSON object builder for summary.json (keys keep insertion order).
class Json {
public:
  Json& set(const std::string& key, double v);
  Json& set(const std::string& key, long v);
  Json& set(const std::string& key, int v) { return set(key, static_cast<long>(v)); }
  Json& set(const std::string& key, const std::string& v);
  Json& set(const std::string& key, const char* v) { return set(key, std::string(v)); }
  Json& set(const std::string& key, bool v);
  Json& set(const std::string& key, const Json& object);
  Json& set(const std::string& key, const std::vector<double>& v);
  /// Appends every key of `other`, in its order.
  Json& merge(const Json& other);
  std::string str(int indent = 0) const;

private:
  std::vector<std::pair<std::string, std::string>> items_; // key, encoded value
  std::vector<std::pair<std::string, Json>> objects_;
  std::vector<std::pair<std::string, int>> order_; // key, 0 = scalar, 1 = object
};

} // namespace mf::io
