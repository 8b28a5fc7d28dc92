#include "gridslam/pose_graph/internal/block_cholesky.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>

#include "gridslam/common/check.hpp"

namespace gridslam::pose_graph::internal {

namespace {

std::size_t U(int i) { return static_cast<std::size_t>(i); }

// Cholesky factor of a symmetric 3x3 block, returned as its inverse L^-1 (lower triangular),
// which is all the factorization and the solves need. False unless positive definite.
bool InverseCholesky3(const Eigen::Matrix3d& d, Eigen::Matrix3d* inverse) {
  if (!(d(0, 0) > 0.0)) {
    return false;
  }
  const double l00 = std::sqrt(d(0, 0));
  const double l10 = d(1, 0) / l00;
  const double l20 = d(2, 0) / l00;
  const double t11 = d(1, 1) - l10 * l10;
  if (!(t11 > 0.0)) {
    return false;
  }
  const double l11 = std::sqrt(t11);
  const double l21 = (d(2, 1) - l20 * l10) / l11;
  const double t22 = d(2, 2) - l20 * l20 - l21 * l21;
  if (!(t22 > 0.0)) {
    return false;
  }
  const double l22 = std::sqrt(t22);
  const double i00 = 1.0 / l00;
  const double i11 = 1.0 / l11;
  const double i22 = 1.0 / l22;
  const double i10 = -l10 * i00 * i11;
  const double i21 = -l21 * i11 * i22;
  const double i20 = -(l20 * i00 + l21 * i10) * i22;
  *inverse << i00, 0.0, 0.0, i10, i11, 0.0, i20, i21, i22;
  return true;
}

}  // namespace

BlockCholesky::BlockCholesky(int num_blocks, const std::vector<std::pair<int, int>>& pairs)
    : n_(num_blocks) {
  GRIDSLAM_CHECK(n_ >= 0) << "negative block count";
  // Fill-reducing ordering of the block graph.
  {
    std::vector<Eigen::Triplet<double>> pattern;
    pattern.reserve(U(n_) + 2 * pairs.size());
    for (int b = 0; b < n_; ++b) {
      pattern.emplace_back(b, b, 1.0);
    }
    for (const auto& [a, b] : pairs) {
      GRIDSLAM_CHECK(a != b && a >= 0 && b >= 0 && a < n_ && b < n_) << "bad block pair";
      pattern.emplace_back(a, b, 1.0);
      pattern.emplace_back(b, a, 1.0);
    }
    Eigen::SparseMatrix<double> graph(n_, n_);
    graph.setFromTriplets(pattern.begin(), pattern.end());
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse;
    Eigen::AMDOrdering<int> amd;
    amd(graph, inverse);
    old_of_new_.assign(inverse.indices().data(), inverse.indices().data() + n_);
    new_of_old_.assign(U(n_), 0);
    for (int k = 0; k < n_; ++k) {
      new_of_old_[U(old_of_new_[U(k)])] = k;
    }
  }
  // Upper triangle of the permuted A by columns: rows i < k, sorted, then the diagonal.
  std::vector<std::vector<int>> columns(U(n_));
  for (const auto& [a, b] : pairs) {
    const int i = std::min(new_of_old_[U(a)], new_of_old_[U(b)]);
    const int k = std::max(new_of_old_[U(a)], new_of_old_[U(b)]);
    columns[U(k)].push_back(i);
  }
  a_col_.assign(U(n_) + 1, 0);
  for (int k = 0; k < n_; ++k) {
    auto& rows = columns[U(k)];
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
    rows.push_back(k);
    a_col_[U(k) + 1] = a_col_[U(k)] + static_cast<int>(rows.size());
    a_row_.insert(a_row_.end(), rows.begin(), rows.end());
  }
  values_.assign(a_row_.size(), Eigen::Matrix3d::Zero());

  // Elimination tree (Davis §4.1, with path compression through `ancestor`).
  std::vector<int> parent(U(n_), -1);
  std::vector<int> ancestor(U(n_), -1);
  for (int k = 0; k < n_; ++k) {
    for (int p = a_col_[U(k)]; p < a_col_[U(k) + 1] - 1; ++p) {
      for (int i = a_row_[U(p)]; i != -1 && i < k;) {
        const int next = ancestor[U(i)];
        ancestor[U(i)] = k;
        if (next == -1) {
          parent[U(i)] = k;
        }
        i = next;
      }
    }
  }
  // Row patterns of L (ereach, Davis §4.2), topologically ordered, and column counts.
  std::vector<int> mark(U(n_), -1);
  std::vector<int> stack(U(n_));
  std::vector<int> counts(U(n_), 1);
  pattern_ptr_.assign(U(n_) + 1, 0);
  for (int k = 0; k < n_; ++k) {
    mark[U(k)] = k;
    int top = n_;
    for (int p = a_col_[U(k)]; p < a_col_[U(k) + 1] - 1; ++p) {
      // Walk up from each entry of column k until a node already reached; each path is pushed
      // as a block on a stack, which leaves every node before its ancestors (cs_ereach).
      int length = 0;
      for (int i = a_row_[U(p)]; mark[U(i)] != k; i = parent[U(i)]) {
        stack[U(length++)] = i;
        mark[U(i)] = k;
      }
      while (length > 0) {
        stack[U(--top)] = stack[U(--length)];
      }
    }
    pattern_.insert(pattern_.end(), stack.begin() + top, stack.end());
    for (int q = top; q < n_; ++q) {
      ++counts[U(stack[U(q)])];
    }
    pattern_ptr_[U(k) + 1] = static_cast<int>(pattern_.size());
  }
  l_col_.assign(U(n_) + 1, 0);
  for (int k = 0; k < n_; ++k) {
    l_col_[U(k) + 1] = l_col_[U(k)] + counts[U(k)];
  }
  l_rows_.assign(U(l_col_[U(n_)]), 0);
  l_values_.assign(l_rows_.size(), Eigen::Matrix3d::Zero());
  x_.assign(U(n_), Eigen::Matrix3d::Zero());
  next_.assign(U(n_), 0);
}

BlockCholesky::Slot BlockCholesky::Find(int a, int b) const {
  const int pa = new_of_old_[U(a)];
  const int pb = new_of_old_[U(b)];
  const int i = std::min(pa, pb);
  const int k = std::max(pa, pb);
  const auto begin = a_row_.begin() + a_col_[U(k)];
  const auto end = a_row_.begin() + a_col_[U(k) + 1];
  const auto it = i == k ? end - 1 : std::lower_bound(begin, end - 1, i);
  GRIDSLAM_CHECK(it != end && *it == i) << "block (" << a << ", " << b << ") not in the pattern";
  // Stored block (i, k) has the rows of the lower permuted index.
  return Slot{static_cast<int>(it - a_row_.begin()), pa > pb};
}

void BlockCholesky::SetZero() {
  std::fill(values_.begin(), values_.end(), Eigen::Matrix3d::Zero());
}

bool BlockCholesky::Factorize(double lambda, bool scaled) {
  // Up-looking Cholesky (Davis §4.7) on 3x3 blocks: row k of L from a sparse triangular solve.
  for (int k = 0; k < n_; ++k) {
    const int end = a_col_[U(k) + 1] - 1;
    for (int p = a_col_[U(k)]; p < end; ++p) {
      x_[U(a_row_[U(p)])] = values_[U(p)];
    }
    Eigen::Matrix3d d = values_[U(end)];
    if (scaled) {
      d.diagonal() *= 1.0 + lambda;
    } else {
      d.diagonal().array() += lambda;
    }
    for (int q = pattern_ptr_[U(k)]; q < pattern_ptr_[U(k) + 1]; ++q) {
      const int i = pattern_[U(q)];
      // Y = L_ii^-1 X_i (the diagonal slot holds L_ii^-1), then X_r -= L_ri Y for the rows
      // r < k already in column i.
      const Eigen::Matrix3d y = l_values_[U(l_col_[U(i)])] * x_[U(i)];
      x_[U(i)].setZero();
      for (int p = l_col_[U(i)] + 1; p < next_[U(i)]; ++p) {
        x_[U(l_rows_[U(p)])].noalias() -= l_values_[U(p)] * y;
      }
      d.noalias() -= y.transpose() * y;
      const int slot = next_[U(i)]++;
      l_rows_[U(slot)] = k;
      l_values_[U(slot)] = y.transpose();
    }
    Eigen::Matrix3d inverse;
    if (!InverseCholesky3(d, &inverse)) {
      for (int j = 0; j <= k; ++j) {
        next_[U(j)] = 0;
      }
      std::fill(x_.begin(), x_.end(), Eigen::Matrix3d::Zero());
      return false;
    }
    l_rows_[U(l_col_[U(k)])] = k;
    l_values_[U(l_col_[U(k)])] = inverse;
    next_[U(k)] = l_col_[U(k)] + 1;
  }
  for (int k = 0; k < n_; ++k) {
    next_[U(k)] = 0;  // Marks the factorization as consumed for the next call.
  }
  return true;
}

Eigen::VectorXd BlockCholesky::Solve(const Eigen::VectorXd& b) const {
  GRIDSLAM_CHECK(b.size() == 3 * n_) << "right-hand side of the wrong size";
  Eigen::VectorXd y(3 * n_);
  for (int k = 0; k < n_; ++k) {
    y.segment<3>(3 * k) = b.segment<3>(3 * old_of_new_[U(k)]);
  }
  for (int j = 0; j < n_; ++j) {
    const Eigen::Vector3d yj = l_values_[U(l_col_[U(j)])] * y.segment<3>(3 * j);
    y.segment<3>(3 * j) = yj;
    for (int p = l_col_[U(j)] + 1; p < l_col_[U(j) + 1]; ++p) {
      y.segment<3>(3 * l_rows_[U(p)]).noalias() -= l_values_[U(p)] * yj;
    }
  }
  for (int j = n_ - 1; j >= 0; --j) {
    Eigen::Vector3d yj = y.segment<3>(3 * j);
    for (int p = l_col_[U(j)] + 1; p < l_col_[U(j) + 1]; ++p) {
      yj.noalias() -= l_values_[U(p)].transpose() * y.segment<3>(3 * l_rows_[U(p)]);
    }
    y.segment<3>(3 * j) = l_values_[U(l_col_[U(j)])].transpose() * yj;
  }
  Eigen::VectorXd x(3 * n_);
  for (int k = 0; k < n_; ++k) {
    x.segment<3>(3 * old_of_new_[U(k)]) = y.segment<3>(3 * k);
  }
  return x;
}

double BlockCholesky::Quadratic(const Eigen::VectorXd& x) const {
  double total = 0.0;
  for (int k = 0; k < n_; ++k) {
    const Eigen::Vector3d xk = x.segment<3>(3 * old_of_new_[U(k)]);
    const int end = a_col_[U(k) + 1] - 1;
    for (int p = a_col_[U(k)]; p < end; ++p) {
      const Eigen::Vector3d xi = x.segment<3>(3 * old_of_new_[U(a_row_[U(p)])]);
      total += 2.0 * xi.dot(values_[U(p)] * xk);
    }
    total += xk.dot(values_[U(end)] * xk);
  }
  return total;
}

double BlockCholesky::MaxDiagonal() const {
  double best = 0.0;
  for (int k = 0; k < n_; ++k) {
    best = std::max(best, values_[U(a_col_[U(k) + 1] - 1)].diagonal().maxCoeff());
  }
  return best;
}

}  // namespace gridslam::pose_graph::internal
