#include "meshfree/io/checkpoint.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/core/run_bounds.hpp"
#include "meshfree/core/timer.hpp"
#include "meshfree/io/key_reader.hpp"
#include "meshfree/io/output.hpp"
#include <cerrno>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <map>
#include <omp.h>
#include <sstream>
#include <sys/file.h>
#include <unistd.h>

namespace mf::io {

namespace fs = std::filesystem;

namespace {

constexpr const char* kMarker = "checkpoint.txt";
constexpr const char* kLock = ".lock";

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

std::string settings_text(const ProblemSettings& s) {
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

std::unique_ptr<StateReader> Restart::open(int rank) const {
  return std::make_unique<StateReader>((fs::path(folder) / state_name(generation, rank)).string());
}

Restart find_restart(const std::string& dir, const ProblemSettings& settings, int ranks) {
  Restart r;
  r.folder = (fs::path(dir) / "checkpoint").string();
  std::ifstream marker(fs::path(r.folder) / kMarker);
  std::string word;
  MF_REQUIRE(marker >> word >> r.generation && word == "generation" && r.generation > 0,
             "--restart ", dir, ": no checkpoint in ", r.folder,
             " (a run writes one every output.checkpoint_interval of simulated time and every "
             "output.checkpoint_wall_interval of wall time)");
  const std::unique_ptr<StateReader> state = r.open(0);
  long count = 0, threads = 0, step = 0;
  state->get("meta.ranks", count);
  state->get("meta.threads", threads);
  state->get("meta.time", r.time);
  state->get("meta.step", step);
  r.ranks = static_cast<int>(count);
  r.threads = static_cast<int>(threads);
  r.step = step;
  MF_REQUIRE(r.ranks == ranks, "--restart ", dir, ": the checkpoint was written by ", r.ranks,
             " MPI rank(s); restart it on as many (", ranks, " given)");
  // The problem must be the one that was run, but for what a restart may change.
  const auto before = settings_map(state->text("meta.settings"));
  const std::map<std::string, std::string> now(settings.begin(), settings.end());
  for (const auto* side : {&before, &now})
    for (const auto& [key, value] : *side) {
      const auto b = before.find(key), n = now.find(key);
      const std::string was = b == before.end() ? "(not given)" : one_line(b->second, 40);
      const std::string is = n == now.end() ? "(not given)" : one_line(n->second, 40);
      if (was != is && !restart_may_change(key))
        fail("--restart ", dir, ": ", one_line(key), " changed since the checkpoint (", was,
             " then, ", is,
             " now); a restart may change only time.end and the output "
             "intervals");
    }
  return r;
}

Checkpoints::Checkpoints(std::string dir, const distribution::Ranks& ranks, CheckpointPolicy policy,
                         ProblemSettings settings, const Restart* restart)
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

void Checkpoints::write(double t, long step, const std::function<void(StateWriter&)>& save) {
  const auto start = std::chrono::steady_clock::now();
  const fs::path folder(folder_);
  if (!locked_) {
    // One run at a time keeps its checkpoints in a folder; the lock goes with its process.
    double busy = 0.0;
    if (ranks_.rank == 0) {
      std::error_code ec;
      fs::create_directories(folder, ec);
      MF_REQUIRE(!ec, folder_, ": cannot create the checkpoint folder: ", ec.message());
      lock_ = ::open((folder / kLock).c_str(), O_CREAT | O_RDWR | O_CLOEXEC | O_NOFOLLOW, 0644);
      busy = lock_ < 0 || ::flock(lock_, LOCK_EX | LOCK_NB) != 0 ? 1.0 : 0.0;
    }
    if (!ranks_.serial()) ranks_.broadcast(&busy, 1, 0);
    if (busy > 0.0) {
      if (ranks_.rank == 0)
        log::warn(folder_, ": another run into this folder keeps its checkpoints there; this run "
                           "writes none");
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
  double bytes = 0.0;
  {
    StateWriter out(mine);
    if (ranks_.rank == 0) {
      out.put("meta.ranks", static_cast<long>(ranks_.size));
      out.put("meta.threads", static_cast<long>(omp_get_max_threads()));
      out.put("meta.time", t);
      out.put("meta.step", step);
      out.put_text("meta.settings", settings_text(settings_));
    }
    save(out);
    out.close();
    bytes = static_cast<double>(out.bytes());
  }
  sync_path(mine, false);
  bytes_ = ranks_.sum(bytes); // every rank's file is whole from here on
  if (ranks_.rank == 0) {
    // The marker names the new generation only once all of it is on disk.
    const std::string next = (folder / (std::string(kMarker) + ".new")).string();
    fs::remove(next, ec);
    {
      OutputStream marker(next, next);
      marker.append("generation " + std::to_string(generation_) + "\n");
      marker.close();
    }
    fs::rename(next, folder / kMarker, ec);
    MF_REQUIRE(!ec, (folder / kMarker).string(),
               ": cannot put the checkpoint in place: ", ec.message());
    sync_path(folder_, true);
    const std::string current = "state-" + std::to_string(generation_) + ".";
    remove_ours(folder, [&current](const std::string& name) {
      return name.rfind("state-", 0) == 0 && name.rfind(current, 0) != 0;
    });
  }
  ranks_.max(0.0);
  if (policy_.interval > 0.0) next_time_ = next_multiple_after(t, policy_.interval);
  last_ = std::chrono::steady_clock::now();
  ++written_;
  seconds_ += seconds_since(start);
}

void remove_checkpoints(const std::string& dir) {
  const fs::path folder = fs::path(dir) / "checkpoint";
  if (!fs::is_directory(fs::symlink_status(folder))) return;
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
