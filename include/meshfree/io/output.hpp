#pragma once
// Run outputs (DESIGN.md, "the run contract"): fields.h5 + fields.xmf (ParaView reads the .xmf),
// history.csv, line_<name>.csv and summary.json. Files are written under temporary names and
// renamed only when the run has succeeded, so a failed run never leaves a result that looks good.
#include "meshfree/core/types.hpp"
#include <map>
#include <mpi.h>
#include <string>
#include <vector>

namespace mf::io {

/// Point fields of one output step: scalars (one value per point) and 2D vectors (written as
/// 3-component vectors with z = 0 so that ParaView can warp by them).
struct FieldStep {
  double time = 0.0;
  std::vector<std::pair<std::string, std::vector<double>>> scalars;
  std::vector<std::pair<std::string, std::vector<Vec2>>> vectors;
  std::vector<std::pair<std::string, std::vector<double>>> vectors3; // 3 values per point
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

/// Collects output files in a directory; nothing appears under the final names until commit().
class OutputDirectory {
public:
  explicit OutputDirectory(std::string dir);
  ~OutputDirectory(); // removes uncommitted temporary files
  const std::string& dir() const { return dir_; }
  /// Files written from now on are named prefix + file (a staged run's stages keep their own
  /// files side by side: preload_fields.h5 beside fields.h5).
  void set_prefix(std::string prefix) { prefix_ = std::move(prefix); }
  /// The name `file` is written under.
  std::string name_of(const std::string& file) const { return prefix_ + file; }

  /// Removes results of an earlier run (fields.*, history.csv, summary.json, line_*.csv).
  void clear_previous() const;
  /// fields.h5 + fields.xmf with every step at once.
  void write_fields(const std::vector<Vec2>& points, const std::vector<FieldStep>& steps,
                    const GridCells& cells = {});
  /// CSV with a header row; every row has header.size() values.
  void write_csv(const std::string& file, const std::vector<std::string>& header,
                 const std::vector<std::vector<double>>& rows);
  void write_text(const std::string& file, const std::string& text);
  /// Renames every temporary file to its final name.
  void commit();

private:
  friend class FieldSeries;
  std::string temp_path(const std::string& file);
  std::string dir_;
  std::string prefix_;
  std::vector<std::string> pending_; // final file names
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
  void close();
  int steps() const { return steps_; }

private:
  void open(const std::vector<double>& xyz, const GridCells& cells);
  OutputDirectory* out_;
  PointSlice slice_;
  std::string stem_;
  std::string h5_; // the data file as the .xmf names it
  long file_ = -1; // hid_t
  std::size_t points_ = 0;
  int steps_ = 0;
  std::string grid_; // the XDMF topology and geometry of every step
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
