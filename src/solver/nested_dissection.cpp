// Nested dissection of a mesh's node graph by coordinate cuts.
#include "signorini/solver/nested_dissection.hpp"

#include <algorithm>
#include <numeric>

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
    for (int a = 0; a < dim; ++a) {
      order_[a].resize(n_);
      std::iota(order_[a].begin(), order_[a].end(), 0);
      std::stable_sort(order_[a].begin(), order_[a].end(),
                       [&](int64_t u, int64_t v) { return x[u * dim + a] < x[v * dim + a]; });
    }
    member_.assign(n_, 0);
    rank_.assign(n_, 0);
    side_.assign(n_, 0);
    buffer_.resize(n_);
    right_.resize(n_ + 2);
    left_.resize(n_ + 2);
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

  /// Ranks along axis a of the nodes of [lo, hi) (rank_), and the best cut across that axis into best.
  void BestCut(std::size_t lo, std::size_t hi, int a, int64_t id, Cut &best) {
    const std::size_t m = hi - lo;
    const int64_t *nodes = order_[a].data() + lo;
    for (std::size_t i = 0; i < m; ++i)
      rank_[nodes[i]] = (int64_t)i;
    // Node i (in axis order) is on the boundary of the second side for the cuts c in (min rank of its neighbours, i]
    // and on the boundary of the first side for c in (i, max rank of its neighbours]: difference arrays give the
    // sizes of both boundaries for every cut in one pass.
    std::fill(right_.begin(), right_.begin() + m + 2, 0);
    std::fill(left_.begin(), left_.begin() + m + 2, 0);
    for (std::size_t i = 0; i < m; ++i) {
      const int64_t v = nodes[i];
      int64_t lowest = (int64_t)i, highest = (int64_t)i;
      for (int64_t e = xadj_[v]; e < xadj_[v + 1]; ++e)
        if (member_[adjncy_[e]] == id) {
          lowest = std::min(lowest, rank_[adjncy_[e]]);
          highest = std::max(highest, rank_[adjncy_[e]]);
        }
      if (lowest < (int64_t)i) ++right_[lowest + 1], --right_[i + 1];
      if (highest > (int64_t)i) ++left_[i + 1], --left_[highest + 1];
    }
    int64_t on_left = 0, on_right = 0;
    for (std::size_t c = 1; c < m; ++c) {
      on_left += left_[c], on_right += right_[c];
      const double f = (double)c / (double)m;
      if (f < MIN_SIDE || f > 1 - MIN_SIDE) continue;
      const double cost = (double)std::min(on_left, on_right) / (f * (1 - f));
      if (best.cost < 0 || cost < best.cost) best = {cost, a, c, on_left <= on_right};
    }
  }

  void Order(std::size_t lo, std::size_t hi) {
    const std::size_t m = hi - lo;
    if (m <= LEAF_NODES) {
      result_.insert(result_.end(), order_[0].begin() + lo, order_[0].begin() + hi);
      return;
    }
    const int64_t id = ++subgraphs_;
    for (std::size_t i = lo; i < hi; ++i)
      member_[order_[0][i]] = id;
    Cut cut;
    for (int a = 0; a < dim_; ++a)
      BestCut(lo, hi, a, id, cut);
    // Sides: 0 before the cut, 1 after it, 2 the separator (the boundary of the chosen side).
    const int64_t *nodes = order_[cut.axis].data() + lo;
    for (std::size_t i = 0; i < m; ++i)
      rank_[nodes[i]] = (int64_t)i;
    for (std::size_t i = 0; i < m; ++i) {
      const int64_t v = nodes[i];
      const bool first = i < cut.position;
      char side = first ? 0 : 1;
      if (first == cut.separator_left)
        for (int64_t e = xadj_[v]; e < xadj_[v + 1] && side < 2; ++e)
          if (member_[adjncy_[e]] == id && (rank_[adjncy_[e]] < (int64_t)cut.position) != first) side = 2;
      side_[v] = side;
    }
    std::size_t count[3] = {0, 0, 0};
    for (int a = 0; a < dim_; ++a) {
      int64_t *list = order_[a].data() + lo;
      std::size_t k = 0;
      for (char s = 0; s < 3; ++s) {
        const std::size_t start = k;
        for (std::size_t i = 0; i < m; ++i)
          if (side_[list[i]] == s) buffer_[k++] = list[i];
        count[(int)s] = k - start;
      }
      std::copy(buffer_.begin(), buffer_.begin() + m, list);
    }
    Order(lo, lo + count[0]);
    Order(lo + count[0], lo + count[0] + count[1]);
    result_.insert(result_.end(), order_[0].begin() + lo + count[0] + count[1], order_[0].begin() + hi);
  }

  const std::vector<int64_t> &xadj_, &adjncy_;
  const int dim_;
  const std::size_t n_;
  std::vector<int64_t> order_[3], member_, rank_, buffer_, right_, left_, result_;
  std::vector<char> side_;
  int64_t subgraphs_ = 0;
};

} // namespace

std::vector<int64_t> CoordinateNestedDissection(const std::vector<int64_t> &xadj, const std::vector<int64_t> &adjncy,
                                                const std::vector<double> &x, int dim) {
  return Dissection(xadj, adjncy, x, dim).Run();
}

} // namespace signorini
