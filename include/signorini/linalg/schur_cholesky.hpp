// A serial sparse Cholesky factorisation (multifrontal, by supernodes, dense work in BLAS/LAPACK) of the leading block
// of a symmetric matrix whose last rows are kept out of the elimination: it yields their Schur complement.
#pragma once

#include <petscsys.h>

#include <cstdint>
#include <vector>

namespace signorini {

/// For A = [A11 A12; A21 A22] (n rows, the m rows of A22 last in the pivot order), A11 = L L^T and the dense
/// S = A22 - A21 A11^-1 A12; then the forward elimination of a right-hand side b, which gives the reduced right-hand
/// side b_2 - A21 A11^-1 b_1, and the backward substitution that, given x_2, completes the solution of A x = b.
/// The same operations as MUMPS with a Schur complement (ICNTL(19), ICNTL(26) = 1 / 2), for an A11 that is positive
/// definite: a pivot that is not safely positive stops the factorisation (Factor's `positive`), and the caller then
/// uses a factorisation that pivots. Rank-local (no communication).
///
/// Analyse: the elimination tree of the permuted A11 (Liu), a postorder, the column counts (Gilbert, Ng and Peyton),
/// fundamental supernodes merged with their last child while few zeros are added, each supernode's row structure,
/// and for every front where the entries of A and the children's update matrices go. Factor: for each supernode in
/// postorder, its dense front (entries of A, the children's update matrices added), potrf of the pivot block, trsm
/// of the rows below, syrk of the update matrix, which goes on a stack for the parent; the update matrices left for
/// the rows of A22 sum to A22 - S.
///
/// Why our own and not CHOLMOD (SuiteSparse, which Debian's PETSc has): CHOLMOD gives no Schur complement, and its
/// two routes to one, measured on the Hertz matrices with the same METIS order (docs/performance.md, *The Schur
/// Cholesky against CHOLMOD*), lose where the kept factorisation runs by default: factoring A11 and forming
/// W = L^-1 P A12 is 3 to 9 times slower at every size; factoring the whole matrix with a shifted multiplier block
/// is 3.4 times slower at 20k rows in 2D and 1.5 times at 16k in 3D, 1.1 to 1.3 times at 195k and 1M in 2D, and
/// 1.15 times faster from about 40k rows in 3D (where it would need a shift chosen in advance and CHOLMOD's internal
/// factor arrays).
class SchurCholesky {
public:
  /// An array of doubles (contents undefined after Resize); from LARGE_BYTES on in a mapping of its own, advised to
  /// transparent huge pages: a first write to fresh memory costs about 1.7 us per 4 KiB page on the machines measured
  /// (6 ms for the 14 MiB factor of the 20k-row Hertz matrix), 2 MiB pages about a tenth of that.
  class Buffer {
  public:
    static constexpr std::size_t LARGE_BYTES = std::size_t(4) << 20;
    Buffer() = default;
    Buffer(const Buffer &) = delete;
    Buffer &operator=(const Buffer &) = delete;
    ~Buffer() { Clear(); }
    [[nodiscard]] PetscErrorCode Resize(std::size_t n);
    double *data() { return data_; }
    const double *data() const { return data_; }
    std::size_t size() const { return size_; }
    void Clear();

  private:
    double *data_ = nullptr;
    std::size_t size_ = 0, mapped_bytes_ = 0;
    void *mapping_ = nullptr;
    std::vector<double> small_;
  };

