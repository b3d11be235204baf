// The automatic solver choice: memory sizes, the node graph's estimate of the factor against the factorisation of the
// scalar pattern, and the decisions.
#include "signorini/linalg/solver_choice.hpp"
#include "signorini/linalg/parallel_dissection.hpp"
#include "signorini/linalg/schur_cholesky.hpp"

#include <gtest/gtest.h>

namespace signorini {
namespace {

TEST(ParseMemorySize, UnitsArePowersOf1024) {
  double b = 0;
  EXPECT_TRUE(ParseMemorySize("512M", b));
  EXPECT_EQ(b, 512.0 * 1024 * 1024);
  EXPECT_TRUE(ParseMemorySize("1.5GB", b));
  EXPECT_EQ(b, 1.5 * 1024 * 1024 * 1024);
  EXPECT_TRUE(ParseMemorySize("2e9", b));
  EXPECT_EQ(b, 2e9);
  EXPECT_TRUE(ParseMemorySize("64k", b));
  EXPECT_EQ(b, 65536.0);
  EXPECT_TRUE(ParseMemorySize("1T", b));
  EXPECT_EQ(b, 1024.0 * 1024 * 1024 * 1024);
}

TEST(ParseMemorySize, RefusesWhatIsNoSize) {
  double b = 7;
  for (const char *text : {"", "lots", "-1G", "0", "1X", "0x10", "1e400", "inf", "nan", "G", "1GG"})
    EXPECT_FALSE(ParseMemorySize(text, b)) << text;
  EXPECT_EQ(b, 7);
}

/// The edges of a k^3 grid of nodes with the neighbours of a hexahedral mesh (the 26 around a node).
std::vector<idx_t> GridEdges(int k) {
  std::vector<idx_t> edges;
  for (int z = 0; z < k; ++z)
    for (int y = 0; y < k; ++y)
      for (int x = 0; x < k; ++x)
        for (int dz = -1; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              const int a = x + dx, b = y + dy, c = z + dz;
              if ((dx || dy || dz) && a >= 0 && a < k && b >= 0 && b < k && c >= 0 && c < k)
                edges.push_back(x + k * (y + k * z)), edges.push_back(a + k * (b + k * c));
            }
  return edges;
}

TEST(EstimateFactorization, NodeGraphTimesBlocksIsTheScalarFactor) {
  // The estimate (node graph, times dim^2 entries and dim^3 flops) against the symbolic factorisation of the scalar
  // pattern of 3 dofs per node in the same METIS order of the nodes.
  const int k = 14, dim = 3;
  const PetscInt nodes = k * k * k;
  SolverProblem problem;
  problem.u_dofs = dim * nodes, problem.dim = dim;
  problem.node_graph = [&](PetscInt &n, std::vector<idx_t> &edges) -> PetscErrorCode {
    n = nodes;
    edges = GridEdges(k);
    return 0;
  };
  FactorEstimate est;
  ASSERT_EQ(EstimateFactorization(PETSC_COMM_SELF, problem, est), 0);
  EXPECT_TRUE(est.exact);

  Graph g = BuildGraph((idx_t)nodes, GridEdges(k));
  std::vector<idx_t> order;
  ASSERT_EQ(MetisOrder(g, order), METIS_OK);
  std::vector<int> position(dim * nodes), row, col;
  for (std::size_t p = 0; p < order.size(); ++p)
    for (int c = 0; c < dim; ++c) position[dim * order[p] + c] = (int)(dim * p + c);
  for (idx_t v = 0; v < g.Size(); ++v)
    for (int a = 0; a < dim; ++a) {
      for (int b = 0; b <= a; ++b) row.push_back(dim * v + a), col.push_back(dim * v + b);
      for (idx_t e = g.xadj[v]; e < g.xadj[v + 1]; ++e)
        if (g.adjncy[e] > v)
          for (int b = 0; b < dim; ++b) row.push_back((int)(dim * g.adjncy[e] + b)), col.push_back(dim * v + a);
    }
  SchurCholesky scalar;
  ASSERT_EQ(scalar.Analyse(dim * nodes, 0, row, col, position, 0), 0);
  EXPECT_GT(est.entries, 0.8 * scalar.Entries());
  EXPECT_LT(est.entries, 1.25 * scalar.Entries());
  EXPECT_GT(est.flops, 0.6 * scalar.Flops());
  EXPECT_LT(est.flops, 1.5 * scalar.Flops());
}

TEST(ChooseSolverPath, Decisions) {
  SolverProblem problem;
  problem.u_dofs = 30000, problem.multipliers = 500, problem.dim = 3;
  problem.node_graph = [](PetscInt &n, std::vector<idx_t> &edges) -> PetscErrorCode {
    n = 10 * 10 * 10;
    edges = GridEdges(10);
    return 0;
  };
  SolverPathOptions opts;
  SolverChoice c;
  // Enough memory: direct; a budget far below the model's estimate: iterative, by the model alone.
  opts.budget = 1e12, opts.budget_set = PETSC_TRUE;
  ASSERT_EQ(ChooseSolverPath(PETSC_COMM_SELF, opts, false, true, problem, c), 0);
  EXPECT_EQ(c.path, SolverPath::DIRECT);
  EXPECT_EQ(c.by, ChosenBy::AUTO);
  opts.budget = 1e6;
  ASSERT_EQ(ChooseSolverPath(PETSC_COMM_SELF, opts, false, true, problem, c), 0);
  EXPECT_EQ(c.path, SolverPath::ITERATIVE);
  EXPECT_FALSE(c.factor.exact);
  EXPECT_NE(c.why.find("of -contact_memory_budget"), std::string::npos) << c.why;
  // The run's own solver decides; -contact_solver before it.
  ASSERT_EQ(ChooseSolverPath(PETSC_COMM_SELF, opts, true, true, problem, c), 0);
  EXPECT_EQ(c.path, SolverPath::DIRECT);
  EXPECT_EQ(c.by, ChosenBy::SOLVER_OPTIONS);
  ASSERT_EQ(ChooseSolverPath(PETSC_COMM_SELF, opts, true, false, problem, c), 0);
  EXPECT_EQ(c.path, SolverPath::ITERATIVE);
  opts.path = SolverPath::DIRECT;
  ASSERT_EQ(ChooseSolverPath(PETSC_COMM_SELF, opts, true, false, problem, c), 0);
  EXPECT_EQ(c.path, SolverPath::DIRECT);
  EXPECT_EQ(c.by, ChosenBy::CONTACT_SOLVER);
}

} // namespace
} // namespace signorini
