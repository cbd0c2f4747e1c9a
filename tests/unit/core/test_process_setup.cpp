// What a process tells Open MPI before MPI starts (core/process_setup): a process no launcher
// started is alone (no daemon, only the transport to itself), a launched one is left as it is,
// and a parameter the user set is never replaced.
#include "meshfree/core/process_setup.hpp"
#include <catch2/catch.hpp>
#include <cstdlib>
#include <map>
#include <optional>
#include <string>

namespace {

const char* const kParameters[] = {"OMPI_MCA_ess_singleton_isolated", "OMPI_MCA_pml",
                                   "OMPI_MCA_btl", "OMPI_MCA_orte_create_session_dirs"};
const char* const kLaunchers[] = {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE",
                                  "SLURM_PROCID"};

std::optional<std::string> get(const char* name) {
  const char* v = std::getenv(name);
  return v ? std::optional<std::string>(v) : std::nullopt;
}

/// The variables this test changes, put back as they were when it ends.
class SavedEnvironment {
public:
  SavedEnvironment() {
    for (const char* n : kParameters) saved_[n] = get(n);
    for (const char* n : kLaunchers) saved_[n] = get(n);
  }
  ~SavedEnvironment() {
    for (const auto& [n, v] : saved_) v ? setenv(n.c_str(), v->c_str(), 1) : unsetenv(n.c_str());
  }
  void clear() const {
    for (const auto& kv : saved_) unsetenv(kv.first.c_str());
  }

private:
  std::map<std::string, std::optional<std::string>> saved_;
};

} // namespace

TEST_CASE("a process no launcher started tells Open MPI it is alone, a launched one is left as "
          "it is, the user's parameters stay",
          "[process]") {
  const SavedEnvironment saved;
  SECTION("started on its own") {
    saved.clear();
    mf::single_process_mpi();
    CHECK(get("OMPI_MCA_ess_singleton_isolated") == "1");
    CHECK(get("OMPI_MCA_pml") == "ob1");
    CHECK(get("OMPI_MCA_btl") == "self");
    CHECK(get("OMPI_MCA_orte_create_session_dirs") == "0");
  }
  SECTION("started by a launcher") {
    for (const char* launcher : kLaunchers) {
      INFO(launcher);
      saved.clear();
      setenv(launcher, "0", 1);
      mf::single_process_mpi();
      for (const char* p : kParameters) CHECK_FALSE(get(p));
    }
  }
  SECTION("the user's parameters") {
    saved.clear();
    setenv("OMPI_MCA_btl", "self,vader", 1);
    setenv("OMPI_MCA_pml", "cm", 1);
    mf::single_process_mpi();
    CHECK(get("OMPI_MCA_btl") == "self,vader");
    CHECK(get("OMPI_MCA_pml") == "cm");
    CHECK(get("OMPI_MCA_ess_singleton_isolated") == "1");
  }
}
