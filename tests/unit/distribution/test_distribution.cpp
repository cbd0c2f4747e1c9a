// Domain decomposition of explicit runs (distribution/): id blocks, one rank's part of a body
// with its ghosts, the halo exchange, one field file written by every rank together, and SPH's
// particles moving between ranks with every registered array. Run on one rank by the unit-test
// suite and on two by ctest `mpi.distribution_halo_and_fields`.
#include "field_registry_support.hpp"
#include "meshfree/distribution/local_part.hpp"
#include "meshfree/io/results.hpp"
#include "meshfree/sph/decomposition.hpp"
#include "test_support.hpp"
#include <catch2/catch.hpp>
#include <filesystem>
#include <hdf5.h>

using namespace mf;

namespace {

particles::ParticleSet lattice_block(int nx, int ny, int nz, double dx) {
  particles::ParticleSet p;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) p.add({i * dx, j * dx, k * dx}, dx * dx * dx, 1000.0, 0);
  return p;
}

double value_of(long id, int d) {
  return 1.5 * id + 0.25 * d;
}

} // namespace

TEST_CASE("id blocks split every id once, in sizes that differ by at most one", "[distribution]") {
  for (long total : {0L, 1L, 7L, 100L, 1000003L})
    for (int ranks : {1, 2, 3, 8}) {
      const distribution::IdBlocks b{total, ranks};
      REQUIRE(b.first(0) == 0);
      REQUIRE(b.first(ranks) == total);
      for (int r = 0; r < ranks; ++r) {
        const long size = b.first(r + 1) - b.first(r);
        REQUIRE(size >= total / ranks);
        REQUIRE(size <= total / ranks + 1);
        if (size > 0) {
          REQUIRE(b.owner(b.first(r)) == r);
          REQUIRE(b.owner(b.first(r + 1) - 1) == r);
        }
      }
    }
}

TEST_CASE("a rank's part holds every particle within reach of its own, and the halo keeps the "
          "ghosts' copies",
          "[distribution]") {
  const auto ranks = distribution::Ranks::of(test_session().comm());
  const double dx = 0.5, reach = 3.0001 * dx;
  const particles::ParticleSet whole = lattice_block(12, 9, 7, dx);
  distribution::LocalPart part = distribution::local_part(whole, ranks, reach);
  const particles::ParticleSet& p = part.particles;
  const distribution::IdBlocks blocks{whole.size(), ranks.size};
  REQUIRE(p.owned_count() == blocks.first(ranks.rank + 1) - blocks.first(ranks.rank));
  // Brute force: the particles within reach of an owned one are exactly those held.
  std::vector<char> needed(whole.size(), 0);
  for (int i : p.owned())
    for (int j : whole.all())
      if ((whole.reference(j) - p.reference(i)).norm() <= reach) needed[j] = 1;
  long held = 0;
  for (int j : whole.all()) {
    REQUIRE((part.local_of[j] >= 0) == (needed[j] == 1));
    held += needed[j];
  }
  REQUIRE(held == p.size());
  if (ranks.size == 1) REQUIRE(p.ghosts().size() == 0);
  if (ranks.size > 1) REQUIRE(part.halo.ghosts() > 0);
  // Owners write their values; the exchange brings them to every copy.
  std::vector<double> u(3 * static_cast<std::size_t>(p.size()), -1.0);
  for (int i : p.owned())
    for (int d = 0; d < 3; ++d) u[3 * i + d] = value_of(p.id[i], d);
  part.halo.exchange(u, 3);
  std::vector<long> ids = p.id;
  part.halo.exchange(ids);
  for (int i : p.all()) {
    REQUIRE(ids[i] == p.id[i]);
    for (int d = 0; d < 3; ++d) REQUIRE(u[3 * i + d] == value_of(p.id[i], d));
  }
}

TEST_CASE("a rank's part holds a copy of every registered array of its particles",
          "[distribution]") {
  const auto ranks = distribution::Ranks::of(test_session().comm());
  particles::ParticleSet whole = lattice_block(6, 5, 4, 1.0);
  const particles::ParticleSet body = whole;
  fill_distinct(whole, whole.size());
  whole.X = body.X, whole.id = body.id; // the body's shape and ids stay
  whole.time = 0.5, whole.step = 3;
  const distribution::LocalPart part = distribution::local_part(whole, ranks, 1.5);
  const particles::ParticleSet& p = part.particles;
  for (int i : p.all()) require_same_particle(p, i, whole, static_cast<int>(p.id[i]));
  REQUIRE(p.time == 0.5);
  REQUIRE(p.step == 3);
}

