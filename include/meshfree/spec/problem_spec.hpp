#pragma once
// A validated, typed problem description (what a problem YAML file says): the front every
// analysis shares (name, units, analysis, model, materials, geometry) and the part of each
// analysis. Plain data: no solver header is included.
#include "meshfree/core/types.hpp"
#include "meshfree/geometry/domain.hpp"
#include "meshfree/geometry/outline_file.hpp"
#include "meshfree/materials/elastic.hpp"
#include "meshfree/materials/j2_plasticity.hpp"
#include "meshfree/spec/galerkin_spec.hpp"
#include "meshfree/spec/material_spec.hpp"
#include "meshfree/spec/pd_spec.hpp"
#include "meshfree/spec/region_spec.hpp"
#include "meshfree/spec/solid_spec.hpp"
#include "meshfree/spec/sph_spec.hpp"
#include "meshfree/spec/stage_spec.hpp"
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>
#include <yaml-cpp/yaml.h>

namespace mf::spec {

enum class Analysis {
  ElasticStatic,
  ElastoplasticStatic,
  ModelProblem1D,
  Peridynamics,
  Sph,
  Staged
};

/// model.type: the kinematic model of every analysis (uniaxial strain is 1D SPH).
enum class ModelType { PlaneStress, PlaneStrain, Solid3D, UniaxialStrain };

struct ProblemSpec;

/// analysis: staged with more than one stage: each stage as a one-analysis problem (the shared
/// keys copied into it) and how it starts from an earlier one (links[k] for stages[k]).
struct StagedSpec {
  std::vector<ProblemSpec> stages;
  std::vector<StageLink> links;
};

/// What belongs to one analysis alone (ProblemSpec::analysis says which; elastic and
/// elastoplastic hold a GalerkinSpec for a plane body, a SolidSpec for a 3D one).
using AnalysisPart =
    std::variant<GalerkinSpec, SolidSpec, ModelProblem1D, PdSpec, SphSpec, StagedSpec>;

/// A problem: the front every analysis shares, then its analysis's own part.
struct ProblemSpec {
  std::string name;
  std::string description;
  std::string units;
  Analysis analysis = Analysis::ElasticStatic;
  std::string stage;        // the stage's name when the file lists `stages:`
  ProblemSettings settings; // every scalar of the file after --set (a restart compares them)
  ModelType model_type = ModelType::PlaneStress;
  int dimension = 2;
  materials::PlaneModel model = materials::PlaneModel::PlaneStress; // 2D: from model_type
  double thickness = 1.0;
  std::vector<MaterialSpec> materials; // the file's `materials:` list
  geometry::Domain domain = geometry::Domain::rectangle({0.0, 0.0}, {1.0, 1.0}); // 2D bodies
  std::vector<geometry::FilePart> file_parts;   // the groups of surfaces of a 2D geometry file
  std::vector<geometry::FileCurve> file_curves; // and its groups of curves
  std::optional<Box> box; // a 3D body (peridynamics, model solid_3d)
  AnalysisPart part;

  /// The part of the analysis; asking for another analysis's part is a program error.
  GalerkinSpec& galerkin() { return part_as<GalerkinSpec>(); }
  const GalerkinSpec& galerkin() const { return part_as<GalerkinSpec>(); }
  SolidSpec& solid() { return part_as<SolidSpec>(); }
  const SolidSpec& solid() const { return part_as<SolidSpec>(); }
  PdSpec& pd() { return part_as<PdSpec>(); }
  const PdSpec& pd() const { return part_as<PdSpec>(); }
  SphSpec& sph() { return part_as<SphSpec>(); }
  const SphSpec& sph() const { return part_as<SphSpec>(); }
  StagedSpec& staged() { return part_as<StagedSpec>(); }
  const StagedSpec& staged() const { return part_as<StagedSpec>(); }
  ModelProblem1D& model_1d() { return part_as<ModelProblem1D>(); }
  const ModelProblem1D& model_1d() const { return part_as<ModelProblem1D>(); }
  bool is_pd() const { return std::holds_alternative<PdSpec>(part); }
  bool is_sph() const { return std::holds_alternative<SphSpec>(part); }
  bool is_galerkin() const { return std::holds_alternative<GalerkinSpec>(part); }
  bool is_solid() const { return std::holds_alternative<SolidSpec>(part); }

  /// Galerkin analyses: the body's material, its elasticity and its plasticity law (none: elastic
  /// at its points), all from the one materials list.
  const MaterialSpec& body_material() const {
    return materials.at(is_solid() ? solid().material_index : galerkin().material_index);
  }
  materials::IsotropicElastic elasticity() const { return {body_material().E, body_material().nu}; }
  const std::optional<materials::ConstitutiveModel>& plasticity() const {
    return body_material().plasticity;
  }

private:
  template <class Part> Part& part_as() {
    if (Part* p = std::get_if<Part>(&part)) return *p;
    throw std::logic_error("problem '" + name + "': its analysis has no such part");
  }
  template <class Part> const Part& part_as() const {
    return const_cast<ProblemSpec*>(this)->part_as<Part>();
  }
};

/// Reads and validates a problem file. `overrides` are "key.path=value" strings applied first.
/// Throws mf::Error with the key path of the first problem found.
ProblemSpec read_problem(const std::string& path, const std::vector<std::string>& overrides = {});
/// `base_dir` (ending in '/', or empty) resolves relative paths in the file, e.g. mesh files.
/// `stage` names the stage of a staged run the file is (empty: a problem of its own).
ProblemSpec parse_problem(YAML::Node root, const std::string& base_dir = "",
                          const std::string& stage = "");

/// The pieces of the boundary a region picks (its named edges, clipped to its box); throws
/// naming `key_path` if none.
std::vector<geometry::Curve> select_boundary(const geometry::Domain& domain, const Region& on,
                                             const std::string& key_path);

} // namespace mf::spec
