#include "meshfree/core/error.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/io/output.hpp"
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace mf::io {

namespace fs = std::filesystem;

namespace {

constexpr const char* kStagingPrefix = ".meshfree-staging-";
constexpr const char* kManifest = ".meshfree-manifest";

/// True when `path` is a folder itself, not a link to one.
bool real_folder(const fs::path& path) {
  struct stat st {};
  return ::lstat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}

std::string host_name() {
  char name[256] = {};
  if (gethostname(name, sizeof name - 1) != 0) return "host";
  std::string s(name);
  std::replace(s.begin(), s.end(), '-', '_'); // the last '-' of a staging name ends the host
  return s;
}

/// A file a run wrote, as its folder's manifest records it.
struct Entry {
  std::string name;
  std::uintmax_t size = 0, inode = 0;
};

/// The whole of a small regular file (a manifest), read without following a link or blocking on
/// a FIFO; empty when there is none.
std::string read_own_file(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return {};
  struct stat st {};
  std::string text;
  if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size < (1 << 24)) {
    text.resize(static_cast<std::size_t>(st.st_size));
    const ssize_t n = ::read(fd, text.data(), text.size());
    text.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
  }
  ::close(fd);
  return text;
}

/// The files a folder's manifest lists: plain file names with the size and inode each had when
/// its run wrote it (none without a manifest; an entry without them names no file of ours).
std::vector<Entry> read_manifest(const fs::path& folder) {
  std::vector<Entry> entries;
  std::istringstream in(read_own_file(folder / kManifest));
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    Entry e;
    if (!std::getline(fields, e.name, '\t') || !(fields >> e.size >> e.inode)) continue;
    if (e.name.find('/') == std::string::npos && e.name != "." && e.name != "..")
      entries.push_back(e);
  }
  return entries;
}

/// Removes a file a manifest lists, only if it is still the regular file its run wrote (same
/// size and inode): a link planted at the name, or a user's file put there since, stays.
void remove_entry(const fs::path& folder, const Entry& e) {
  const fs::path path = folder / e.name;
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode) ||
      static_cast<std::uintmax_t>(st.st_size) != e.size ||
      static_cast<std::uintmax_t>(st.st_ino) != e.inode)
    return;
  std::error_code ec;
  if (!fs::remove(path, ec) && ec)
    fail(path.string(), ": cannot remove the previous result: ", ec.message());
}

/// Removes path if it is a file or a link (the link, never its target); anything else stays.
void remove_file(const fs::path& path) {
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(path, ec);
  if (ec || !(fs::is_regular_file(st) || fs::is_symlink(st))) return;
  if (!fs::remove(path, ec) && ec)
    fail(path.string(), ": cannot remove the previous result: ", ec.message());
}

/// True for the names the code writes into a staging folder: results (.h5, .xmf, .csv,
/// summary.json) and the manifest.
bool written_by_us(const std::string& name) {
  return name == kManifest || ends_with(name, ".h5") || ends_with(name, ".xmf") ||
         ends_with(name, ".csv") || ends_with(name, ".json");
}

/// Removes a folder the code wrote (a staging folder, or a kept unfinished run): the files its
/// manifest lists, or without one the kinds of file the code writes, then the folder if nothing
/// else is left in it. Returns false when something else stays.
bool remove_our_folder(const fs::path& folder) {
  std::error_code ec;
  if (fs::exists(fs::symlink_status(folder / kManifest))) {
    for (const auto& e : read_manifest(folder)) remove_entry(folder, e);
    remove_file(folder / kManifest);
  } else {
    for (const auto& entry : fs::directory_iterator(folder, ec))
      if (written_by_us(entry.path().filename().string())) remove_file(entry.path());
  }
  return fs::remove(folder, ec) && !ec;
}

/// True while process pid runs on this machine (a killed process not yet reaped does not).
bool running(long pid) {
  if (kill(static_cast<pid_t>(pid), 0) != 0 && errno != EPERM) return false;
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return true;
  const std::size_t close = line.rfind(')'); // the state follows the command name
  return close == std::string::npos || close + 2 >= line.size() || line[close + 2] != 'Z';
}

