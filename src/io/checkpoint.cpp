#include "meshfree/io/checkpoint.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/core/run_bounds.hpp"
#include "meshfree/core/timer.hpp"
#include "meshfree/core/version.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/spec/key_reader.hpp"
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <iostream>
#include <map>
#include <mpi.h>
#include <omp.h>
#include <sstream>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace mf::io {

namespace fs = std::filesystem;

namespace {

constexpr const char* kMarker = "checkpoint.txt";
constexpr const char* kLock = ".lock";
// The layout of a checkpoint's files: a checkpoint of another layout is refused, not misread.
constexpr long kFormat = 3;

std::string state_name(long generation, int rank) {
  return "state-" + std::to_string(generation) + "." + std::to_string(rank) + ".h5";
}

/// Flushes a file (or a folder's entries) to disk; a failure names the path.
void sync_path(const std::string& path, bool folder) {
  const int fd = ::open(path.c_str(), (folder ? O_RDONLY | O_DIRECTORY : O_RDONLY) | O_CLOEXEC);
  if (fd < 0) fail("cannot open ", path, " to flush it: ", system_reason(errno));
  const bool ok = ::fsync(fd) == 0 || errno == EINVAL || errno == EROFS;
  const int error = errno;
  ::close(fd);
  if (!ok) fail(system_reason(error), " writing ", path);
}

/// The names meshfree writes into a checkpoint folder (and only those are ever removed).
bool ours(const std::string& name) {
  return name == kMarker || name == std::string(kMarker) + ".new" || name == kLock ||
         (name.rfind("state-", 0) == 0 && ends_with(name, ".h5")) ||
         (name.find(".part-") != std::string::npos && ends_with(name, ".h5"));
}

void remove_ours(const fs::path& folder, const std::function<bool(const std::string&)>& which) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    if (ours(name) && which(name) && fs::is_regular_file(fs::symlink_status(entry.path())))
      fs::remove(entry.path(), ec);
  }
}

std::string settings_text(const spec::ProblemSettings& s) {
  std::string text;
  for (const auto& [key, value] : s) text += key + "\t" + value + "\n";
  return text;
}

std::map<std::string, std::string> settings_map(const std::string& text) {
  std::map<std::string, std::string> m;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t tab = line.find('\t');
    if (tab != std::string::npos) m[line.substr(0, tab)] = line.substr(tab + 1);
  }
  return m;
}

/// The problem's identity: a hash of every setting a restart may not change (its physics and
/// discretisation).
long identity(const spec::ProblemSettings& settings);

/// True when `path` is a folder itself, not a link to one.
bool real_folder(const fs::path& path) {
  struct stat st {};
  return ::lstat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}

/// The generation checkpoint.txt names, or 0: read from a regular file only (never through a
/// link, never blocking on a FIFO), and only as publish_generation writes it ("generation 12e3"
/// names none, not generation 12).
long marked_generation(const fs::path& folder) {
  const int fd = ::open((folder / kMarker).c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return 0;
  struct stat st {};
  char text[64] = {};
  const bool ok =
      ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && ::read(fd, text, sizeof text - 1) > 0;
  ::close(fd);
  std::istringstream in(ok ? text : "");
  std::string word;
  long generation = 0;
  const bool named = in >> word >> generation && word == "generation" && generation > 0;
  return named && (in >> std::ws).eof() ? generation : 0;
}

} // namespace

bool restart_may_change(const std::string& path) {
  // A staged run's keys are those of its stages: stages.<k>.time.end and so on.
  std::string key = path;
  if (key.rfind("stages.", 0) == 0) {
    const std::size_t dot = key.find('.', 7);
    key = dot == std::string::npos ? std::string() : key.substr(dot + 1);
  }
  return key == "time.end" || key == "output.checkpoint_every" ||
         (key.rfind("output.", 0) == 0 && ends_with(key, "_interval") &&
          key.find('.', 7) == std::string::npos);
}

