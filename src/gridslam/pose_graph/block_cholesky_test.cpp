#include "gridslam/pose_graph/internal/block_cholesky.hpp"

#include <random>
#include <set>

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

namespace gridslam::pose_graph::internal {
namespace {

// A random sparse SPD block matrix: a chain plus random extra pairs, diagonally dominant.
struct Problem {
  int n = 0;
  std::vector<std::pair<int, int>> pairs;
  Eigen::MatrixXd dense;
};

Problem MakeProblem(int n, int extra, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> pick(0, n - 1);
  std::normal_distribution<double> normal(0.0, 1.0);
  Problem p;
  p.n = n;
  std::set<std::pair<int, int>> seen;
  for (int k = 1; k < n; ++k) {
    p.pairs.emplace_back(k - 1, k);
  }
  for (int e = 0; e < extra; ++e) {
    const int a = pick(rng);
    const int b = pick(rng);
    if (a != b) {
      p.pairs.emplace_back(a, b);
    }
  }
  p.dense = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  for (const auto& [a, b] : p.pairs) {
    Eigen::Matrix3d block;
    for (int i = 0; i < 9; ++i) {
      block(i / 3, i % 3) = normal(rng);
    }
    p.dense.block<3, 3>(3 * a, 3 * b) += block;
    p.dense.block<3, 3>(3 * b, 3 * a) += block.transpose();
  }
  for (int d = 0; d < 3 * n; ++d) {
    p.dense(d, d) = p.dense.row(d).cwiseAbs().sum() + 1.0;
  }
  return p;
}

void Fill(BlockCholesky& cholesky, const Problem& p) {
  cholesky.SetZero();
  auto put = [&](int a, int b) {
    const auto slot = cholesky.Find(a, b);
    const Eigen::Matrix3d block = p.dense.block<3, 3>(3 * a, 3 * b);
    cholesky.values()[static_cast<std::size_t>(slot.index)] =
        slot.transposed ? Eigen::Matrix3d(block.transpose()) : block;
  };
  for (int b = 0; b < p.n; ++b) {
    put(b, b);
  }
  for (const auto& [a, b] : p.pairs) {
    put(a, b);  // Duplicates write the same summed block twice.
  }
}

TEST(BlockCholeskyTest, SolvesLikeADenseCholesky) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Problem p = MakeProblem(40, 30, seed);
    BlockCholesky cholesky(p.n, p.pairs);
    Fill(cholesky, p);
    ASSERT_TRUE(cholesky.Factorize());
    std::mt19937 rng(seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    Eigen::VectorXd b(3 * p.n);
    for (int i = 0; i < b.size(); ++i) {
      b[i] = normal(rng);
    }
    const Eigen::VectorXd expected = p.dense.llt().solve(b);
    EXPECT_LT((cholesky.Solve(b) - expected).norm(), 1e-9 * expected.norm());
    EXPECT_NEAR(cholesky.Quadratic(b), b.dot(p.dense * b), 1e-9 * std::abs(b.dot(p.dense * b)));
    EXPECT_NEAR(cholesky.MaxDiagonal(), p.dense.diagonal().maxCoeff(), 1e-12);
    EXPECT_GE(cholesky.FactorBlocks(), p.n);

    // Damped: (A + lambda I) x = b; refactorizing reuses the symbolic analysis.
    ASSERT_TRUE(cholesky.Factorize(2.5));
    const Eigen::MatrixXd damped = p.dense + 2.5 * Eigen::MatrixXd::Identity(3 * p.n, 3 * p.n);
    const Eigen::VectorXd expected_damped = damped.llt().solve(b);
    EXPECT_LT((cholesky.Solve(b) - expected_damped).norm(), 1e-9 * expected_damped.norm());
  }
}

TEST(BlockCholeskyTest, RejectsAnIndefiniteMatrixAndRecovers) {
  const Problem p = MakeProblem(10, 5, 3);
  BlockCholesky cholesky(p.n, p.pairs);
  Fill(cholesky, p);
  cholesky.values()[static_cast<std::size_t>(cholesky.Find(4, 4).index)](1, 1) = -1e6;
  EXPECT_FALSE(cholesky.Factorize());
  Fill(cholesky, p);
  ASSERT_TRUE(cholesky.Factorize());
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(3 * p.n);
  EXPECT_LT((cholesky.Solve(b) - p.dense.llt().solve(b)).norm(), 1e-9);
}

TEST(BlockCholeskyTest, EmptySystem) {
  BlockCholesky cholesky(0, {});
  EXPECT_TRUE(cholesky.Factorize());
  EXPECT_EQ(cholesky.Solve(Eigen::VectorXd()).size(), 0);
}

}  // namespace
}  // namespace gridslam::pose_graph::internal
