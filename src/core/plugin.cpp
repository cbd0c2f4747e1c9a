#include "meshfree/core/plugin.hpp"
#include "meshfree/core/error.hpp"
#include <dlfcn.h>
#include <filesystem>
#include <vector>

namespace mf {

void* plugin_function(const char* library, const char* entry, std::string& why) {
  std::vector<std::filesystem::path> folders;
  std::error_code ec;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) folders.push_back(self.parent_path());
  if (folders.empty() || folders.front() != std::filesystem::path(MESHFREE_PLUGIN_DIR))
    folders.emplace_back(MESHFREE_PLUGIN_DIR);
  for (const auto& folder : folders) {
    const std::string path = (folder / library).string();
    // dlopen hands back the same handle for a library already loaded.
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* reason = dlerror();
      why += "; " + (reason ? std::string(reason) : path);
      continue;
    }
    if (void* function = dlsym(handle, entry)) return function;
    why += "; " + path + " has no " + entry;
  }
  return nullptr;
}

void* gmsh_function(const char* entry, const std::string& what, const std::string& remedy) {
  std::string tried;
  if (void* function = plugin_function(kGmshLibrary, entry, tried)) return function;
  fail(what, " needs gmsh's library ", kGmshLibrary, ", which cannot be loaded", tried, " (",
       remedy, ")");
}

} // namespace mf
