// The table of analyses: every analysis the reader knows has one entry, under the name the reader
// accepts, with what check and run need; a name one letter off is refused by the reader.
#include "meshfree/app/analysis.hpp"
#include "meshfree/core/error.hpp"
#include <catch2/catch.hpp>
#include <set>
#include <string>
#include <yaml-cpp/yaml.h>

using namespace mf;

namespace {

/// The reader's message for a file that names only `analysis` (empty: no message).
std::string reader_message(const std::string& analysis) {
  try {
    spec::parse_problem(YAML::Load("name: t\nanalysis: " + analysis + "\n"));
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

} // namespace

TEST_CASE("every analysis has one table entry under the name its reader accepts", "[app]") {
  const spec::Analysis all[] = {spec::Analysis::ElasticStatic, spec::Analysis::ElastoplasticStatic,
                                spec::Analysis::ModelProblem1D, spec::Analysis::Peridynamics,
                                spec::Analysis::Sph, spec::Analysis::Staged};
  std::set<std::string> names;
  for (spec::Analysis a : all) {
    const app::AnalysisEntry& e = app::entry_of(a);
    INFO(e.name);
    CHECK(e.analysis == a);
    CHECK(names.insert(e.name).second);
    CHECK(e.describe != nullptr);
    CHECK(e.run != nullptr);
    // A run that writes checkpoints bounds the instant a restart may hold.
    CHECK((!e.checkpoints || e.end_time != nullptr));
    // The reader takes the name: its complaint is about a later key, not about `analysis`.
    const std::string message = reader_message(e.name);
    CHECK(message.rfind("analysis", 0) != 0);
    // A name one letter off is refused, naming the key.
    CHECK(reader_message(std::string(e.name) + "s").rfind("analysis:", 0) == 0);
  }
  CHECK(app::checkpointing_analyses() == "elastoplastic_static, peridynamics, sph and staged");
}