namespace {

long identity(const spec::ProblemSettings& settings) {
  std::string text;
  for (const auto& [key, value] : settings)
    if (!restart_may_change(key)) text += key + "\t" + value + "\n";
  return static_cast<long>(checksum(text.data(), text.size()));
}

/// The first key that differs between the checkpoint's settings and this run's, but for those a
/// restart may change: an input error naming it.
void compare_settings(const std::string& dir, const std::map<std::string, std::string>& before,
                      const spec::ProblemSettings& settings) {
  const std::map<std::string, std::string> now(settings.begin(), settings.end());
  for (const auto* side : {&before, &now})
    for (const auto& [key, value] : *side) {
      const auto b = before.find(key), n = now.find(key);
      const std::string was = b == before.end() ? "(not given)" : spec::one_line(b->second, 40);
      const std::string is = n == now.end() ? "(not given)" : spec::one_line(n->second, 40);
      if (was != is && !restart_may_change(key))
        refuse_checkpoint("--restart " + dir + ": " + spec::one_line(key) +
                          " changed since the checkpoint (" + was + " then, " + is +
                          " now); a restart may change only time.end and the output intervals");
    }
}

/// The instant and step a checkpoint holds: finite, inside the run (0 <= t <= end), and
/// consistent with each other (a step taken for every instant after the start).
void check_instant(const std::string& dir, const Restart& r, double end_time) {
  const std::string where = "--restart " + dir + ": the checkpoint's ";
  if (!std::isfinite(r.time) || r.time < 0.0 || r.time > end_time * (1 + 1e-12))
    refuse_checkpoint(where + "time " + detail::concat(r.time) + " is not inside this run (0 to " +
                      detail::concat(end_time) + ")");
  if (r.step < 0 || (r.step == 0) != (r.time == 0.0))
    refuse_checkpoint(where + "step " + std::to_string(r.step) + " does not go with its time " +
                      detail::concat(r.time));
}

} // namespace

std::unique_ptr<StateReader> Restart::open(int rank) const {
  return std::make_unique<StateReader>((fs::path(folder) / state_name(generation, rank)).string());
}

void Restart::verify() const {
  for (int rank = 0; rank < ranks; ++rank) open(rank)->verify();
}

void check_resumed(const StateReader& file, double time, long step) {
  double kept_time = 0.0;
  long kept_step = 0;
  file.get("meta.time", kept_time);
  file.get("meta.step", kept_step);
  if (time != kept_time || step != kept_step)
    refuse_checkpoint("the checkpoint's state is at t = " + detail::concat(time) + " (step " +
                      std::to_string(step) + "), its header at t = " + detail::concat(kept_time) +
                      " (step " + std::to_string(kept_step) + "): a damaged checkpoint (" +
                      file.path() + ")");
}

void refused_on_this_rank(const CheckpointRefused& refusal) {
  int size = 1, rank = 0, started = 0;
  MPI_Initialized(&started);
  if (started) MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size == 1) return;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  std::cerr << "meshfree: --restart: " << refusal.what() << " (rank " << rank << ")" << std::endl;
  MPI_Abort(MPI_COMM_WORLD, 2);
}

Restart find_restart(const std::string& dir, const spec::ProblemSettings& settings, int ranks,
                     double end_time) {
  Restart r;
  r.folder = (fs::path(dir) / "checkpoint").string();
  if (fs::is_symlink(fs::symlink_status(r.folder)))
    refuse_checkpoint("--restart " + dir + ": " + r.folder +
                      " is a link; meshfree reads checkpoints only from a folder of its own");
  r.generation = real_folder(r.folder) ? marked_generation(r.folder) : 0;
  MF_REQUIRE(r.generation > 0, "--restart ", dir, ": no checkpoint in ", r.folder,
             " (a run writes one every output.checkpoint_interval of simulated time and every "
             "output.checkpoint_wall_interval of wall time)");
  const std::unique_ptr<StateReader> state = r.open(0);
  long format = 0, count = 0, threads = 0, kept_identity = 0;
  state->get("meta.format", format);
  if (format != kFormat)
    refuse_checkpoint("--restart " + dir + ": the checkpoint has layout " + std::to_string(format) +
                      ", this meshfree reads layout " + std::to_string(kFormat));
  // Another version of meshfree may compute another state from the same problem (a changed
  // scheme, another order of sums): its checkpoint is not continued by this one.
  const std::string version = state->text("meta.version");
  if (version != program_version())
    refuse_checkpoint("--restart " + dir + ": the checkpoint was written by meshfree " +
                      spec::one_line(version, 40) + ", this is meshfree " + program_version() +
                      "; restart it with the version that wrote it");
  state->get("meta.ranks", count);
  state->get("meta.threads", threads);
  state->get("meta.time", r.time);
  state->get("meta.step", r.step);
  state->get("meta.identity", kept_identity);
  r.ranks = static_cast<int>(count);
  r.threads = static_cast<int>(threads);
  if (r.ranks != ranks)
    refuse_checkpoint("--restart " + dir + ": the checkpoint was written by " +
                      std::to_string(count) + " MPI rank(s); restart it on as many (" +
                      std::to_string(ranks) + " given)");
  // The problem must be the one that was run, but for what a restart may change.
  compare_settings(dir, settings_map(state->text("meta.settings")), settings);
  if (kept_identity != identity(settings))
    refuse_checkpoint("--restart " + dir +
                      ": the checkpoint is of another problem (its identity "
                      "hash differs from this run's)");
  check_instant(dir, r, end_time);
  return r;
}

