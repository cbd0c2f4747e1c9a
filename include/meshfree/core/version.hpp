#pragma once
// The program's version: CMakeLists.txt's project(meshfree VERSION ...), written into a source
// file generated at configuration (src/core/version.cpp.in).

namespace mf {
/// "MAJOR.MINOR.PATCH".
const char* program_version();
} // namespace mf
