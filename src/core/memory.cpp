#include "meshfree/core/memory.hpp"
#include "meshfree/core/error.hpp"
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <sys/resource.h>
#include <unistd.h>

namespace mf {

double peak_resident_bytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0.0;
  return 1024.0 * static_cast<double>(usage.ru_maxrss); // Linux reports kilobytes
}

double usable_memory() {
  const double pages = static_cast<double>(sysconf(_SC_PHYS_PAGES));
  const double page = static_cast<double>(sysconf(_SC_PAGE_SIZE));
  double bytes = pages > 0 && page > 0 ? pages * page : 0.0;
  // cgroup v2, then v1; "max" or a huge number means no limit.
  for (const char* path :
       {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
    std::ifstream in(path);
    std::string value;
    if (!(in >> value) || value == "max") continue;
    try {
      const double limit = std::stod(value);
      if (limit > 0.0 && (bytes == 0.0 || limit < bytes)) bytes = limit;
    } catch (const std::exception&) {
    }
  }
  return bytes;
}

namespace {
/// Two significant digits: an estimate shows no more.
std::string rough(double v) {
  std::ostringstream os;
  os << std::setprecision(2) << v;
  return os.str();
}
} // namespace

std::string describe_bytes(double bytes) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB"};
  int u = 0;
  while (bytes >= 1024.0 && u < 4) bytes /= 1024.0, ++u;
  std::ostringstream os;
  os << std::fixed << std::setprecision(bytes < 10.0 ? 1 : 0) << bytes;
  return "about " + os.str() + " " + units[u];
}

void require_memory(const std::string& key, const std::string& what, double count,
                    double bytes_each) {
  const double need = count * bytes_each, have = usable_memory();
  if (have > 0.0 && !(need <= have)) {
    const double gib = 1024.0 * 1024.0 * 1024.0;
    fail(key, ": ", what, ": about ", rough(count), ", about ", rough(need / gib), " GiB at ",
         rough(bytes_each), " bytes each, more than the ", rough(have / gib),
         " GiB of memory here");
  }
}

} // namespace mf