Checkpoints::Checkpoints(std::string dir, const distribution::Ranks& ranks,
                         spec::CheckpointPolicy policy, spec::ProblemSettings settings,
                         const Restart* restart)
    : dir_(std::move(dir)), folder_((fs::path(dir_) / "checkpoint").string()), ranks_(ranks),
      policy_(policy), settings_(std::move(settings)), last_(std::chrono::steady_clock::now()) {
  if (dir_.empty()) policy_ = {0.0, 0.0};
  next_time_ = policy_.interval;
  if (restart) {
    restarted_at_ = restart->time;
    generation_ = restart->generation;
    cleared_ = true; // its parts are this run's too
    if (policy_.interval > 0.0) next_time_ = next_multiple_after(restart->time, policy_.interval);
  }
}

Checkpoints::~Checkpoints() {
  if (lock_ >= 0) ::close(lock_);
}

bool Checkpoints::due(double t) {
  if (!policy_.any()) return false;
  if (policy_.interval > 0.0 && t >= next_time_ * (1 - 1e-12)) return true;
  if (policy_.wall_interval <= 0.0) return false;
  double late = seconds_since(last_) >= policy_.wall_interval ? 1.0 : 0.0;
  if (!ranks_.serial()) ranks_.broadcast(&late, 1, 0); // one clock decides for every rank
  return late > 0.0;
}

std::string Checkpoints::part(const std::string& stem, int k) const {
  return (fs::path(folder_) / (stem + ".part-" + std::to_string(k) + ".h5")).string();
}

namespace {

/// Rank 0's claim on the checkpoint folder: creates it and takes its lock (kept in `lock`, the
/// lock goes with the process). Returns 0 when taken, 1 when another run holds it, 2 when the
/// name is not a real folder.
double claim_folder(const std::string& dir, const std::string& folder, int& lock) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  MF_REQUIRE(!ec, dir, ": cannot create the output folder: ", ec.message());
  // mkdir, not create_directories: a link at the name is never followed.
  if (::mkdir(folder.c_str(), 0755) != 0 && errno != EEXIST)
    fail(folder, ": cannot create the checkpoint folder: ", system_reason(errno));
  if (!real_folder(folder)) return 2.0;
  lock =
      ::open((fs::path(folder) / kLock).c_str(), O_CREAT | O_RDWR | O_CLOEXEC | O_NOFOLLOW, 0644);
  return lock < 0 || ::flock(lock, LOCK_EX | LOCK_NB) != 0 ? 1.0 : 0.0;
}

void warn_unclaimed(const std::string& folder, double busy) {
  if (busy > 1.0)
    log::warn(folder, ": not a folder (a link?); meshfree follows no link, and this run "
                      "writes no checkpoints");
  else
    log::warn(folder, ": another run into this folder keeps its checkpoints there; this run "
                      "writes none");
}

