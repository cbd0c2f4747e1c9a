#include "meshfree/core/process_setup.hpp"
#include <cstdlib>
#include <initializer_list>
#include <limits>
#include <malloc.h>

namespace mf {

namespace {

/// OMP_WAIT_POLICY=passive unless the user chose a policy. libgomp reads its environment in its
/// initialiser, when the dynamic linker initialises the shared libraries; an executable's
/// preinit array runs before any of them (System V ABI, DT_PREINIT_ARRAY; glibc's _dl_init), so
/// the policy is in place when libgomp looks, without the process running itself again.
void passive_wait_policy(int, char**, char**) {
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;
  setenv("OMP_WAIT_POLICY", "passive", 0);
}

} // namespace

// In every executable that links this file: the program and the unit tests' runner, which call
// keep_freed_memory from it.
__attribute__((section(".preinit_array"),
               used)) void (*const kPassiveWaitPolicy)(int, char**, char**) = passive_wait_policy;

void keep_freed_memory() {
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max());
}

void single_process_mpi() {
  // Started by a launcher (mpirun, srun, another PMI): its processes talk to each other.
  for (const char* launched :
       {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE", "SLURM_PROCID"})
    if (std::getenv(launched)) return;
  setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
  setenv("OMPI_MCA_pml", "ob1", 0);
  setenv("OMPI_MCA_btl", "self", 0);
  setenv("OMPI_MCA_orte_create_session_dirs", "0", 0);
}

} // namespace mf
