#pragma once
// Input files are regular files: opening a FIFO blocks until something writes into it (a run
// that waits forever with no word), a device may never end, and a folder reads as an error deep
// in a stream ("basic_filebuf::underflow"). Each is refused by name before it is opened.
#include <string>

namespace mf {

/// Stops with "<path>: cannot open the <what>" when nothing is there, "<path>: is a folder, not
/// a <what>" or "<path>: is a FIFO, device or socket, not a <what>" when it is not a regular
/// file (links are followed to what they name).
void require_regular_file(const std::string& path, const std::string& what);

} // namespace mf