TEST_CASE("SPH particles that change rank take every registered array with them",
          "[distribution]") {
  const auto ranks = distribution::Ranks::of(test_session().comm());
  const int n = 40;
  sph::Hydro h;
  for (int i = 0; i < n; ++i) sph::add_particle(h, {1.0 * i, 0, 0}, 1.0, 1.0, 0.0, 1.0, 0);
  particles::ParticleSet& P = h.particles;
  fill_distinct(P, n);
  fill_distinct(h.fields, n);
  // A row of particles along x, ids by index, displaced a little.
  for (int i = 0; i < n; ++i) {
    P.id[i] = i;
    for (int d = 0; d < 3; ++d) P.X[3 * i + d] = d == 0 ? i : 0.0, P.u[3 * i + d] = 1e-3 * i;
  }
  particles::ParticleSet whole = P;
  const sph::ParticleFields whole_fields = h.fields;
  const auto same_as_whole = [&] {
    REQUIRE(ranks.sum(static_cast<long>(P.owned_count())) == n);
    REQUIRE(P.size() == P.owned_count());
    for (int i : P.owned()) {
      const int g = static_cast<int>(P.id[i]);
      if (i > 0) REQUIRE(P.id[i - 1] < g); // in increasing id
      require_same_particle(P, i, whole, g);
      require_same_particle(h.fields, i, whole_fields, g);
    }
  };
  sph::distribute(h, ranks);
  same_as_whole();
  // The row turned end for end: on two ranks every particle crosses to the other slab.
  for (int g = 0; g < n; ++g) whole.u[3 * g] = (n - 1.0) - 2.0 * g;
  for (int i : P.owned()) P.u[3 * i] = whole.u[3 * P.id[i]];
  sph::migrate(h);
  REQUIRE(ranks.sum(h.migrated) == (ranks.size == 2 ? n : 0));
  same_as_whole();
}

TEST_CASE("a field series spread over the ranks is one file in global id order", "[distribution]") {
  const auto ranks = distribution::Ranks::of(test_session().comm());
  const particles::ParticleSet whole = lattice_block(10, 6, 5, 1.0);
  distribution::LocalPart part = distribution::local_part(whole, ranks, 1.5);
  const particles::ParticleSet& p = part.particles;
  const int n = p.owned_count();
  const std::string dir = "test_distribution_out";
  std::unique_ptr<io::OutputDirectory> out;
  if (ranks.rank == 0) out = std::make_unique<io::OutputDirectory>(dir);
  std::vector<double> xyz(p.X.begin(), p.X.begin() + 3 * n), id(n);
  for (int i = 0; i < n; ++i) id[i] = static_cast<double>(p.id[i]);
  {
    io::FieldOutput fields(
        out.get(), "fields", xyz,
        {ranks.comm, static_cast<std::size_t>(part.first), static_cast<std::size_t>(whole.size())});
    fields.scalar("id", id);
    fields.write(0.0);
    fields.close();
  }
  if (out) out->commit();
  MPI_Barrier(ranks.comm);
  if (ranks.rank == 0) {
    const hid_t f = H5Fopen((dir + "/fields.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    REQUIRE(f >= 0);
    std::vector<double> all_id(whole.size()), all_x(3 * whole.size());
    const hid_t a = H5Dopen2(f, "/step_000000/id", H5P_DEFAULT);
    REQUIRE(H5Dread(a, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, all_id.data()) >= 0);
    const hid_t x = H5Dopen2(f, "/geometry/coordinates", H5P_DEFAULT);
    REQUIRE(H5Dread(x, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, all_x.data()) >= 0);
    H5Dclose(a);
    H5Dclose(x);
    H5Fclose(f);
    for (int i : whole.all()) {
      REQUIRE(all_id[i] == i);
      for (int d = 0; d < 3; ++d) REQUIRE(all_x[3 * i + d] == whole.X[3 * i + d]);
    }
    std::filesystem::remove_all(dir);
  }
}