/// Writes this rank's state file; returns its size in bytes.
double write_state_file(const std::string& path, const spec::ProblemSettings& settings,
                        const distribution::Ranks& ranks, double t, long step,
                        const std::function<void(StateWriter&)>& save) {
  StateWriter out(path);
  // Every rank's file says whose state it holds (a restart checks each against its run).
  out.put("meta.format", kFormat);
  out.put("meta.identity", identity(settings));
  out.put_text("meta.version", program_version());
  out.put("meta.ranks", static_cast<long>(ranks.size));
  out.put("meta.threads", static_cast<long>(omp_get_max_threads()));
  out.put("meta.time", t);
  out.put("meta.step", step);
  if (ranks.rank == 0) out.put_text("meta.settings", settings_text(settings));
  save(out);
  out.close();
  return static_cast<double>(out.bytes());
}

/// Rank 0, once every rank's file is whole: the marker names the new generation, and the
/// older generations' files go.
void publish_generation(const fs::path& folder, long generation) {
  std::error_code ec;
  const std::string next = (folder / (std::string(kMarker) + ".new")).string();
  fs::remove(next, ec);
  {
    OutputStream marker(next, next);
    marker.append("generation " + std::to_string(generation) + "\n");
    marker.close();
  }
  fs::rename(next, folder / kMarker, ec);
  MF_REQUIRE(!ec, (folder / kMarker).string(),
             ": cannot put the checkpoint in place: ", ec.message());
  sync_path(folder.string(), true);
  const std::string current = "state-" + std::to_string(generation) + ".";
  remove_ours(folder, [&current](const std::string& name) {
    return name.rfind("state-", 0) == 0 && name.rfind(current, 0) != 0;
  });
}

} // namespace

void Checkpoints::write(double t, long step, const std::function<void(StateWriter&)>& save) {
  const auto start = std::chrono::steady_clock::now();
  const fs::path folder(folder_);
  if (!locked_) {
    // One run at a time keeps its checkpoints in a folder.
    double busy = ranks_.rank == 0 ? claim_folder(dir_, folder_, lock_) : 0.0;
    if (!ranks_.serial()) ranks_.broadcast(&busy, 1, 0);
    if (busy > 0.0) {
      if (ranks_.rank == 0) warn_unclaimed(folder_, busy);
      policy_ = {0.0, 0.0};
      return;
    }
    locked_ = true;
  }
  if (ranks_.rank == 0 && !cleared_) // an earlier run's checkpoint is superseded by this one
    remove_ours(folder, [](const std::string& name) { return name != kLock; });
  cleared_ = true;
  ranks_.max(0.0); // the folder is there for every rank
  ++generation_;
  const std::string mine = (folder / state_name(generation_, ranks_.rank)).string();
  std::error_code ec;
  fs::remove(mine, ec); // a killed run's unfinished file of the same generation
  const double bytes = write_state_file(mine, settings_, ranks_, t, step, save);
  sync_path(mine, false);
  bytes_ = ranks_.sum(bytes); // every rank's file is whole from here on
  if (ranks_.rank == 0) publish_generation(folder, generation_);
  ranks_.max(0.0);
  if (policy_.interval > 0.0) next_time_ = next_multiple_after(t, policy_.interval);
  last_ = std::chrono::steady_clock::now();
  ++written_;
  seconds_ += seconds_since(start);
}

void remove_checkpoints(const std::string& dir) {
  const fs::path folder = fs::path(dir) / "checkpoint";
  if (!real_folder(folder)) return; // nothing of ours, and a link is not followed
  // Not while another run into DIR holds them.
  const int lock = ::open((folder / kLock).c_str(), O_RDWR | O_CLOEXEC | O_NOFOLLOW);
  const bool held = lock >= 0 && ::flock(lock, LOCK_EX | LOCK_NB) != 0;
  if (lock >= 0) ::close(lock);
  if (held) return;
  remove_ours(folder, [](const std::string&) { return true; });
  std::error_code ec;
  fs::remove(folder, ec); // only when nothing else is in it
}

Json CheckpointCounts::describe(double run_seconds) const {
  Json j;
  j.set("written", written).set("seconds", seconds).set("bytes", bytes);
  j.set("share_of_run", run_seconds > 0.0 ? seconds / run_seconds : 0.0);
  if (restarted_at >= 0.0) j.set("restarted_at_time", restarted_at);
  return j;
}

} // namespace mf::io