/// Staging folders of earlier runs into `dir` that did not finish (killed, or the machine went
/// down): their files go, with a line saying what they were. A folder of a process that still
/// runs on this machine, or of another machine's run, is left alone.
void remove_stale_staging(const fs::path& dir) {
  std::error_code ec;
  const std::string host = host_name();
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(kStagingPrefix, 0) != 0 || !fs::is_directory(fs::symlink_status(entry.path())))
      continue;
    const std::string rest = name.substr(std::strlen(kStagingPrefix));
    const std::size_t dash = rest.rfind('-');
    long pid = 0;
    try {
      pid = dash == std::string::npos ? 0 : std::stol(rest.substr(dash + 1));
    } catch (const std::exception&) {
      pid = 0;
    }
    if (dash == std::string::npos || rest.substr(0, dash) != host) {
      log::info(entry.path().string(), ": the staging folder of a run on another machine; left "
                                       "alone");
      continue;
    }
    if (pid > 0 && pid != getpid() && running(pid)) {
      log::info(entry.path().string(), ": process ", pid,
                " is still writing into this folder; its staging folder is left alone");
      continue;
    }
    log::info(entry.path().string(), ": the unfinished files of an earlier run (process ", pid,
              ") that was stopped or killed; removing them");
    if (!remove_our_folder(entry.path()))
      log::info(entry.path().string(), ": holds files meshfree did not write; left in place");
  }
}

} // namespace

std::string system_reason(int error) {
  std::string s = std::strerror(error);
  if (!s.empty()) s[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(s[0])));
  return s;
}

OutputStream::OutputStream(const std::string& path, std::string shown) : shown_(std::move(shown)) {
  // Created exclusively: a file or link already at the path is an error, never followed or
  // truncated.
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd_ < 0) fail("cannot create ", shown_, ": ", system_reason(errno));
}

OutputStream::~OutputStream() {
  if (fd_ >= 0) ::close(fd_);
}

void OutputStream::append(const std::string& text) {
  MF_REQUIRE(fd_ >= 0, shown_, ": written after it was closed");
  const char* p = text.data();
  std::size_t left = text.size();
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail(system_reason(errno), " writing ", shown_);
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}

void OutputStream::close() {
  if (fd_ < 0) return;
  // Space may be claimed only when the data reach the disk (network and copy-on-write file
  // systems): the error shows at fsync or close, not at write.
  const int fd = fd_;
  fd_ = -1;
  if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) {
    const int error = errno;
    ::close(fd);
    fail(system_reason(error), " writing ", shown_);
  }
  if (::close(fd) != 0) fail(system_reason(errno), " writing ", shown_);
}

namespace {
/// A new file holding `text`, every write, the flush to disk and the close checked.
void write_new_file(const std::string& path, const std::string& text, const std::string& shown) {
  OutputStream stream(path, shown);
  stream.append(text);
  stream.close();
}
} // namespace

OutputDirectory::OutputDirectory(std::string dir, std::string option)
    : dir_(std::move(dir)), option_(std::move(option)) {
  std::error_code ec;
  const fs::file_status st = fs::status(dir_, ec);
  if (fs::exists(st)) {
    MF_REQUIRE(fs::is_directory(st), "--out ", dir_, ": not a directory");
    MF_REQUIRE(::access(dir_.c_str(), W_OK | X_OK) == 0, "--out ", dir_,
               ": not a directory this user can write into (", system_reason(errno), ")");
    lock();
    return;
  }
  // It will be created in its nearest existing ancestor, which must be a writable directory.
  fs::path parent = fs::absolute(dir_, ec).parent_path();
  while (!parent.empty() && !fs::exists(fs::status(parent, ec)) && parent != parent.root_path())
    parent = parent.parent_path();
  MF_REQUIRE(fs::is_directory(fs::status(parent, ec)) && ::access(parent.c_str(), W_OK | X_OK) == 0,
             "--out ", dir_, ": cannot be created in ", parent.string(),
             " (not a directory this user can write into)");
}

void OutputDirectory::lock() {
  if (lock_ >= 0) return;
  // The folder itself is locked (flock on its descriptor): nothing is written to hold the lock,
  // and it goes with the process however that ends.
  lock_ = ::open(dir_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (lock_ < 0) return;
  if (::flock(lock_, LOCK_EX | LOCK_NB) == 0) return;
  const int error = errno;
  ::close(lock_);
  lock_ = -1;
  // A file system without locks (some network ones) leaves the folder unguarded.
  if (error == EWOULDBLOCK)
    fail(option_, " ", dir_, ": in use by a run of meshfree that is still going; wait for it to "
         "end or choose another folder");
}

OutputDirectory::~OutputDirectory() {
  if (lock_ >= 0) ::close(lock_);
}

void OutputDirectory::discard() {
  finished_ = true;
  if (!opened()) return;
  // The staging folder is this run's own (created fresh, private): all of it goes.
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(staging_, ec)) remove_file(entry.path());
  fs::remove(staging_, ec);
}

void OutputDirectory::open() {
  if (opened()) return;
  std::error_code ec;
  fs::create_directories(dir_, ec);
  MF_REQUIRE(!ec, "--out ", dir_, ": cannot create the output directory: ", ec.message());
  lock();
  remove_stale_staging(dir_);
  // This run's own folder inside DIR, created fresh (mkdir fails on anything already there) and
  // private to the user, so nothing can be planted in it; results move out of it only when the
  // run has completed.
  const std::string staging =
      (fs::path(dir_) / (kStagingPrefix + host_name() + "-" + std::to_string(getpid()))).string();
  if (::mkdir(staging.c_str(), 0700) != 0)
    fail("--out ", dir_, ": cannot create the staging folder ", staging, ": ",
         system_reason(errno));
  staging_ = staging;
}


