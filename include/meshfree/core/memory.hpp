#pragma once
// How much memory a run may count on, and the refusal of a discretisation that would not fit,
// before anything is allocated (an allocation that fails, or the kernel's out-of-memory killer,
// says nothing of which key asked for too much).
#include <string>

namespace mf {

/// Bytes a run holds per item at its peak, measured on the problems of problems/ with a margin:
/// what require_memory checks and `meshfree check` reports.
namespace bytes_per {
/// A Galerkin node with its points' shape functions, the matrix and the direct solver's factor
/// (the bound the input check applies before the points exist: 21 KB measured on plate_tension).
constexpr double galerkin_node = 30000.0;
/// The same with the multigrid solver (no factor): 11.0 KB measured at 5.1e5 nodes on
/// plate_tension (5.6 GB peak), with a margin.
constexpr double galerkin_node_multigrid = 14000.0;
/// Once the points are known: per node (matrix, factor) and per Gauss point (shape functions,
/// slot map, material state, output), from the peaks of plate_tension (32 MB over 1,681 nodes and
/// 14,400 points) and the elastoplastic perforated strip (114 MB, 2,546 nodes, 39,059 points).
constexpr double galerkin_node_alone = 12000.0;
/// A node of a 3D Galerkin body (3 DOFs) with the direct solver, whose factor grows faster than
/// the matrix in 3D: 104 KB a DOF measured at the peak of the 88,341-DOF thick plate, 40 KB on
/// the thin 15,585-DOF cylinder slice (README.md, "3D bodies"); and with the multigrid solver:
/// 21.5-25.8 KB a DOF measured on the box from 12k to 108k DOFs.
constexpr double solid_node_direct = 3.3e5;
constexpr double solid_node_multigrid = 8.0e4;
/// A node of 8- or 20-node bricks with the multigrid solver: 3.6-4.6 KB a DOF measured on the
/// hex8 box from 4e4 to 4.5e5 DOFs, 6.3-7.7 KB on the hex20 box to 10^6 (README.md, "3D
/// bodies"), with a margin.
constexpr double solid_brick_node_multigrid = 2.4e4;
/// The bytes per node of a 3D Galerkin body: meshfree or bricks, direct or multigrid.
constexpr double solid_node(bool bricks, bool multigrid) {
  return !multigrid ? solid_node_direct
         : bricks   ? solid_brick_node_multigrid
                    : solid_node_multigrid;
}
constexpr double galerkin_point = 2500.0;
/// What the program holds before any of these (its libraries: MPI, PETSc, HDF5).
constexpr double program = 45.0 * 1024.0 * 1024.0;
/// An SPH particle with its neighbour lists and rates (1.5 KB measured on the 2D tunnel, 3.8 KB
/// on the 3D Taylor bar).
constexpr double sph_particle(int dim) {
  return dim == 1 ? 1000.0 : dim == 2 ? 2000.0 : 5000.0;
}
/// A peridynamic particle's arrays, and each bond partner it has (about 5 bytes, counted twice
/// at the peak of building them).
constexpr double pd_particle = 600.0;
constexpr double pd_partner = 10.0;
} // namespace bytes_per

/// "about 1.2 GiB" (or MiB, KiB).
std::string describe_bytes(double bytes);

/// Bytes of memory this process can count on: the machine's physical memory, or the limit of
/// its control group (a container, a batch job) when that is lower.
double usable_memory();

/// The largest resident set size this process has had so far, in bytes (getrusage).
double peak_resident_bytes();

/// Stops with "<key>: <what>: about N, about X GiB at B bytes each, more than the Y GiB of
/// memory here" when count * bytes_each exceeds usable_memory(). `count` is a floating-point
/// estimate, so that a tiny spacing cannot overflow an integer on the way.
void require_memory(const std::string& key, const std::string& what, double count,
                    double bytes_each);

} // namespace mf
