#pragma once
// What every analysis writes (docs/architecture.md, "The run contract"): summary.json (a
// header naming the problem and the analysis, the status and why a run stopped, named sections
// such as counts and results, and the wall time of each phase), history.csv (named columns, one
// row per recorded instant), and field series whose fields are registered once by name and kind
// and sampled at every output step, for particles, nodes and quadrature points alike.
#include "meshfree/core/timer.hpp"
#include "meshfree/io/output.hpp"
#include <functional>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace mf::io {

/// history.csv: named columns, rows appended as the run goes.
class History {
public:
  History() = default;
  explicit History(std::vector<std::string> columns) : columns_(std::move(columns)) {}
  void add_column(std::string name) { columns_.push_back(std::move(name)); }
  const std::vector<std::string>& columns() const { return columns_; }
  /// Appends a row with one value per column; a value that is not finite stops the run with
  /// the column and the row.
  void append(std::vector<double> row);
  /// Appends a row whose NaN mark values that do not apply (a staged run's preload rows have no
  /// energies of the explicit stage).
  void append_with_gaps(std::vector<double> row);
  const std::vector<std::vector<double>>& rows() const { return rows_; }
  bool empty() const { return rows_.empty(); }
  const std::vector<double>& last() const { return rows_.back(); }
  /// Largest |value| of column c over every row (0 without rows).
  double max_abs(std::size_t c) const;
  /// From now on each row goes to `file` of `out` as it is appended (the rows so far at once),
  /// so that a run that is killed keeps its history up to then in its staging folder.
  void stream_to(OutputDirectory& out, const std::string& file = "history.csv");
  /// Writes `file`; a streamed history is finished instead (flushed to disk and closed).
  void write(OutputDirectory& out, const std::string& file = "history.csv") const;
  /// From now on every row appended (or restored) is also handed to `also`: a staged run's
  /// history gets each row of its explicit stage as it is recorded.
  void also_to(std::function<void(const std::vector<double>&)> also) { also_ = std::move(also); }
  /// The rows so far as one array "rows" (a checkpoint keeps them; loading restores them).
  template <class Visit> void for_each_state(Visit&& visit) {
    std::vector<double> rows = std::decay_t<Visit>::loads ? std::vector<double>() : flat();
    visit("rows", rows);
    if constexpr (std::decay_t<Visit>::loads) restore(rows);
  }

private:
  /// The rows so far, row after row.
  std::vector<double> flat() const;
  /// Rows taken back from flat() in place of any appended so far (streamed, when streaming).
  void restore(const std::vector<double>& flat);
  std::vector<std::string> columns_;
  std::vector<std::vector<double>> rows_;
  std::shared_ptr<OutputStream> stream_; // while the rows are streamed
  std::function<void(const std::vector<double>&)> also_;
};

/// The first keys of summary.json; an empty method is left out.
struct RunHeader {
  std::string problem, description, units, analysis, method;
};

/// summary.json: the header, "status" (and "stop_reason" when a run stopped early), top-level
/// values (ranks, threads), then the sections in the order they were first asked for, with
/// "time_s" (each phase of the timer, anything added to section("time_s"), and "total") just
/// before "results".
class Summary {
public:
  explicit Summary(RunHeader header) : header_(std::move(header)) {}
  void set_status(std::string status, std::string stop_reason = {});
  /// A value written after the status.
  template <class T> Summary& set(const std::string& key, const T& value) {
    top_.set(key, value);
    return *this;
  }
  /// The section `name`, created empty at its first use.
  Json& section(const std::string& name);
  std::string str(const PhaseTimer& timer) const;
  void write(OutputDirectory& out, const PhaseTimer& timer) const;

private:
  RunHeader header_;
  std::string status_ = "completed", stop_reason_;
  Json top_;
  std::vector<std::pair<std::string, std::unique_ptr<Json>>> sections_;
};

/// A series of fields on one point set (fields.h5/.xmf, or another stem for quadrature points),
/// each field registered once by name and kind with the function that fills its values; write()
/// samples every field at one instant. Without an output directory nothing is written.
class FieldOutput {
public:
  using Fill = std::function<void(std::vector<double>&)>;
  using Fill2 = std::function<void(std::vector<Vec2>&)>;
  /// Points in space, x, y, z of each in turn.
  FieldOutput(OutputDirectory* out, const std::string& stem, const std::vector<double>& xyz);
  /// This rank's points of a series spread over MPI ranks (see FieldSeries); written on every
  /// rank of slice.comm, `out` being the directory of the rank that has one.
  FieldOutput(OutputDirectory* out, const std::string& stem, const std::vector<double>& xyz,
              const PointSlice& slice);
  /// Points of a plane, with the cells of a mesh if any.
  FieldOutput(OutputDirectory* out, const std::string& stem, const std::vector<Vec2>& points,
              const GridCells& cells = {});
  // The fills of arrays refer to this object: it stays where it was made.
  FieldOutput(const FieldOutput&) = delete;
  FieldOutput& operator=(const FieldOutput&) = delete;
  /// One value per point.
  void scalar(std::string name, Fill fill);
  /// Three values per point.
  void vector(std::string name, Fill fill);
  /// A plane vector per point (written with z = 0).
  void vector2(std::string name, Fill2 fill);
  /// The points' current positions (x, y, z of each in turn): each step's geometry is then the
  /// deformed configuration, and the points the series was made with are the vector field
  /// reference_position (FieldStep::positions).
  void positions(Fill fill) { positions_ = std::move(fill); }
  /// The first points() values (three per point for a vector) of an array that lives as long
  /// as this series (it may grow: it is read at each write); its elements convert to double.
  template <class T> void scalar(std::string name, const std::vector<T>& a) {
    add(scalars_, std::move(name), a, 1);
  }
  template <class T> void vector(std::string name, const std::vector<T>& a) {
    add(vectors_, std::move(name), a, 3);
  }
  std::size_t points() const { return points_; }
  bool active() const { return series_ != nullptr; }
  /// The steps from now on are on other points (FieldSeries::regrid); the fields' fills then
  /// give values for these.
  void regrid(const std::vector<Vec2>& points, const GridCells& cells = {});
  /// Every registered field at time t.
  void write(double t);
  /// See FieldSeries::split and FieldSeries::for_each_state (nothing without a series).
  void split(const std::string& part) {
    if (series_) series_->split(part);
  }
  template <class Visit> void for_each_state(Visit&& visit) {
    if (series_) series_->for_each_state(visit);
  }
  void close();

private:
  /// A field filled at each write, or an array of doubles written where it lies.
  struct Field {
    std::string name;
    Fill fill;
    const std::vector<double>* array = nullptr;
  };
  template <class T>
  void add(std::vector<Field>& to, std::string name, const std::vector<T>& a, std::size_t per) {
    if constexpr (std::is_same_v<T, double>) {
      to.push_back({std::move(name), nullptr, &a});
    } else {
      // The count is read at each write: regrid() changes it.
      to.push_back({std::move(name),
                    [&a, per, this](std::vector<double>& out) {
                      out.assign(a.begin(), a.begin() + per * points_);
                    },
                    nullptr});
    }
  }
  /// The field's values at this write.
  FieldValues values_of(const Field& f, std::size_t per) const;
  std::unique_ptr<FieldSeries> series_;
  std::size_t points_ = 0;
  std::vector<Field> scalars_, vectors_;
  std::vector<std::pair<std::string, Fill2>> vectors2_;
  Fill positions_;
};

} // namespace mf::io
