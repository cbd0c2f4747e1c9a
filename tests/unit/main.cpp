// Catch2 runner inside a PETSc session, so that tests can solve through PETSc.
#define CATCH_CONFIG_RUNNER
#include "meshfree/core/log.hpp"
#include "meshfree/core/process_setup.hpp"
#include "meshfree/solvers/petsc_session.hpp"
#include "test_support.hpp"
#include <catch2/catch.hpp>

namespace {
mf::solvers::PetscSession* g_session = nullptr;
}

const mf::solvers::PetscSession& test_session() {
  return *g_session;
}

int main(int argc, char** argv) {
  mf::keep_freed_memory();
  mf::single_process_mpi();
  int pargc = 1;
  char** pargv = argv;
  mf::solvers::PetscSession session(&pargc, &pargv);
  g_session = &session;
  mf::log::verbose() = false;
  return Catch::Session().run(argc, argv);
}
