// CoordinateNestedDissection on grid graphs: a permutation, with far less fill than the grid's natural order.
#include "signorini/linalg/nested_dissection.hpp"

#include <algorithm>
#include <numeric>

#include <gtest/gtest.h>

namespace signorini {
namespace {

/// The graph of a k^dim grid of nodes (neighbours along each axis) with node coordinates; scale stretches axis 0.
struct Grid {
  std::vector<int64_t> xadj{0}, adjncy;
  std::vector<double> x;
};

Grid MakeGrid(int k, int dim, double scale) {
  Grid g;
  const int n = dim == 2 ? k * k : k * k * k;
  for (int v = 0; v < n; ++v) {
    int c[3] = {v % k, (v / k) % k, v / (k * k)};
    for (int d = 0; d < dim; ++d)
      g.x.push_back((d == 0 ? scale : 1.0) * c[d]);
    for (int d = 0; d < dim; ++d)
      for (int s : {-1, 1}) {
        int w[3] = {c[0], c[1], c[2]};
        w[d] += s;
        if (w[d] < 0 || w[d] >= k) continue;
        g.adjncy.push_back(w[0] + k * w[1] + k * k * w[2]);
      }
    g.xadj.push_back((int64_t)g.adjncy.size());
  }
  return g;
}

/// Entries of the Cholesky factor's lower triangle (diagonal included) for the elimination order `order` (position k
/// holds the node eliminated k-th): the row subtrees of the elimination tree.
double FactorEntries(const Grid &g, const std::vector<int64_t> &order) {
  const int64_t n = (int64_t)order.size();
  std::vector<int64_t> position(n), parent(n, -1), ancestor(n, -1), mark(n, -1);
  for (int64_t k = 0; k < n; ++k)
    position[order[k]] = k;
  for (int64_t k = 0; k < n; ++k)
    for (int64_t e = g.xadj[order[k]]; e < g.xadj[order[k] + 1]; ++e) {
      int64_t r = position[g.adjncy[e]];
      if (r >= k) continue;
      while (ancestor[r] != -1 && ancestor[r] != k) {
        const int64_t next = ancestor[r];
        ancestor[r] = k, r = next;
      }
      if (ancestor[r] == -1) ancestor[r] = k, parent[r] = k;
    }
  double entries = 0;
  for (int64_t k = 0; k < n; ++k) {
    mark[k] = k;
    ++entries;
    for (int64_t e = g.xadj[order[k]]; e < g.xadj[order[k] + 1]; ++e)
      for (int64_t j = position[g.adjncy[e]]; j < k && mark[j] != k; j = parent[j])
        mark[j] = k, ++entries;
  }
  return entries;
}

TEST(CoordinateNestedDissection, OrdersEveryNodeOnceWithLittleFill) {
  for (int dim : {2, 3})
    for (double scale : {1.0, 3.0}) {
      SCOPED_TRACE("dim " + std::to_string(dim) + " scale " + std::to_string(scale));
      const Grid g = MakeGrid(dim == 2 ? 100 : 16, dim, scale);
      const std::vector<int64_t> order = CoordinateNestedDissection(g.xadj, g.adjncy, g.x, dim);
      std::vector<int64_t> sorted = order, all(g.xadj.size() - 1);
      std::sort(sorted.begin(), sorted.end());
      std::iota(all.begin(), all.end(), 0);
      ASSERT_EQ(sorted, all);
      // The natural order is banded (bandwidth k^(dim-1)); a nested dissection needs far less: a quarter of it for
      // the 100 x 100 grid (260k entries against 1.0M), 40 % for the 16^3 grid (388k against 991k).
      const double natural = FactorEntries(g, all), dissected = FactorEntries(g, order);
      EXPECT_LT(dissected, 0.5 * natural) << "natural order " << natural;
    }
}

} // namespace
} // namespace signorini
