// BuildGraph and PartitionNestedDissection on one rank: the symmetrised graph, and METIS's order of the whole graph.
#include "signorini/linalg/parallel_dissection.hpp"

#include <algorithm>
#include <numeric>

#include <gtest/gtest.h>

namespace signorini {
namespace {

TEST(BuildGraph, SymmetrisesSortsAndDropsRepeats) {
  // Edges of a path 0 - 1 - 2 - 3 given in both directions, one twice, and 2 - 0.
  const Graph g = BuildGraph(4, {1, 0, 0, 1, 1, 2, 1, 2, 3, 2, 2, 0});
  EXPECT_EQ(g.xadj, (std::vector<idx_t>{0, 2, 4, 7, 8}));
  EXPECT_EQ(g.adjncy, (std::vector<idx_t>{1, 2, 0, 2, 0, 1, 3, 2}));
}

TEST(PartitionNestedDissection, OneRankIsMetisOfTheWholeGraph) {
  // A 30 x 30 grid, each edge given once from its lower vertex (as a symmetric matrix's upper triangle does).
  const idx_t k = 30, n = k * k;
  std::vector<idx_t> edges;
  for (idx_t v = 0; v < n; ++v) {
    if (v % k + 1 < k) edges.push_back(v), edges.push_back(v + 1);
    if (v + k < n) edges.push_back(v), edges.push_back(v + k);
  }
  std::vector<idx_t> order, metis;
  int status = 0;
  ASSERT_EQ(PartitionNestedDissection(PETSC_COMM_SELF, {0, n}, edges, order, status), 0);
  EXPECT_EQ(status, METIS_OK);
  Graph g = BuildGraph(n, edges);
  ASSERT_EQ(MetisOrder(g, metis), METIS_OK);
  EXPECT_EQ(order, metis);
  std::vector<idx_t> all(n);
  std::iota(all.begin(), all.end(), 0);
  std::sort(order.begin(), order.end());
  EXPECT_EQ(order, all);
}

} // namespace
} // namespace signorini
