#include "gridslam/pose_graph/initialization.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "gridslam/pose_graph/graph_utils.hpp"

namespace gridslam::pose_graph {

namespace {

std::size_t U(int i) { return static_cast<std::size_t>(i); }

using Triplets = std::vector<Eigen::Triplet<double>>;

/// Per vertex index: its first unknown (dim per vertex) or -1 for anchors.
std::vector<int> Unknowns(const std::vector<bool>& fixed, int dim, int* count) {
  std::vector<int> first(fixed.size(), -1);
  int n = 0;
  for (std::size_t v = 0; v < fixed.size(); ++v) {
    if (!fixed[v]) {
      first[v] = n;
      n += dim;
    }
  }
  *count = n;
  return first;
}

/// Adds the normal equations of the residual  x_j - M x_i - c  (dim-vectors, weight W) to (H, b);
/// anchored ends contribute their values x_fixed to the right-hand side.
template <int Dim>
void AddRelative(int i, int j, const Eigen::Matrix<double, Dim, Dim>& M,
                 const Eigen::Matrix<double, Dim, 1>& c, const Eigen::Matrix<double, Dim, Dim>& W,
                 const std::vector<int>& first,
                 const std::vector<Eigen::Matrix<double, Dim, 1>>& x_fixed, Triplets& H,
                 Eigen::VectorXd& b) {
  // r = x_j - M x_i - c = A_j x_j + A_i x_i - c with A_j = I, A_i = -M.
  using Mat = Eigen::Matrix<double, Dim, Dim>;
  const Mat A_i = -M;
  const int fi = first[U(i)];
  const int fj = first[U(j)];
  Eigen::Matrix<double, Dim, 1> rhs = c;  // A_i x_i + A_j x_j = c, known parts moved right.
  if (fi < 0) {
    rhs -= A_i * x_fixed[U(i)];
  }
  if (fj < 0) {
    rhs -= x_fixed[U(j)];
  }
  auto add_block = [&](int r0, int c0, const Mat& block) {
    for (int r = 0; r < Dim; ++r) {
      for (int q = 0; q < Dim; ++q) {
        if (block(r, q) != 0.0) {
          H.emplace_back(r0 + r, c0 + q, block(r, q));
        }
      }
    }
  };
  if (fi >= 0) {
    add_block(fi, fi, A_i.transpose() * W * A_i);
    b.segment<Dim>(fi) += A_i.transpose() * W * rhs;
  }
  if (fj >= 0) {
    add_block(fj, fj, W);
    b.segment<Dim>(fj) += W * rhs;
  }
  if (fi >= 0 && fj >= 0) {
    const Mat Hij = A_i.transpose() * W;
    add_block(fi, fj, Hij);
    add_block(fj, fi, Hij.transpose());
  }
}

bool SolveSparse(int n, const Triplets& triplets, const Eigen::VectorXd& b, Eigen::VectorXd* x) {
  if (n == 0) {
    x->resize(0);
    return true;
  }
  Eigen::SparseMatrix<double> H(n, n);
  H.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(H);
  if (solver.info() != Eigen::Success) {
    return false;
  }
  *x = solver.solve(b);
  return solver.info() == Eigen::Success && x->allFinite();
}

/// Rotation weight of an edge: its rotational information (a small floor keeps the system
/// regular for edges without one).
double RotationWeight(const Edge& e) { return std::max(e.information(2, 2), 1e-12); }

/// Orientations by the chordal relaxation; false on a solver failure.
bool ChordalOrientations(const PoseGraph& graph, const std::vector<bool>& fixed,
                         std::vector<double>* theta) {
  int n = 0;
  const std::vector<int> first = Unknowns(fixed, 2, &n);
  std::vector<Eigen::Vector2d> x_fixed(graph.num_vertices());
  for (std::size_t v = 0; v < x_fixed.size(); ++v) {
    const double t = graph.vertex(static_cast<int>(v)).T_map_v.theta();
    x_fixed[v] = Eigen::Vector2d(std::cos(t), std::sin(t));
  }
  Triplets H;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
  for (int k = 0; k < static_cast<int>(graph.num_edges()); ++k) {
    const Edge& e = graph.edge(k);
    const double cz = std::cos(e.T_i_j.theta());
    const double sz = std::sin(e.T_i_j.theta());
    Eigen::Matrix2d M;
    M << cz, -sz, sz, cz;
    const Eigen::Matrix2d W = RotationWeight(e) * Eigen::Matrix2d::Identity();
    AddRelative<2>(graph.FromIndex(k), graph.ToIndex(k), M, Eigen::Vector2d::Zero(), W, first,
                   x_fixed, H, b);
  }
  Eigen::VectorXd x;
  if (!SolveSparse(n, H, b, &x)) {
    return false;
  }
  theta->resize(graph.num_vertices());
  for (std::size_t v = 0; v < theta->size(); ++v) {
    const Eigen::Vector2d r = first[v] < 0 ? x_fixed[v] : Eigen::Vector2d(x.segment<2>(first[v]));
    (*theta)[v] = std::atan2(r.y(), r.x());
  }
  return true;
}

/// Orientations by LAGO's regularized linear least squares; false on a solver failure.
bool LagoOrientations(const PoseGraph& graph, const std::vector<bool>& fixed,
                      std::vector<double>* theta) {
  // Orientations composed along the chaining tree, without wrapping.
  const int num = static_cast<int>(graph.num_vertices());
  const std::vector<int> parent_edge = ChainingTree(graph, fixed);
  std::vector<std::vector<int>> children(U(num));
  std::vector<int> stack;
  std::vector<double> tree(U(num), 0.0);
  for (int v = 0; v < num; ++v) {
    const int e = parent_edge[U(v)];
    if (e < 0) {
      stack.push_back(v);
      tree[U(v)] = graph.vertex(v).T_map_v.theta();
    } else {
      const int p = graph.FromIndex(e) == v ? graph.ToIndex(e) : graph.FromIndex(e);
      children[U(p)].push_back(v);
    }
  }
  while (!stack.empty()) {
    const int p = stack.back();
    stack.pop_back();
    for (const int v : children[U(p)]) {
      const int e = parent_edge[U(v)];
      const double z = graph.edge(e).T_i_j.theta();
      tree[U(v)] = tree[U(p)] + (graph.FromIndex(e) == p ? z : -z);
      stack.push_back(v);
    }
  }
  int n = 0;
  const std::vector<int> first = Unknowns(fixed, 1, &n);
  std::vector<Eigen::Matrix<double, 1, 1>> x_fixed(U(num));
  for (int v = 0; v < num; ++v) {
    x_fixed[U(v)](0) = tree[U(v)];
  }
  Triplets H;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
  const Eigen::Matrix<double, 1, 1> one = Eigen::Matrix<double, 1, 1>::Identity();
  for (int k = 0; k < static_cast<int>(graph.num_edges()); ++k) {
    const Edge& e = graph.edge(k);
    const int i = graph.FromIndex(k);
    const int j = graph.ToIndex(k);
    const double z = e.T_i_j.theta();
    const double turns = std::round((tree[U(j)] - tree[U(i)] - z) / (2.0 * std::numbers::pi));
    Eigen::Matrix<double, 1, 1> c;
    c(0) = z + 2.0 * std::numbers::pi * turns;
    AddRelative<1>(i, j, one, c, RotationWeight(e) * one, first, x_fixed, H, b);
  }
  Eigen::VectorXd x;
  if (!SolveSparse(n, H, b, &x)) {
    return false;
  }
  theta->resize(U(num));
  for (int v = 0; v < num; ++v) {
    (*theta)[U(v)] = first[U(v)] < 0 ? graph.vertex(v).T_map_v.theta() : x(first[U(v)]);
  }
  return true;
}

/// Positions given the orientations; false on a solver failure.
bool Positions(const PoseGraph& graph, const std::vector<bool>& fixed,
               const std::vector<double>& theta, std::vector<Eigen::Vector2d>* positions) {
  int n = 0;
  const std::vector<int> first = Unknowns(fixed, 2, &n);
  std::vector<Eigen::Vector2d> x_fixed(graph.num_vertices());
  for (std::size_t v = 0; v < x_fixed.size(); ++v) {
    x_fixed[v] = graph.vertex(static_cast<int>(v)).T_map_v.translation();
  }
  Triplets H;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
  for (int k = 0; k < static_cast<int>(graph.num_edges()); ++k) {
    const Edge& e = graph.edge(k);
    const int i = graph.FromIndex(k);
    const int j = graph.ToIndex(k);
    // e_t = R(theta_i + theta_z)^T (t_j - t_i) - R_z^T t_z: with A = R(theta_i + theta_z)^T,
    // t_j - t_i should be R(theta_i) t_z, weighted by A^T Omega_tt A.
    const double a = theta[U(i)] + e.T_i_j.theta();
    Eigen::Matrix2d A;
    A << std::cos(a), std::sin(a), -std::sin(a), std::cos(a);
    const Eigen::Matrix2d W = A.transpose() * e.information.topLeftCorner<2, 2>() * A;
    const double ci = std::cos(theta[U(i)]);
    const double si = std::sin(theta[U(i)]);
    const Eigen::Vector2d c(ci * e.T_i_j.x() - si * e.T_i_j.y(),
                            si * e.T_i_j.x() + ci * e.T_i_j.y());
    AddRelative<2>(i, j, Eigen::Matrix2d::Identity(), c, W, first, x_fixed, H, b);
  }
  Eigen::VectorXd x;
  if (!SolveSparse(n, H, b, &x)) {
    return false;
  }
  positions->resize(graph.num_vertices());
  for (std::size_t v = 0; v < positions->size(); ++v) {
    (*positions)[v] = first[v] < 0 ? x_fixed[v] : Eigen::Vector2d(x.segment<2>(first[v]));
  }
  return true;
}

}  // namespace

bool ParseInitialization(const std::string& name, Initialization* out) {
  if (name == "none") {
    *out = Initialization::kNone;
  } else if (name == "chordal") {
    *out = Initialization::kChordal;
  } else if (name == "lago") {
    *out = Initialization::kLago;
  } else {
    return false;
  }
  return true;
}

bool InitializeOrientationFirst(PoseGraph& graph, Initialization method) {
  if (method == Initialization::kNone || graph.num_edges() == 0) {
    return true;
  }
  const std::vector<bool> fixed = EffectiveFixed(graph);
  std::vector<double> theta;
  const bool ok = method == Initialization::kChordal ? ChordalOrientations(graph, fixed, &theta)
                                                     : LagoOrientations(graph, fixed, &theta);
  std::vector<Eigen::Vector2d> positions;
  if (!ok || !Positions(graph, fixed, theta, &positions)) {
    return false;
  }
  for (int v = 0; v < static_cast<int>(graph.num_vertices()); ++v) {
    if (!fixed[U(v)]) {
      graph.SetPose(v, Pose2(positions[U(v)].x(), positions[U(v)].y(), theta[U(v)]));
    }
  }
  return true;
}

}  // namespace gridslam::pose_graph