std::string OutputDirectory::shown(const std::string& file) const {
  return (fs::path(dir_) / name_of(file)).string();
}

std::string OutputDirectory::temp_path(const std::string& name) {
  open();
  const std::string file = name_of(name);
  MF_REQUIRE(!finished_, shown(name), ": written after the run's files were put in place");
  MF_REQUIRE(std::find(pending_.begin(), pending_.end(), file) == pending_.end(), shown(name),
             ": written twice in one run");
  pending_.push_back(file);
  return (fs::path(staging_) / file).string();
}

void OutputDirectory::write_text(const std::string& file, const std::string& text) {
  write_new_file(temp_path(file), text, shown(file));
}

std::unique_ptr<OutputStream> OutputDirectory::open_stream(const std::string& file) {
  return std::make_unique<OutputStream>(temp_path(file), shown(file));
}

void OutputDirectory::write_manifest(const std::string& folder) const {
  std::string text = "# meshfree: the files its last run wrote here (name, size, inode); the "
                     "next run into this folder replaces or removes these and no others\n";
  for (const auto& f : pending_) {
    // The file as it is in the staging folder: a rename keeps its inode and size.
    struct stat st {};
    if (::lstat((fs::path(staging_) / f).c_str(), &st) == 0 && S_ISREG(st.st_mode))
      text += f + "\t" + std::to_string(st.st_size) + "\t" + std::to_string(st.st_ino) + "\n";
  }
  write_new_file((fs::path(folder) / kManifest).string(), text,
                 (fs::path(folder) / kManifest).string());
}

void OutputDirectory::commit() {
  MF_REQUIRE(!finished_, dir_, ": the run's files were put in place already");
  open();
  const fs::path dir(dir_), staging(staging_);
  write_manifest(staging_);
  const std::vector<Entry> previous = read_manifest(dir);
  // The previous result stops being one first (a folder without summary.json holds no finished
  // run), then the files it had that this run does not write again go; nothing that no manifest
  // lists is touched, nor a listed name that is no longer the file that run wrote.
  for (const auto& e : previous)
    if (e.name == "summary.json") remove_entry(dir, e);
  for (const auto& e : previous)
    if (std::find(pending_.begin(), pending_.end(), e.name) == pending_.end()) remove_entry(dir, e);
  // Then this run's files, the manifest and summary.json last. A rename replaces a link at the
  // name, never its target.
  std::vector<std::string> order;
  for (const auto& f : pending_)
    if (f != "summary.json") order.push_back(f);
  order.push_back(kManifest);
  if (std::find(pending_.begin(), pending_.end(), "summary.json") != pending_.end())
    order.push_back("summary.json");
  for (const auto& f : order) {
    std::error_code ec;
    fs::rename(staging / f, dir / f, ec);
    MF_REQUIRE(!ec, (dir / f).string(), ": cannot move the result into place: ", ec.message(),
               " (this run's files are in ", staging_, ")");
  }
  std::error_code ec;
  fs::remove(staging, ec);
  // An earlier run's kept files describe a result this one supersedes.
  for (const char* kept : {"failed", "stopped"})
    if (real_folder(dir / kept) && fs::exists(fs::symlink_status(dir / kept / kManifest)))
      remove_our_folder(dir / kept);
  finished_ = true;
}

void OutputDirectory::replace_summary(const std::string& text) {
  const auto at = std::find(pending_.begin(), pending_.end(), name_of("summary.json"));
  if (at != pending_.end()) {
    remove_file(fs::path(staging_) / *at);
    pending_.erase(at);
  }
  write_text("summary.json", text);
}

std::string OutputDirectory::keep_unfinished(const std::string& status) {
  MF_REQUIRE(!finished_, dir_, ": the run's files were put in place already");
  open();
  finished_ = true;
  // Only the names that were written (a file may have failed before its creation).
  std::vector<std::string> written;
  for (const auto& f : pending_)
    if (fs::exists(fs::symlink_status(fs::path(staging_) / f))) written.push_back(f);
  pending_ = written;
  write_manifest(staging_);
  const fs::path target = fs::path(dir_) / status;
  std::error_code ec;
  if (fs::exists(fs::symlink_status(target, ec))) {
    // An earlier run's kept files go; anything else at that name stays, and so do these.
    const bool ours =
        real_folder(target) && fs::exists(fs::symlink_status(target / kManifest));
    if (!ours || !remove_our_folder(target)) return staging_;
  }
  fs::rename(staging_, target, ec);
  return ec ? staging_ : target.string();
}

} // namespace mf::io
