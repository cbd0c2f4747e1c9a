#pragma once
// How much memory a run may count on, and the refusal of a discretisation that would not fit,
// before anything is allocated (an allocation that fails, or the kernel's out-of-memory killer,
// says nothing of which key asked for too much).
#include <string>

namespace mf {

/// Bytes of memory this process can count on: the machine's physical memory, or the limit of
/// its control group (a container, a batch job) when that is lower.
double usable_memory();

/// Stops with "<key>: <what>: about N, about X GiB at B bytes each, more than the Y GiB of
/// memory here" when count * bytes_each exceeds usable_memory(). `count` is a floating-point
/// estimate, so that a tiny spacing cannot overflow an integer on the way.
void require_memory(const std::string& key, const std::string& what, double count,
                    double bytes_each);

} // namespace mf
