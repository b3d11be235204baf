// Nested dissection of a mesh's node graph by coordinate cuts.
#include "signorini/linalg/nested_dissection.hpp"

#include <algorithm>
#include <utility>

namespace signorini {

namespace {

constexpr std::size_t LEAF_NODES = 8; ///< subgraphs this small are eliminated as they are
constexpr double MIN_SIDE = 0.3;      ///< the smaller side of a cut holds at least this fraction of the nodes

/// The recursion's state. order_[a][lo, hi) holds the nodes of the current subgraph sorted along axis a (the lists
/// are split stably, so every subgraph keeps its nodes sorted along every axis without sorting again).
class Dissection {
public:
  Dissection(const std::vector<int64_t> &xadj, const std::vector<int64_t> &adjncy, const std::vector<double> &x,
             int dim)
      : xadj_(xadj), adjncy_(adjncy), dim_(dim), n_(x.size() / dim) {
    // Sorted by (coordinate, node), the order of a stable sort by coordinate, with each key beside its node instead of
    // fetched through the node number at every comparison.
    std::vector<std::pair<double, int64_t>> keyed(n_);
    for (int a = 0; a < dim; ++a) {
      for (std::size_t v = 0; v < n_; ++v)
        keyed[v] = {x[v * dim + a], (int64_t)v};
      std::sort(keyed.begin(), keyed.end());
      order_[a].resize(n_);
      for (std::size_t i = 0; i < n_; ++i)
        order_[a][i] = keyed[i].second;
    }
    state_.assign(n_, {0, {0, 0, 0}});
    side_.assign(n_, 0);
    buffer_.resize(n_);
    for (int a = 0; a < dim; ++a)
      right_[a].resize(n_ + 2), left_[a].resize(n_ + 2);
    result_.reserve(n_);
  }

  std::vector<int64_t> Run() {
    Order(0, n_);
    return std::move(result_);
  }

private:
  struct Cut {
    double cost = -1;
    int axis = 0;
    std::size_t position = 0; ///< the first position of the second side along the axis
    bool separator_left = false;
  };

  /// The best cut of the subgraph [lo, hi) (its nodes marked id) across any axis, the earlier axis at a tie.
  Cut BestCut(std::size_t lo, std::size_t hi, int64_t id) {
    const std::size_t m = hi - lo;
    for (int a = 0; a < dim_; ++a) {
      const int64_t *nodes = order_[a].data() + lo;
      for (std::size_t i = 0; i < m; ++i)
        state_[nodes[i]].rank[a] = (int64_t)i;
      std::fill(right_[a].begin(), right_[a].begin() + m + 2, 0);
      std::fill(left_[a].begin(), left_[a].begin() + m + 2, 0);
    }
    // Node v of rank i along axis a is on the boundary of the second side for the cuts c in (min rank of its
    // neighbours, i] and on the boundary of the first side for c in (i, max rank of its neighbours]: difference
    // arrays give the sizes of both boundaries for every cut. One pass over the neighbours serves every axis (they
    // are the ordering's main cost: scattered reads).
    const int64_t *nodes = order_[0].data() + lo;
    for (std::size_t k = 0; k < m; ++k) {
      const int64_t v = nodes[k];
      int64_t lowest[3], highest[3];
      for (int a = 0; a < dim_; ++a)
        lowest[a] = highest[a] = state_[v].rank[a];
      for (int64_t e = xadj_[v]; e < xadj_[v + 1]; ++e) {
        const NodeState &w = state_[adjncy_[e]];
        if (w.subgraph != id) continue;
        for (int a = 0; a < dim_; ++a)
          lowest[a] = std::min(lowest[a], w.rank[a]), highest[a] = std::max(highest[a], w.rank[a]);
      }
      for (int a = 0; a < dim_; ++a) {
        const int64_t i = state_[v].rank[a];
        if (lowest[a] < i) ++right_[a][lowest[a] + 1], --right_[a][i + 1];
        if (highest[a] > i) ++left_[a][i + 1], --left_[a][highest[a] + 1];
      }
    }
    Cut best;
    for (int a = 0; a < dim_; ++a) {
      int64_t on_left = 0, on_right = 0;
      for (std::size_t c = 1; c < m; ++c) {
        on_left += left_[a][c], on_right += right_[a][c];
        const double f = (double)c / (double)m;
        if (f < MIN_SIDE || f > 1 - MIN_SIDE) continue;
        const double cost = (double)std::min(on_left, on_right) / (f * (1 - f));
        if (best.cost < 0 || cost < best.cost) best = {cost, a, c, on_left <= on_right};
      }
    }
    return best;
  }

  void Order(std::size_t lo, std::size_t hi) {
    const std::size_t m = hi - lo;
    if (m <= LEAF_NODES) {
      result_.insert(result_.end(), order_[0].begin() + lo, order_[0].begin() + hi);
      return;
    }
    const int64_t id = ++subgraphs_;
    for (std::size_t i = lo; i < hi; ++i)
      state_[order_[0][i]].subgraph = id;
    const Cut cut = BestCut(lo, hi, id);
    // Sides: 0 before the cut, 1 after it, 2 the separator (the boundary of the chosen side).
    const int64_t *nodes = order_[cut.axis].data() + lo;
    std::size_t count[3] = {0, 0, 0};
    for (std::size_t i = 0; i < m; ++i) {
      const int64_t v = nodes[i];
      const bool first = i < cut.position;
      char side = first ? 0 : 1;
      if (first == cut.separator_left)
        for (int64_t e = xadj_[v]; e < xadj_[v + 1] && side < 2; ++e) {
          const NodeState &w = state_[adjncy_[e]];
          if (w.subgraph == id && (w.rank[cut.axis] < (int64_t)cut.position) != first) side = 2;
        }
      side_[v] = side;
      ++count[(int)side];
    }
    // Each list split stably into the three sides in one pass.
    for (int a = 0; a < dim_; ++a) {
      int64_t *list = order_[a].data() + lo;
      std::size_t next[3] = {0, count[0], count[0] + count[1]};
      for (std::size_t i = 0; i < m; ++i)
        buffer_[next[(int)side_[list[i]]]++] = list[i];
      std::copy(buffer_.begin(), buffer_.begin() + m, list);
    }
    Order(lo, lo + count[0]);
    Order(lo + count[0], lo + count[0] + count[1]);
    result_.insert(result_.end(), order_[0].begin() + lo + count[0] + count[1], order_[0].begin() + hi);
  }

  const std::vector<int64_t> &xadj_, &adjncy_;
  const int dim_;
  const std::size_t n_;
  /// A node's subgraph (the id of the last subgraph it was in) and its ranks along the axes in that subgraph, side by
  /// side: the passes over the neighbours read them together.
  struct NodeState {
    int64_t subgraph, rank[3];
  };
  std::vector<NodeState> state_;
  std::vector<int64_t> order_[3], buffer_, right_[3], left_[3], result_;
  std::vector<char> side_;
  int64_t subgraphs_ = 0;
};

} // namespace

std::vector<int64_t> CoordinateNestedDissection(const std::vector<int64_t> &xadj, const std::vector<int64_t> &adjncy,
                                                const std::vector<double> &x, int dim) {
  return Dissection(xadj, adjncy, x, dim).Run();
}

} // namespace signorini
