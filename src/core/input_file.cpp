#include "meshfree/core/input_file.hpp"
#include "meshfree/core/error.hpp"
#include <sys/stat.h>

namespace mf {

void require_regular_file(const std::string& path, const std::string& what) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) fail(path, ": cannot open the ", what);
  if (S_ISDIR(st.st_mode)) fail(path, ": is a folder, not a ", what);
  if (!S_ISREG(st.st_mode)) fail(path, ": is a FIFO, device or socket, not a ", what);
}

} // namespace mf
