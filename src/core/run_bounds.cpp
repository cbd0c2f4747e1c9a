#include "meshfree/core/run_bounds.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/core/memory.hpp"
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <omp.h>
#include <sstream>

namespace mf {

namespace {
/// Two significant digits: an estimate shows no more.
std::string rough(double v) {
  std::ostringstream os;
  os << std::setprecision(2) << v;
  return os.str();
}

/// Free bytes on the disk that holds `folder`, or on its nearest existing parent; 0 if unknown.
double free_bytes(const std::string& folder) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path p = fs::absolute(folder.empty() ? "." : folder, ec);
  while (!p.empty() && !fs::exists(p, ec) && p != p.parent_path()) p = p.parent_path();
  const fs::space_info s = fs::space(p, ec);
  return ec ? 0.0 : static_cast<double>(s.available);
}
} // namespace

int cores_here() {
  return std::max(1, omp_get_max_threads());
}

void require_run_time(const std::string& key, const std::string& what, double count,
                      double per_second_per_core) {
  const int cores = cores_here();
  const double seconds = count / (per_second_per_core * cores);
  if (!(seconds <= max_run_seconds))
    fail(key, ": ", what, ": about ", rough(count), ", about ", rough(seconds / 86400.0),
         " days on the ", cores, " core(s) here at ", rough(per_second_per_core),
         " per second per core, more than the ", rough(max_run_seconds / 86400.0),
         " days a run may take");
}

void require_disk(const std::string& key, const std::string& what, double count,
                  double bytes_each, const std::string& folder) {
  const double need = count * bytes_each, have = free_bytes(folder);
  if (have > 0.0 && !(need <= have)) {
    const double gib = 1024.0 * 1024.0 * 1024.0;
    fail(key, ": ", what, ": about ", rough(count), ", about ", rough(need / gib), " GiB at ",
         rough(bytes_each), " bytes each, more than the ", rough(have / gib),
         " GiB free on the disk of ", folder);
  }
}

double next_multiple_after(double t, double interval) {
  return interval * (std::floor(t / interval * (1 + 1e-12)) + 1.0);
}

} // namespace mf
