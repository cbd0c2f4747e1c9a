#pragma once
// The preload seen by the particles of the next stage: each particle is carried as a passive
// material point through the preload's converged increments. Its strain is the Galerkin strain at
// its reference position, its stress the one the same constitutive update gives from its own
// committed history (implicit::update_point: material, initial stress, J2 return), so no
// projection is made and no particle overshoots its yield surface. A preload computed on a
// symmetric part is mirrored across the given planes to the whole body.
#include "meshfree/implicit/elastoplastic_result.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include <vector>

namespace mf::stages {

using materials::Vec6;

/// How a position maps into the preload's part: the point there and which axes the mirror
/// reversed.
struct Mirrored {
  Vec3 x;
  bool flip[3] = {false, false, false};
};

/// The preload at the particles, increment by increment (increment 0 is the unloaded state).
/// Stresses are 3D Voigt [xx, yy, zz, yz, xz, xy], tension positive.
struct PreloadAtParticles {
  std::vector<double> pseudo_time;         // n / N - 1 per increment: -1 (unloaded) .. 0
  std::vector<std::vector<Vec3>> u;        // [increment][particle]
  std::vector<std::vector<Vec6>> stress;   // [increment][particle]
  std::vector<std::vector<double>> alpha;  // [increment][particle], equivalent plastic strain
  std::vector<materials::MaterialState> history; // final committed history per particle
  std::vector<char> plastic;               // yielding in the last increment
  std::vector<Mirrored> image;             // where each particle lies in the preload's part
  int increments() const { return static_cast<int>(u.size()); }
  const std::vector<Vec3>& final_u() const { return u.back(); }
  const std::vector<Vec6>& final_stress() const { return stress.back(); }
};

/// The preload `r` of `preload` at the particles' reference positions `x` (3 per particle), after
/// mirroring each position into the preload's part. Throws mf::Error naming `key_path` for a
/// particle that no node of the preload covers.
PreloadAtParticles sample_preload(const spec::ProblemSpec& preload,
                                  const implicit::ElastoplasticResult& r,
                                  const std::vector<Vec3>& x,
                                  const std::vector<spec::MirrorPlane>& mirror,
                                  const std::string& key_path);

/// The image of `x` in the part of the body that `inside` (a point of the preload's part) lies
/// in, across each mirror plane `x` is on the other side of.
Mirrored mirror_into(const Vec3& x, const std::vector<spec::MirrorPlane>& mirror,
                     const Vec3& inside);
/// The images of every particle.
std::vector<Mirrored> mirror_into(const std::vector<Vec3>& x,
                                  const std::vector<spec::MirrorPlane>& mirror, const Vec3& inside);

/// Vectors as a flat array, x, y, z of each in turn (the particle set's layout).
std::vector<double> flat(const std::vector<Vec3>& v);

/// Every image of `x` across the mirror planes of the first `dims` axes (x itself first), with
/// the reflections that made it: the preload's part sees the particle at one of them.
std::vector<Mirrored> mirror_images(const Vec3& x, const std::vector<spec::MirrorPlane>& mirror,
                                    int dims);

/// The arrays of a preload of increments 0..N at particles mirrored as `image`, all zero, at
/// pseudo-times n / N - 1; a sampler fills them.
PreloadAtParticles unloaded_preload(int N, std::vector<Mirrored> image);

/// The preload at the particles of the given global ids (indices into pa's particles), in that
/// order: a rank's owned particles after the body was split over ranks.
PreloadAtParticles select_particles(const PreloadAtParticles& pa, const std::vector<long>& ids);

/// A vector, a stress and a material history of the part, seen from the mirrored image.
Vec3 mirrored(const Vec3& v, const Mirrored& m);
Vec6 mirrored(const Vec6& s, const Mirrored& m);
materials::MaterialState mirrored(const materials::MaterialState& h, const Mirrored& m);

} // namespace mf::stages
