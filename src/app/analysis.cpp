#include "meshfree/app/analysis.hpp"
#include "meshfree/app/elastic_static.hpp"
#include "meshfree/app/elastoplastic_static.hpp"
#include "meshfree/app/model_problem_1d.hpp"
#include "meshfree/app/peridynamics.hpp"
#include "meshfree/app/sph_run.hpp"
#include "meshfree/app/staged.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/core/log.hpp"
#include <vector>

namespace mf::app {

namespace {

/// One row per analysis, in the order the documentation lists them.
const std::vector<AnalysisEntry>& table() {
  static const std::vector<AnalysisEntry> entries{elastic_static_entry(),
                                                  elastoplastic_static_entry(),
                                                  model_problem_1d_entry(),
                                                  peridynamics_entry(),
                                                  sph_entry(),
                                                  staged_entry()};
  return entries;
}

} // namespace

const AnalysisEntry& entry_of(spec::Analysis analysis) {
  for (const AnalysisEntry& e : table())
    if (e.analysis == analysis) return e;
  fail("no analysis entry for analysis number ", static_cast<int>(analysis));
}

std::string checkpointing_analyses() {
  std::vector<std::string> names;
  for (const AnalysisEntry& e : table())
    if (e.checkpoints) names.emplace_back(e.name);
  std::string s;
  for (std::size_t k = 0; k < names.size(); ++k)
    s += (k == 0 ? "" : k + 1 == names.size() ? " and " : ", ") + names[k];
  return s;
}

void log_phases(const PhaseTimer& timer) {
  std::string phases;
  for (const auto& [name, s] : timer.phases())
    phases += " " + name + " " + std::to_string(s) + " s;";
  log::info("wall time per phase:", phases);
}

} // namespace mf::app
