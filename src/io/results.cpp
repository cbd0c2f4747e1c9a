#include "meshfree/io/results.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/io/state_file.hpp"
#include <algorithm>
#include <cmath>

namespace mf::io {

void History::append(std::vector<double> row) {
  MF_ASSERT(row.size() == columns_.size());
  // A value that is not a number is never a result: the run fails, naming where it appeared.
  for (std::size_t c = 0; c < row.size(); ++c)
    MF_REQUIRE(std::isfinite(row[c]), "history: ", columns_[c], " is ", row[c], " in row ",
               rows_.size() + 1, " (", columns_[0], " = ", row[0], ")");
  append_with_gaps(std::move(row));
}

void History::append_with_gaps(std::vector<double> row) {
  MF_ASSERT(row.size() == columns_.size());
  if (stream_) stream_->append(csv_line(row));
  rows_.push_back(std::move(row));
  if (also_) also_(rows_.back());
}

void History::stream_to(OutputDirectory& out, const std::string& file) {
  std::string text = csv_line(columns_);
  for (const auto& row : rows_) text += csv_line(row);
  stream_ = out.open_stream(file);
  stream_->append(text);
}

std::vector<double> History::flat() const {
  std::vector<double> v;
  v.reserve(rows_.size() * columns_.size());
  for (const auto& row : rows_) v.insert(v.end(), row.begin(), row.end());
  return v;
}

void History::restore(const std::vector<double>& flat) {
  const std::size_t n = columns_.size();
  if (n == 0 || flat.size() % n != 0)
    refuse_checkpoint("the checkpoint's history holds " + std::to_string(flat.size()) +
                      " values, not rows of " + std::to_string(n) + " columns");
  MF_REQUIRE(rows_.empty(), "history: rows restored after some were appended");
  std::string text;
  for (std::size_t k = 0; k < flat.size(); k += n) {
    rows_.emplace_back(flat.begin() + k, flat.begin() + k + n);
    text += csv_line(rows_.back());
    if (also_) also_(rows_.back());
  }
  if (stream_) stream_->append(text);
}

double History::max_abs(std::size_t c) const {
  double v = 0.0;
  for (const auto& row : rows_) v = std::max(v, std::abs(row[c]));
  return v;
}

void History::write(OutputDirectory& out, const std::string& file) const {
  if (stream_)
    stream_->close();
  else
    out.write_csv(file, columns_, rows_);
}

void Summary::set_status(std::string status, std::string stop_reason) {
  status_ = std::move(status);
  stop_reason_ = std::move(stop_reason);
}

Json& Summary::section(const std::string& name) {
  for (auto& [key, json] : sections_)
    if (key == name) return *json;
  sections_.emplace_back(name, std::make_unique<Json>());
  return *sections_.back().second;
}

std::string Summary::str(const PhaseTimer& timer) const {
  Json times;
  for (const auto& [name, seconds] : timer.phases()) times.set(name, seconds);
  const Json* extra_times = nullptr;
  for (const auto& [key, json] : sections_)
    if (key == "time_s") extra_times = json.get();
  if (extra_times) times.merge(*extra_times);
  times.set("total", timer.total());
  Json kernel; // this rank's, like the times
  for (const auto& [name, seconds] : timer.kernel_phases()) kernel.set(name, seconds);
  const auto set_times = [&](Json& j) {
    j.set("time_s", times);
    if (!timer.kernel_phases().empty()) j.set("kernel_time_s", kernel);
  };

  Json j;
  j.set("problem", header_.problem).set("description", header_.description);
  j.set("units", header_.units);
  j.set("analysis", header_.analysis);
  if (!header_.method.empty()) j.set("method", header_.method);
  j.set("status", status_);
  if (!stop_reason_.empty()) j.set("stop_reason", stop_reason_);
  j.merge(top_);
  bool timed = false;
  for (const auto& [key, json] : sections_) {
    if (key == "time_s") continue;
    if (key == "results") set_times(j), timed = true;
    j.set(key, *json);
  }
  if (!timed) set_times(j);
  return j.str() + "\n";
}

void Summary::write(OutputDirectory& out, const PhaseTimer& timer) const {
  out.write_text("summary.json", str(timer));
}

FieldOutput::FieldOutput(OutputDirectory* out, const std::string& stem,
                         const std::vector<double>& xyz)
    : points_(xyz.size() / 3) {
  if (out) series_ = std::make_unique<FieldSeries>(*out, stem, xyz);
}

FieldOutput::FieldOutput(OutputDirectory* out, const std::string& stem,
                         const std::vector<double>& xyz, const PointSlice& slice)
    : points_(xyz.size() / 3) {
  if (!slice.spread()) {
    if (out) series_ = std::make_unique<FieldSeries>(*out, stem, xyz);
    return;
  }
  // Every rank opens the file together; whether there is one is decided on rank 0.
  int open = out ? 1 : 0;
  MPI_Bcast(&open, 1, MPI_INT, 0, slice.comm);
  if (open) series_ = std::make_unique<FieldSeries>(out, stem, xyz, slice);
}

FieldOutput::FieldOutput(OutputDirectory* out, const std::string& stem,
                         const std::vector<Vec2>& points, const GridCells& cells)
    : points_(points.size()) {
  if (out) series_ = std::make_unique<FieldSeries>(*out, stem, points, cells);
}

void FieldOutput::scalar(std::string name, Fill fill) {
  scalars_.push_back({std::move(name), std::move(fill), nullptr});
}

void FieldOutput::vector(std::string name, Fill fill) {
  vectors_.push_back({std::move(name), std::move(fill), nullptr});
}

void FieldOutput::vector2(std::string name, Fill2 fill) {
  vectors2_.emplace_back(std::move(name), std::move(fill));
}

void FieldOutput::write(double t) {
  if (!series_) return;
  FieldStep step;
  step.time = t;
  if (positions_) {
    positions_(step.positions);
    MF_ASSERT(step.positions.size() == 3 * points_);
  }
  for (const Field& f : scalars_) step.scalars.emplace_back(f.name, values_of(f, 1));
  for (const Field& f : vectors_) step.vectors3.emplace_back(f.name, values_of(f, 3));
  for (const auto& [name, fill] : vectors2_) {
    step.vectors.emplace_back(name, std::vector<Vec2>());
    fill(step.vectors.back().second);
    MF_ASSERT(step.vectors.back().second.size() == points_);
  }
  series_->add_step(step);
}

FieldValues FieldOutput::values_of(const Field& f, std::size_t per) const {
  const std::size_t count = per * points_;
  if (f.array) {
    MF_ASSERT(f.array->size() >= count);
    return FieldValues::in_place(f.array->data(), count);
  }
  FieldValues v(std::vector<double>{});
  f.fill(v.held());
  MF_ASSERT(v.size() == count);
  return v;
}

void FieldOutput::regrid(const std::vector<Vec2>& points, const GridCells& cells) {
  points_ = points.size();
  if (series_) series_->regrid(points, cells);
}

void FieldOutput::close() {
  if (series_) series_->close();
}

} // namespace mf::io
