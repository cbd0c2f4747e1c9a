#pragma once
// Filling a shape table, plane (ShapeTable) or solid (SolidShapeTable), from points' support
// lists: the one loop both meshfree spaces run, threaded, with the progress of large tables.
#include "meshfree/core/progress.hpp"
#include "meshfree/implicit/meshfree_space.hpp" // Csr
#include <algorithm>
#include <atomic>
#include <omp.h>
#include <vector>

namespace mf::implicit {

/// The shape functions at points rows[k] (their support lists in `support`): `evaluate(p, nodes,
/// count, phi, dphi)` writes point p's values (and gradients where dphi is not null) and returns
/// false where its moment matrix is singular. `unknowns` (the body's DOFs) and `nodes` decide
/// whether the loop reports its progress: only for large bodies and tables of more points than
/// nodes (the body's integration points; not a few boundary points, nor samples at the nodes).
/// Returns the lowest failing point in `failed` (-1 if none), so that a message naming it does
/// not depend on the threads.
template <class Table, class Evaluate>
Table tabulate_shapes(const std::vector<int>& rows, const Csr& support, bool gradients,
                      double unknowns, int nodes, Evaluate evaluate, int& failed) {
  Table t;
  const int n = static_cast<int>(rows.size());
  t.offset.assign(n + 1, 0);
  for (int k = 0; k < n; ++k) t.offset[k + 1] = t.offset[k] + support.size(rows[k]);
  t.node.resize(t.offset[n]);
  t.phi.resize(t.offset[n]);
  if (gradients) t.dphi.resize(t.offset[n]);
  std::atomic<int> lowest{-1};
  log::PhaseProgress progress("shape functions", n,
                              unknowns >= log::kProgressUnknowns && n > nodes);
#pragma omp parallel for schedule(dynamic, 256)
  for (int k = 0; k < n; ++k) {
    progress.count_one(omp_get_thread_num());
    const int p = rows[k];
    const int* nb = support.index.data() + support.offset[p];
    const int count = support.size(p);
    std::copy(nb, nb + count, t.node.begin() + t.offset[k]);
    if (!evaluate(p, nb, count, t.phi.data() + t.offset[k],
                  gradients ? t.dphi.data() + t.offset[k] : nullptr)) {
      int seen = lowest.load();
      while ((seen < 0 || p < seen) && !lowest.compare_exchange_weak(seen, p)) {
      }
    }
  }
  progress.finish();
  failed = lowest;
  return t;
}

} // namespace mf::implicit
