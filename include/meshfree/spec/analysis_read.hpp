#pragma once
// The reader of each analysis: what follows the front (name, units, analysis, model, materials,
// geometry) that read_problem reads for every analysis.
#include "meshfree/spec/key_reader.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include <string>

namespace mf::spec {

/// geometry: a rectangle, a polygon or the plane body of a geometry file (`file`, relative to
/// `base_dir`, and `scale`), with rounded corners and holes of any outline (2D bodies); a file's
/// groups of surfaces and of curves go to `p`'s file_parts and file_curves where given.
geometry::Domain read_domain(KeyReader& geometry, const std::string& base_dir,
                             ProblemSpec* p = nullptr);
/// `file` (relative to `base_dir`) and its `scale`: what the geometry file holds (errors name the
/// key `file`).
geometry::OutlineFile read_geometry_file(KeyReader& r, const std::string& base_dir);
/// The part named by `group` among a geometry file's groups of surfaces; an error naming `group`
/// lists them where it is not one of them.
const geometry::FilePart& file_part(KeyReader& r, const std::vector<geometry::FilePart>& parts);

/// One entry of `parts:` (a group of the geometry file's surfaces and its material).
struct PartMaterial {
  std::string key_path; // parts[k]
  const geometry::FilePart* part = nullptr;
  int material = 0; // into p.materials
};
/// parts: [{group, material}] of a body read from a geometry file (p.file_parts): every group
/// once, each with a material of the file; refused where the body has no groups, a group is
/// given twice or not at all, or the groups do not cover the body. Empty without the key.
std::vector<PartMaterial> read_part_materials(KeyReader& r, const ProblemSpec& p);

/// elastic_static and elastoplastic_static: the material, discretisation, exact solution, body
/// force, boundary, steps, nonlinear and output.
void parse_galerkin(KeyReader& r, ProblemSpec& p, const std::string& base_dir);
/// elastic_static and elastoplastic_static with model solid_3d (the geometry, read with the
/// front, has emplaced the SolidSpec): material, discretisation, exact solution, body force,
/// boundary conditions on faces, steps and nonlinear.
void parse_solid(KeyReader& r, ProblemSpec& p, const std::string& base_dir);
/// model_problem_1d: problem_1d, discretisation and penalty.
void parse_model_1d(KeyReader& r, ProblemSpec& p, const std::string& base_dir);
/// peridynamics: material, interfaces, discretisation, regions, notches, cracks, functions,
/// boundary, impactors, time and output. `base_dir` resolves relative file names.
PdSpec parse_pd(KeyReader& r, const ProblemSpec& front, const std::string& base_dir);
/// sph: discretisation, regions (the bodies of particles), boundary, detonation, viscosity,
/// artificial stress, interface, time and output.
SphSpec parse_sph(KeyReader& r, const ProblemSpec& front, const std::string& base_dir);
/// staged: the `stages:` list, each stage a problem of the shared keys and its own, and how each
/// starts from an earlier one (ProblemSpec::stages and ::links).
void parse_stages(KeyReader& r, ProblemSpec& p, const std::string& base_dir);
/// The names of the conditions of a stage a later stage holds or releases: its boundary
/// conditions, its body force ("body_force") and its gravity ("gravity").
std::vector<std::string> stage_conditions(const ProblemSpec& p);

} // namespace mf::spec
