#pragma once
// How a program of this project sets up its process before anything else runs: the OpenMP
// threads' wait (set before main), what glibc does with freed memory, and what Open MPI starts
// for a single process.
// The program and the unit tests both start with them, so that a test measures the code as a run
// executes it.

namespace mf {

// OpenMP threads that wait at the end of a loop sleep instead of spinning, unless the user chose
// a policy (OMP_WAIT_POLICY or GOMP_SPINCOUNT): with another job on one of the cores a spinning
// team waits for its slowest thread at every loop, a sleeping one gives the core away
// (README.md, "Running", has the measured cost). libgomp reads OMP_WAIT_POLICY when it is
// loaded, before main; process_setup.cpp sets it from the executable's preinit array, which
// runs before any shared library's initialiser. Nothing to call.

/// Freed memory stays with the process instead of going back to the system. glibc serves large
/// blocks by mmap and unmaps them on free, so every large vector (a shape table, a solver's work
/// space) is paged in afresh, and the first touch of a page is what costs on virtual machines,
/// more for memory the host has taken back than for memory just freed; keeping it makes large
/// assemblies faster at the same peak memory (measured in README.md, "Running").
void keep_freed_memory();

/// A program started without mpirun is one MPI process: Open MPI is told so, unless the user set
/// these parameters, so that it starts no runtime daemon for it (ess_singleton_isolated) and opens
/// only the transport to itself (pml ob1, btl self), no network library: the Omni-Path library
/// Debian's Open MPI loads for its psm2 component sleeps in its initialiser on a machine without
/// that network, and starting the daemon costs about as much again (README.md, "Running", has
/// the measured start-up). Nor does it make a session directory (orte_create_session_dirs): every
/// isolated process names its own /tmp/ompi.<host>.<uid>/jf.0/1/0, so of two runs started at once
/// one could remove that folder as it ended while the other was making it, and the other failed
/// to start; with only the transport to itself a process keeps nothing there. Under mpirun, srun
/// or another launcher nothing changes. Call it before MPI is initialised.
void single_process_mpi();

} // namespace mf
