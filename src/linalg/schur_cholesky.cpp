// A serial multifrontal sparse Cholesky factorisation with a Schur complement on the last rows.
#include "signorini/linalg/schur_cholesky.hpp"

#include <petscblaslapack.h>
#include <sys/mman.h>

#include <algorithm>
#include <cmath>

namespace signorini {

namespace {

/// The lower triangle of the permuted pattern by columns: column c < ns holds the rows r >= c (positions) of the
/// entries whose smaller position is c, with the entry numbers (duplicates kept); a last column, ns, holds the
/// entries of two Schur rows, its "row" their place in the m x m Schur front (row + column * m, Schur order).
struct LowerPattern {
  std::vector<int64_t> start, row, entry;
};

LowerPattern BuildLower(int64_t ns, int64_t m, const std::vector<int> &row, const std::vector<int> &col, int base,
                        const std::vector<int64_t> &position) {
  LowerPattern p;
  p.start.assign(ns + 2, 0);
  const std::size_t nnz = row.size();
  for (std::size_t k = 0; k < nnz; ++k) {
    const int64_t a = position[row[k] - base], b = position[col[k] - base];
    ++p.start[std::min(std::min(a, b), ns) + 1];
  }
  for (int64_t c = 0; c <= ns; ++c)
    p.start[c + 1] += p.start[c];
  p.row.resize(nnz);
  p.entry.resize(nnz);
  std::vector<int64_t> next(p.start.begin(), p.start.end() - 1);
  for (std::size_t k = 0; k < nnz; ++k) {
    const int64_t a = position[row[k] - base], b = position[col[k] - base];
    const int64_t lo = std::min(a, b), hi = std::max(a, b);
    const int64_t c = std::min(lo, ns);
    p.row[next[c]] = lo < ns ? hi : (hi - ns) + (lo - ns) * m, p.entry[next[c]] = (int64_t)k;
    ++next[c];
  }
  return p;
}

/// The elimination tree of A11, the columns < ns in the pivot positions `position` (Liu's algorithm with path
/// compression; the Schur rows play no part): parent[j], or ns for a root (ns stands for the Schur rows and joins the
/// roots into one tree).
std::vector<int64_t> EliminationTree(int64_t ns, const std::vector<int> &row, const std::vector<int> &col, int base,
                                     const std::vector<int64_t> &position) {
  // Row by row: the columns c < r of row r < ns, bucketed from the entries.
  std::vector<int64_t> start(ns + 1, 0);
  const std::size_t nnz = row.size();
  for (std::size_t k = 0; k < nnz; ++k) {
    const int64_t a = position[row[k] - base], b = position[col[k] - base];
    if (a != b && std::max(a, b) < ns) ++start[std::max(a, b) + 1];
  }
  for (int64_t r = 0; r < ns; ++r)
    start[r + 1] += start[r];
  std::vector<int64_t> cols(start[ns]), next(start.begin(), start.end() - 1);
  for (std::size_t k = 0; k < nnz; ++k) {
    const int64_t a = position[row[k] - base], b = position[col[k] - base];
    if (a != b && std::max(a, b) < ns) cols[next[std::max(a, b)]++] = std::min(a, b);
  }
  std::vector<int64_t> parent(ns, ns), ancestor(ns, -1);
  for (int64_t r = 0; r < ns; ++r)
    for (int64_t e = start[r]; e < start[r + 1]; ++e)
      for (int64_t i = cols[e]; i != -1 && i < r;) {
        const int64_t up = ancestor[i];
        ancestor[i] = r;
        if (up == -1) parent[i] = r;
        i = up;
      }
  return parent;
}

/// A postorder of the tree (children in increasing order): order[k] is the column visited k-th.
std::vector<int64_t> Postorder(int64_t ns, const std::vector<int64_t> &parent) {
  std::vector<int64_t> head(ns + 1, -1), next(ns, -1), order, stack;
  for (int64_t j = ns - 1; j >= 0; --j)
    next[j] = head[parent[j]], head[parent[j]] = j;
  order.reserve(ns);
  stack.push_back(ns);
  while (!stack.empty()) {
    const int64_t j = stack.back();
    const int64_t child = head[j];
    if (child == -1) {
      stack.pop_back();
      if (j < ns) order.push_back(j);
    } else {
      head[j] = next[child];
      stack.push_back(child);
    }
  }
  return order;
}

/// The column counts of L (diagonal and rows below, Schur rows included) for a postordered tree: Gilbert, Ng and
/// Peyton's row-subtree counting (each row's subtree found from its leaves, the overlaps removed at the least common
/// ancestors, by union-find).
std::vector<int64_t> ColumnCounts(int64_t n, int64_t ns, const std::vector<int64_t> &parent,
                                  const LowerPattern &lower) {
  std::vector<int64_t> delta(ns + 1, 0), first(ns + 1, -1), max_first(n, -1), previous_leaf(n, -1), ancestor(ns + 1);
  for (int64_t k = 0; k < ns; ++k) {
    int64_t j = k;
    delta[j] = first[j] == -1 ? 1 : 0; // a leaf of the tree
    for (; j < ns && first[j] == -1; j = parent[j])
      first[j] = k;
  }
  for (int64_t j = 0; j <= ns; ++j)
    ancestor[j] = j;
  const auto find = [&ancestor](int64_t q) {
    int64_t root = q;
    while (root != ancestor[root])
      root = ancestor[root];
    while (q != root) {
      const int64_t up = ancestor[q];
      ancestor[q] = root;
      q = up;
    }
    return root;
  };
  for (int64_t j = 0; j < ns; ++j) {
    if (parent[j] < ns) --delta[parent[j]];
    for (int64_t e = lower.start[j]; e < lower.start[j + 1]; ++e) {
      const int64_t i = lower.row[e];
      if (i <= j || first[j] <= max_first[i]) continue; // j is not a leaf of row i's subtree
      max_first[i] = first[j];
      const int64_t previous = previous_leaf[i];
      previous_leaf[i] = j;
      ++delta[j];
      if (previous != -1) --delta[find(previous)]; // the overlap of the paths from both leaves
    }
    ancestor[j] = parent[j];
  }
  for (int64_t j = 0; j < ns; ++j)
    if (parent[j] < ns) delta[parent[j]] += delta[j];
  delta.resize(ns);
  return delta;
}

/// A supernode in the making: pivot columns [first, first + cols), rows below, nonzeros of L in its columns.
struct Group {
  int64_t first, cols, rows, nonzeros;
};

/// Fundamental supernodes (column j + 1 continues j's when j is its only child and L's columns nest), then each
/// merged with the supernode just before it when that is its child and the merged panel stays mostly nonzero (the
/// rule of CHOLMOD's relaxed amalgamation: up to 4 columns always, 16 with 80 % zeros, 48 with 10 %, any with 5 %).
/// Merges happen only at a group's start: the groups stay contiguous, each merge a parent with its child.
std::vector<Group> Supernodes(int64_t ns, const std::vector<int64_t> &parent, const std::vector<int64_t> &count) {
  std::vector<int64_t> children(ns + 1, 0);
  for (int64_t j = 0; j < ns; ++j)
    ++children[parent[j]];
  std::vector<Group> groups;
  for (int64_t j = 0; j < ns; ++j) {
    if (!groups.empty()) {
      Group &g = groups.back();
      const int64_t last = g.first + g.cols - 1;
      if (last == j - 1 && parent[last] == j && children[j] == 1 && count[last] == count[j] + 1) {
        ++g.cols, --g.rows, g.nonzeros += count[j];
        continue;
      }
    }
    Group g{j, 1, count[j] - 1, count[j]};
    while (!groups.empty()) {
      const Group &c = groups.back();
      const int64_t c_last = c.first + c.cols - 1;
      if (c_last + 1 != g.first || parent[c_last] < g.first || parent[c_last] >= g.first + g.cols) break;
      const double cols = (double)(c.cols + g.cols), stored = cols * (cols + 1) / 2 + cols * (double)g.rows;
      const double zeros = 1 - (double)(c.nonzeros + g.nonzeros) / stored;
      if (!(cols <= 4 || (cols <= 16 && zeros < 0.8) || (cols <= 48 && zeros < 0.1) || zeros < 0.05)) break;
      g = {c.first, c.cols + g.cols, g.rows, c.nonzeros + g.nonzeros};
      groups.pop_back();
    }
    groups.push_back(g);
  }
  return groups;
}

/// Each group's rows below it (sorted positions, appended to structure from start[s]): its columns' entries below it
/// and its children's rows below it; kids[s]: its children (kids[groups.size()]: the Schur front's, the groups whose
/// first row below is a Schur row). The row counts are checked against the column counts.
PetscErrorCode SupernodeRows(int64_t n, int64_t ns, const std::vector<Group> &groups, const LowerPattern &lower,
                             std::vector<int64_t> &structure, std::vector<int64_t> &start,
                             std::vector<std::vector<int64_t>> &kids) {
  PetscFunctionBeginUser;
  const int64_t count_groups = (int64_t)groups.size();
  std::vector<int64_t> supernode_of(ns), mark(n, -1), rows;
  for (int64_t s = 0; s < count_groups; ++s)
    for (int64_t j = groups[s].first; j < groups[s].first + groups[s].cols; ++j)
      supernode_of[j] = s;
  kids.assign(count_groups + 1, {});
  start.assign(count_groups + 1, 0);
  structure.clear();
  for (int64_t s = 0; s < count_groups; ++s) {
    const int64_t last = groups[s].first + groups[s].cols - 1;
    const auto add = [&](int64_t r) {
      if (r > last && mark[r] != s) mark[r] = s, rows.push_back(r);
    };
    rows.clear();
    for (int64_t j = groups[s].first; j <= last; ++j)
      for (int64_t e = lower.start[j]; e < lower.start[j + 1]; ++e)
        add(lower.row[e]);
    for (int64_t c : kids[s])
      for (int64_t k = start[c]; k < start[c] + groups[c].rows; ++k)
        add(structure[k]);
    std::sort(rows.begin(), rows.end());
    start[s] = (int64_t)structure.size();
    structure.insert(structure.end(), rows.begin(), rows.end());
    PetscCheck((int64_t)rows.size() == groups[s].rows, PETSC_COMM_SELF, PETSC_ERR_PLIB,
               "SchurCholesky: supernode %" PetscInt64_FMT " has %" PetscInt64_FMT
               " rows, its counts say %" PetscInt64_FMT,
               s, (int64_t)rows.size(), groups[s].rows);
    if (!rows.empty()) kids[rows.front() < ns ? supernode_of[rows.front()] : count_groups].push_back(s);
  }
  start[count_groups] = (int64_t)structure.size();
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode SchurCholesky::Buffer::Resize(std::size_t n) {
  PetscFunctionBeginUser;
  if (n == size_) PetscFunctionReturn(0);
  Clear();
  const std::size_t bytes = n * sizeof(double);
  if (bytes < LARGE_BYTES) {
    small_.resize(n);
    data_ = small_.data();
  } else {
    // Aligned to 2 MiB inside a slightly larger mapping, so that whole huge pages cover it.
    const std::size_t huge = std::size_t(2) << 20;
    mapped_bytes_ = bytes + huge;
    mapping_ = mmap(nullptr, mapped_bytes_, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    PetscCheck(mapping_ != MAP_FAILED, PETSC_COMM_SELF, PETSC_ERR_MEM,
               "could not map %.3g GB for the Cholesky factors", 1e-9 * (double)mapped_bytes_);
    const std::size_t start = ((std::size_t)mapping_ + huge - 1) & ~(huge - 1);
    data_ = reinterpret_cast<double *>(start);
    (void)madvise(data_, bytes, MADV_HUGEPAGE); // advice only: without it, 4 KiB pages
  }
  size_ = n;
  PetscFunctionReturn(0);
}

void SchurCholesky::Buffer::Clear() {
  if (mapping_ && mapping_ != MAP_FAILED) (void)munmap(mapping_, mapped_bytes_);
  mapping_ = nullptr;
  mapped_bytes_ = 0;
  std::vector<double>().swap(small_);
  data_ = nullptr;
  size_ = 0;
}

void SchurCholesky::Clear() {
  n_ = m_ = ns_ = 0;
  for (auto *v : {&position_, &structure_, &child_, &relative_, &entry_, &offset_, &diagonal_entry_})
    std::vector<int64_t>().swap(*v);
  factor_.Clear();
  stack_.Clear();
  for (auto *v : {&work_, &forward_})
    std::vector<double>().swap(*v);
  std::vector<Supernode>().swap(supernodes_);
  factor_size_ = max_front_ = max_stack_ = 0;
  flops_ = diagonal_max_ = 0;
  factored_ = false;
}

PetscErrorCode SchurCholesky::Layout(const std::vector<int64_t> &lower_start, const std::vector<int64_t> &lower_row,
                                     const std::vector<std::vector<int64_t>> &kids) {
  PetscFunctionBeginUser;
  // Factor layout, flops, the stack of update matrices (children are pushed in postorder and popped by their parent:
  // its children's matrices are the top of the stack), and where in each front the entries of A and the children's
  // rows go (row + column * front size).
  const int64_t count_groups = (int64_t)supernodes_.size() - 1;
  std::vector<int64_t> local(n_, -1);
  int64_t top = 0;
  for (int64_t s = 0; s <= count_groups; ++s) {
    Supernode &sn = supernodes_[s];
    const bool schur = s == count_groups;
    const int64_t front = sn.cols + sn.rows;
    if (!schur) {
      sn.factor = factor_size_;
      factor_size_ += front * sn.cols;
      max_front_ = std::max(max_front_, front * front);
      const double c = (double)sn.cols, r = (double)sn.rows;
      flops_ += c * c * c / 3 + r * c * c + r * r * c;
    }
    for (int64_t k = 0; k < sn.cols; ++k)
      local[sn.first + k] = k;
    for (int64_t k = 0; k < sn.rows; ++k)
      local[structure_[sn.structure + k]] = sn.cols + k;
    sn.entries = lower_start[sn.first], sn.entries_end = lower_start[sn.first + sn.cols + (schur ? 1 : 0)];
    for (int64_t j = sn.first; j < sn.first + sn.cols; ++j)
      for (int64_t e = lower_start[j]; e < lower_start[j + 1]; ++e) {
        const int64_t i = local[lower_row[e]];
        PetscCheck(i >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "SchurCholesky: an entry outside its front");
        offset_[e] = i + (j - sn.first) * front;
      }
    sn.children = (int64_t)child_.size();
    sn.relative = (int64_t)relative_.size();
    for (int64_t c : kids[s]) {
      const Supernode &cn = supernodes_[c];
      child_.push_back(c);
      for (int64_t k = cn.structure; k < cn.structure + cn.rows; ++k)
        relative_.push_back(local[structure_[k]]);
      top -= cn.rows * cn.rows;
    }
    sn.children_end = (int64_t)child_.size();
    if (!schur) top += sn.rows * sn.rows;
    max_stack_ = std::max(max_stack_, top);
    for (int64_t k = 0; k < sn.cols; ++k)
      local[sn.first + k] = -1;
    for (int64_t k = 0; k < sn.rows; ++k)
      local[structure_[sn.structure + k]] = -1;
  }
  PetscCheck(top == 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "SchurCholesky: update matrices left on the stack");
  PetscFunctionReturn(0);
}

PetscErrorCode SchurCholesky::Analyse(PetscInt n, PetscInt m, const std::vector<int> &row, const std::vector<int> &col,
                                      const std::vector<int> &position, int base) {
  PetscFunctionBeginUser;
  Clear();
  PetscCheck(m >= 0 && m <= n && (PetscInt)position.size() == n && row.size() == col.size(), PETSC_COMM_SELF,
             PETSC_ERR_ARG_SIZ, "SchurCholesky: inconsistent sizes");
  n_ = n, m_ = m, ns_ = n - m;
  const int64_t ns = ns_;
  position_.resize(n);
  for (PetscInt i = 0; i < n; ++i)
    position_[i] = position[i] - base;
  // The tree of the given order, then the same order relabelled by a postorder of the tree (the same fill, the same
  // tree relabelled).
  std::vector<int64_t> parent(ns);
  {
    const std::vector<int64_t> given_parent = EliminationTree(ns, row, col, base, position_);
    const std::vector<int64_t> order = Postorder(ns, given_parent);
    PetscCheck((int64_t)order.size() == ns, PETSC_COMM_SELF, PETSC_ERR_PLIB, "SchurCholesky: postorder incomplete");
    std::vector<int64_t> relabel(ns + 1);
    for (int64_t k = 0; k < ns; ++k)
      relabel[order[k]] = k;
    relabel[ns] = ns;
    for (int64_t j = 0; j < ns; ++j)
      parent[relabel[j]] = relabel[given_parent[j]];
    for (auto &p : position_)
      if (p < ns) p = relabel[p];
  }
  LowerPattern lower = BuildLower(ns, m, row, col, base, position_);
  const std::vector<Group> groups = Supernodes(ns, parent, ColumnCounts(n, ns, parent, lower));
  const int64_t count_groups = (int64_t)groups.size();
  std::vector<int64_t> start;
  std::vector<std::vector<int64_t>> kids;
  PetscCall(SupernodeRows(n, ns, groups, lower, structure_, start, kids));
  supernodes_.resize(count_groups + 1); // the last one: the Schur front, its rows the Schur rows
  for (int64_t s = 0; s < count_groups; ++s) {
    Supernode &sn = supernodes_[s];
    sn.first = groups[s].first, sn.cols = groups[s].cols, sn.rows = groups[s].rows, sn.structure = start[s];
  }
  Supernode &schur = supernodes_[count_groups];
  schur.first = ns, schur.cols = 0, schur.rows = m, schur.structure = (int64_t)structure_.size();
  for (int64_t k = 0; k < m; ++k)
    structure_.push_back(ns + k);

  // The entries of A by front (a supernode's columns are consecutive, the Schur front's last) and the diagonal.
  entry_ = std::move(lower.entry);
  offset_.resize(entry_.size());
  for (int64_t j = 0; j < ns; ++j)
    for (int64_t e = lower.start[j]; e < lower.start[j + 1]; ++e)
      if (lower.row[e] == j) diagonal_entry_.push_back(entry_[e]), diagonal_entry_.push_back(j);
  for (int64_t e = lower.start[ns]; e < lower.start[ns + 1]; ++e)
    offset_[e] = lower.row[e];

  PetscCall(Layout(lower.start, lower.row, kids));
  // The front of a supernode is laid out where its panel goes, so the factor has room for the largest update matrix
  // after the last panel.
  PetscCall(factor_.Resize(factor_size_ + max_front_));
  PetscFunctionReturn(0);
}

PetscErrorCode SchurCholesky::BlasSizes(const Supernode &sn, PetscBLASInt &front, PetscBLASInt &cols,
                                        PetscBLASInt &rows) {
  PetscFunctionBeginUser;
  PetscCall(PetscBLASIntCast(sn.cols + sn.rows, &front));
  PetscCall(PetscBLASIntCast(sn.cols, &cols));
  PetscCall(PetscBLASIntCast(sn.rows, &rows));
  PetscFunctionReturn(0);
}

PetscErrorCode SchurCholesky::Factor(const std::vector<double> &value, std::vector<double> &schur, bool &positive) {
  PetscFunctionBeginUser;
  factored_ = positive = false;
  {
    std::vector<double> diagonal(ns_, 0.0);
    for (std::size_t k = 0; k < diagonal_entry_.size(); k += 2)
      diagonal[diagonal_entry_[k + 1]] += value[diagonal_entry_[k]];
    diagonal_max_ = 0;
    for (double d : diagonal)
      diagonal_max_ = std::max(diagonal_max_, std::abs(d));
  }
  const double tolerance = PIVOT_TOLERANCE * diagonal_max_;
  PetscCall(stack_.Resize(max_stack_));
  schur.assign(m_ * m_, 0.0);
  const int64_t count = (int64_t)supernodes_.size() - 1;
  int64_t top = 0;
  for (int64_t s = 0; s <= count; ++s) {
    const Supernode &sn = supernodes_[s];
    const int64_t front = sn.cols + sn.rows;
    double *F = s == count ? schur.data() : factor_.data() + sn.factor;
    if (s < count) // the lower triangle, which alone the factorisation reads and writes
      for (int64_t j = 0; j < front; ++j)
        std::fill(F + j + j * front, F + (j + 1) * front, 0.0);
    for (int64_t k = sn.entries; k < sn.entries_end; ++k)
      F[offset_[k]] += value[entry_[k]];
    // The children's update matrices (the top of the stack, in the order pushed), added at their rows' places.
    int64_t size = 0;
    for (int64_t c = sn.children; c < sn.children_end; ++c)
      size += supernodes_[child_[c]].rows * supernodes_[child_[c]].rows;
    const int64_t *relative = relative_.data() + sn.relative;
    for (int64_t c = sn.children, at = top - size; c < sn.children_end; ++c) {
      const int64_t rows = supernodes_[child_[c]].rows;
      const double *update = stack_.data() + at;
      for (int64_t j = 0; j < rows; ++j) {
        double *column = F + relative[j] * front;
        for (int64_t i = j; i < rows; ++i)
          column[relative[i]] += update[i + j * rows];
      }
      at += rows * rows, relative += rows;
    }
    top -= size;
    if (s == count) break;
    // L11 = chol(F11), L21 = F21 L11^-T, the update matrix F22 - L21 L21^T.
    PetscBLASInt nf, nc, nr, info;
    PetscCall(BlasSizes(sn, nf, nc, nr));
    LAPACKpotrf_("L", &nc, F, &nf, &info);
    if (info != 0) PetscFunctionReturn(0);
    for (int64_t j = 0; j < sn.cols; ++j)
      if (!(F[j + j * front] * F[j + j * front] > tolerance)) PetscFunctionReturn(0);
    if (sn.rows == 0) continue;
    const double one = 1, minus_one = -1;
    BLAStrsm_("R", "L", "T", "N", &nr, &nc, &one, F, &nf, F + sn.cols, &nf);
    double *F22 = F + sn.cols + sn.cols * front;
    BLASsyrk_("L", "N", &nr, &nc, &minus_one, F + sn.cols, &nf, &one, F22, &nf);
    double *update = stack_.data() + top;
    for (int64_t j = 0; j < sn.rows; ++j)
      std::copy(F22 + j + j * front, F22 + sn.rows + j * front, update + j + j * sn.rows);
    top += sn.rows * sn.rows;
  }
  for (int64_t j = 0; j < m_; ++j)
    for (int64_t i = j + 1; i < m_; ++i)
      schur[j + i * m_] = schur[i + j * m_];
  factored_ = positive = true;
  PetscFunctionReturn(0);
}

PetscErrorCode SchurCholesky::Forward(const double *b, double *reduced) {
  PetscFunctionBeginUser;
  PetscCheck(factored_, PETSC_COMM_SELF, PETSC_ERR_ORDER, "SchurCholesky: no factors");
  forward_.resize(n_);
  for (int64_t i = 0; i < n_; ++i)
    forward_[position_[i]] = b[i];
  work_.resize(n_);
  const int64_t count = (int64_t)supernodes_.size() - 1;
  const double one = 1, zero = 0;
  const PetscBLASInt inc = 1;
  for (int64_t s = 0; s < count; ++s) {
    const Supernode &sn = supernodes_[s];
    const double *L = factor_.data() + sn.factor;
    double *y = forward_.data() + sn.first;
    const int64_t *rows = structure_.data() + sn.structure;
    if (sn.cols * (sn.cols + sn.rows) > SMALL_PANEL) {
      PetscBLASInt nf, nc, nr;
      PetscCall(BlasSizes(sn, nf, nc, nr));
      BLAStrsm_("L", "L", "N", "N", &nc, &inc, &one, L, &nf, y, &nc);
      if (sn.rows == 0) continue;
      BLASgemv_("N", &nr, &nc, &one, L + sn.cols, &nf, y, &inc, &zero, work_.data(), &inc);
      for (int64_t i = 0; i < sn.rows; ++i)
        forward_[rows[i]] -= work_[i];
      continue;
    }
    // A small panel: the same by columns, without the calls' overhead.
    const int64_t front = sn.cols + sn.rows;
    for (int64_t j = 0; j < sn.cols; ++j) {
      const double *column = L + j * front;
      const double yj = y[j] /= column[j];
      for (int64_t i = j + 1; i < sn.cols; ++i)
        y[i] -= column[i] * yj;
      for (int64_t i = 0; i < sn.rows; ++i)
        forward_[rows[i]] -= column[sn.cols + i] * yj;
    }
  }
  std::copy(forward_.begin() + ns_, forward_.end(), reduced);
  PetscFunctionReturn(0);
}

PetscErrorCode SchurCholesky::Backward(const double *x2, double *x) {
  PetscFunctionBeginUser;
  PetscCheck(factored_ && (int64_t)forward_.size() == n_, PETSC_COMM_SELF, PETSC_ERR_ORDER,
             "SchurCholesky: no forward elimination");
  std::copy(x2, x2 + m_, forward_.begin() + ns_);
  const double one = 1, minus_one = -1;
  const PetscBLASInt inc = 1;
  for (int64_t s = (int64_t)supernodes_.size() - 2; s >= 0; --s) {
    const Supernode &sn = supernodes_[s];
    const double *L = factor_.data() + sn.factor;
    double *y = forward_.data() + sn.first;
    const int64_t *rows = structure_.data() + sn.structure;
    for (int64_t i = 0; i < sn.rows; ++i)
      work_[i] = forward_[rows[i]];
    if (sn.cols * (sn.cols + sn.rows) > SMALL_PANEL) {
      PetscBLASInt nf, nc, nr;
      PetscCall(BlasSizes(sn, nf, nc, nr));
      if (sn.rows > 0) BLASgemv_("T", &nr, &nc, &minus_one, L + sn.cols, &nf, work_.data(), &inc, &one, y, &inc);
      BLAStrsm_("L", "L", "T", "N", &nc, &inc, &one, L, &nf, y, &nc);
      continue;
    }
    // A small panel: the same by columns (dot products), without the calls' overhead.
    const int64_t front = sn.cols + sn.rows;
    for (int64_t j = sn.cols - 1; j >= 0; --j) {
      const double *column = L + j * front;
      double sum = y[j];
      for (int64_t i = 0; i < sn.rows; ++i)
        sum -= column[sn.cols + i] * work_[i];
      for (int64_t i = j + 1; i < sn.cols; ++i)
        sum -= column[i] * y[i];
      y[j] = sum / column[j];
    }
  }
  for (int64_t i = 0; i < n_; ++i)
    x[i] = forward_[position_[i]];
  forward_.clear();
  PetscFunctionReturn(0);
}

} // namespace signorini
