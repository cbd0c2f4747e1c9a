#pragma once
// Functions of a shared library of the project that is loaded only when it is needed (the gmsh
// library, whose 80 dependencies would slow every start: fem/gmsh_mesher.hpp).
#include <string>

namespace mf {

/// gmsh's mesher and reader, with the gmsh library behind them.
inline constexpr const char* kGmshLibrary = "libmeshfree_gmsh.so";

/// The function `entry` of the project's library `library`, looked for next to the program, then
/// in the build folder it was built in; loaded once and kept. Null where neither holds it, with
/// each attempt's reason in `why`.
void* plugin_function(const char* library, const char* entry, std::string& why);

/// The function `entry` of gmsh's library; stops with "<what> needs gmsh's library ..., which
/// cannot be loaded; <reasons> (<remedy>)" where it cannot be had.
void* gmsh_function(const char* entry, const std::string& what, const std::string& remedy);

} // namespace mf