  /// The pattern: entries (row[k] - base, col[k] - base) (one triangle, duplicates allowed and summed) of an n x n
  /// symmetric matrix, and position[i] - base the pivot position of row i (a permutation of 0..n-1); the rows at
  /// positions n - m .. n - 1 are the Schur rows, in that order.
  [[nodiscard]] PetscErrorCode Analyse(PetscInt n, PetscInt m, const std::vector<int> &row, const std::vector<int> &col,
                                       const std::vector<int> &position, int base);
  /// Elimination flops (potrf, trsm and syrk of every front, the additions not counted) and factor entries.
  double Flops() const { return flops_; }
  double Entries() const { return (double)factor_size_; }
  /// The numerical factorisation of the values (value[k] belongs to entry k of Analyse). schur: S (m x m, column
  /// major, the order of the Schur rows). positive: false when a pivot of A11 was not larger than PIVOT_TOLERANCE
  /// times the largest diagonal entry of A11 (A11 is then singular, nearly so, or indefinite; the factors are void).
  [[nodiscard]] PetscErrorCode Factor(const std::vector<double> &value, std::vector<double> &schur, bool &positive);
  /// The forward elimination of b (n entries, original row order), kept for Backward, and the reduced right-hand side
  /// b_2 - A21 A11^-1 b_1 (m entries, Schur order).
  [[nodiscard]] PetscErrorCode Forward(const double *b, double *reduced);
  /// x (n entries, original row order): the solution of A x = b for the b of the last Forward whose Schur part is
  /// x_2 (m entries, Schur order).
  [[nodiscard]] PetscErrorCode Backward(const double *x2, double *x);
  /// Frees everything.
  void Clear();

  /// Pivots not above this fraction of A11's largest diagonal entry stop the factorisation (Factor): far above the
  /// round-off of a singular block (1e-16), far below the pivots of the elastic stiffness matrices met (1e-6 of it
  /// for the 2D Hertz meshes).
  static constexpr double PIVOT_TOLERANCE = 1e-11;
  /// Panels (columns x front rows) up to this many entries are solved by plain loops in Forward and Backward, larger
  /// ones by BLAS (trsm, gemv): the 2D Hertz matrices' thousands of small supernodes cost more in calls than in work.
  static constexpr int64_t SMALL_PANEL = 2048;

private:
  struct Supernode {
    int64_t first = 0, cols = 0, rows = 0;  ///< pivot columns [first, first + cols), rows below them
    int64_t structure = 0;                  ///< start of the rows below in structure_ (global positions, sorted)
    int64_t factor = 0;                     ///< start of the (cols + rows) x cols panel in factor_
    int64_t entries = 0, entries_end = 0;   ///< the entries of A assembled into this front (entry_/offset_)
    int64_t children = 0, children_end = 0; ///< the children (child_), whose update matrices are on the stack
    int64_t relative = 0;                   ///< start of the children's rows mapped into this front (relative_)
  };

  /// From the supernodes and their rows (structure_) and the lower pattern by columns (lower_start, lower_row; the
  /// last column the Schur front's entries): the factor's layout, the flops, the stack's size, and where in each front
  /// the entries of A and the children's rows go (offset_, relative_, child_; kids[s]: supernode s's children).
  [[nodiscard]] PetscErrorCode Layout(const std::vector<int64_t> &lower_start, const std::vector<int64_t> &lower_row,
                                      const std::vector<std::vector<int64_t>> &kids);
  /// A supernode's front size (its panel's leading dimension), pivot columns and rows below, as BLAS takes them.
  [[nodiscard]] static PetscErrorCode BlasSizes(const Supernode &sn, PetscBLASInt &front, PetscBLASInt &cols,
                                                PetscBLASInt &rows);

  int64_t n_ = 0, m_ = 0, ns_ = 0;    ///< rows, Schur rows, eliminated rows
  std::vector<int64_t> position_;     ///< final pivot position of each original row
  std::vector<Supernode> supernodes_; ///< in postorder; the last one, with no pivots, is the Schur front
  std::vector<int64_t> structure_, child_, relative_, entry_, offset_;
  Buffer factor_, stack_;
  std::vector<double> work_, forward_;
  int64_t factor_size_ = 0, max_front_ = 0, max_stack_ = 0;
  double flops_ = 0, diagonal_max_ = 0;
  std::vector<int64_t> diagonal_entry_; ///< pairs (entry, position) of the entries on A11's diagonal
  bool factored_ = false;
};

} // namespace signorini
