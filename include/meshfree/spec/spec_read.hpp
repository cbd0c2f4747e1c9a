#pragma once
// Readers shared by every analysis: names, points, boxes and regions, gauges, blasts, the
// `materials:` list and the `time:` map. Every error names the key path.
#include "meshfree/spec/key_reader.hpp"
#include "meshfree/spec/material_spec.hpp"
#include "meshfree/spec/region_spec.hpp"
#include <optional>
#include <string>
#include <vector>

namespace mf::spec {

/// Names end up in file names and CSV/JSON keys: letters, digits, '_' and '-' only.
void check_name(KeyReader& r, const std::string& key, const std::string& name,
                bool may_be_empty = false);

/// A point or vector with `dim` components (the others are 0).
Point read_point(KeyReader& r, const std::string& key, int dim);
/// A non-zero vector with `dim` components, scaled to unit length.
Point read_unit_vector(KeyReader& r, const std::string& key, int dim);
/// [[x0, ...], [x1, ...]] with `dim` coordinates per corner; the other axes are unbounded.
Box read_box(KeyReader& r, const std::string& key, int dim);

/// Which shapes a region may be made of.
enum RegionShapes : unsigned {
  kBox = 1u,
  kCircle = 2u, // `circle: {center: [x, y], radius}`: only what lies inside is kept
  kRing = 4u,   // `ring: {center, inner_radius, outer_radius}` (2D)
  kHoles = 8u,  // `holes: [{center: [x, y], radius} | {polygon} | {rectangle} | {slot}]`: what
                //   lies inside is left out
  kEdges = 16u, // `edges: name` or `edges: [names]`: boundary pieces of a 2D body
  kSolids = kBox | kCircle | kRing | kHoles,
};

/// The region keys of a map (box, circle, ring, holes, edges: those `shapes` allows; the others
/// are left unread, so finish() rejects them).
Region read_region(KeyReader& r, int dim, unsigned shapes);

/// A hole of outline other than a circle, named `name`: `polygon: [[x, y], ...]`, `rectangle:
/// {origin, size}` or `slot: {from: [x, y], to: [x, y], width}`; null where the entry gives
/// none of them.
std::optional<geometry::OutlineHole> read_outline_hole(KeyReader& h, const std::string& name);

/// output.gauges: [{name, at}], names unique.
std::vector<GaugeSpec> read_gauges(KeyReader& output, int dim);

/// What sets the step of an explicit analysis.
enum class StepControl { Safety, Courant };
/// time: {end, dt, safety} (StepControl::Safety) or {end, courant} (StepControl::Courant).
TimeSpec read_time(KeyReader& r, StepControl control);
/// The history_interval, fields_interval and gauges of an `output:` map (the other keys are the
/// caller's, who also calls finish()).
SeriesOutputSpec read_series_output(KeyReader& output, int dim);

/// A `blast:` map: {tnt_mass, burst: surface|free_air, charge_at, normal, near_field}.
BlastSpec read_blast(KeyReader& b, int dim, bool near_field);

/// The J2 yield stress and isotropic hardening law of a map with `yield_stress` and `hardening`
/// (perfect | {type: linear|voce|swift|table, ...}); sets j.sigma0 (Swift and table laws define
/// it themselves).
void read_hardening(KeyReader& p, materials::J2Parameters& j);

/// The `materials:` list, every part of every entry read and checked.
std::vector<MaterialSpec> read_materials(KeyReader& r);
/// A table [[x0, y0], [x1, y1], ...] of at least `at_least` rows with strictly ascending x (and
/// positive y where asked), as a piecewise-linear function.
materials::PiecewiseLinear read_table(KeyReader& r, const std::string& key, std::size_t at_least,
                                      bool positive_values);
/// The index of the material `name`, or an error at `key` listing the known names.
int find_material(KeyReader& r, const std::string& key, const std::vector<MaterialSpec>& list,
                  const std::string& name);
/// An error "<material key path>.<part>: <message>".
[[noreturn]] void material_error(const MaterialSpec& m, const std::string& part,
                                 const std::string& message);

} // namespace mf::spec
