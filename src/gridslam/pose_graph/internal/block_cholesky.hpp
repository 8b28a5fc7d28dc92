// Sparse Cholesky factorization A = L L^T of a symmetric positive-definite matrix made of 3x3
// blocks, the linear solver of the Gauss-Newton/LM back end (gauss_newton.hpp). Pose graphs have
// one 3x3 block per vertex and per edge, so working on blocks instead of scalars divides the index
// work and the ordering problem by nine and turns every update into a dense 3x3 product. The
// pattern is fixed at construction: a fill-reducing ordering of the blocks (approximate minimum
// degree, Eigen's AMDOrdering), the elimination tree and the row patterns of L (Davis, "Direct
// Methods for Sparse Linear Systems", 2006, §4: etree, ereach, up-looking Cholesky) are computed
// once; Factorize() then only does numeric work.
#pragma once

#include <utility>
#include <vector>

#include <Eigen/Core>

namespace gridslam::pose_graph::internal {

class BlockCholesky {
 public:
  /// Where block (a, b) of A lives: values()[index], transposed if `transposed`.
  struct Slot {
    int index = -1;
    bool transposed = false;
  };

  /// `num_blocks` diagonal blocks plus the off-diagonal blocks at `pairs` (a != b; either order;
  /// duplicates allowed).
  BlockCholesky(int num_blocks, const std::vector<std::pair<int, int>>& pairs);

  /// Storage of block (a, b) of A; (a, b) must be a diagonal block or one of the pairs (checked).
  [[nodiscard]] Slot Find(int a, int b) const;
  /// Upper-triangle block storage of A (in the permuted order); fill through Find().
  [[nodiscard]] std::vector<Eigen::Matrix3d>& values() { return values_; }
  void SetZero();

  /// Factorizes A + lambda D, D = I or, with `scaled`, D = diag(A) (Marquardt). False if it is
  /// not numerically positive definite.
  bool Factorize(double lambda = 0.0, bool scaled = false);
  /// Solves (A + lambda D) x = b with the last factorization.
  [[nodiscard]] Eigen::VectorXd Solve(const Eigen::VectorXd& b) const;
  /// x^T A x (without lambda).
  [[nodiscard]] double Quadratic(const Eigen::VectorXd& x) const;
  /// Largest diagonal entry of A.
  [[nodiscard]] double MaxDiagonal() const;
  /// Number of 3x3 blocks in L (fill-in included).
  [[nodiscard]] long FactorBlocks() const { return static_cast<long>(l_rows_.size()); }

 private:
  int n_ = 0;
  std::vector<int> new_of_old_;
  std::vector<int> old_of_new_;
  // A, upper triangle by columns of the permuted order; the diagonal block comes last in each.
  std::vector<int> a_col_;
  std::vector<int> a_row_;
  std::vector<Eigen::Matrix3d> values_;
  // Symbolic factorization: row patterns of L in topological order.
  std::vector<int> pattern_ptr_;
  std::vector<int> pattern_;
  // L by columns; the diagonal block first in each, stored as its inverse L_kk^-1.
  std::vector<int> l_col_;
  std::vector<int> l_rows_;
  std::vector<Eigen::Matrix3d> l_values_;
  // Workspace.
  std::vector<Eigen::Matrix3d> x_;
  std::vector<int> next_;
};

}  // namespace gridslam::pose_graph::internal
