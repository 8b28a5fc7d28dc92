// The error of one pose-graph edge, its Jacobians and the total chi^2, in the g2o convention
// (docs/formats.md §2; g2o EdgeSE2::computeError / linearizeOplus): for vertices X_i, X_j and the
// measurement Z = T_i_j, e = (x, y, theta) of Z^-1 * X_i^-1 * X_j with theta wrapped to [-pi, pi),
// and chi^2 = sum over edges of e^T * Omega * e. Jacobians are taken with respect to additive
// perturbations of the vertex parameters (x + dx, y + dy, theta + dtheta), g2o's VertexSE2::oplus,
// which is also the parameterization of the Gauss-Newton/LM solver. Inline, allocation-free
// versions for the hot loops of the optimizers.
#pragma once

#include <cmath>

#include <Eigen/Core>

#include "gridslam/common/angles.hpp"
#include "gridslam/geometry/pose2.hpp"
#include "gridslam/pose_graph/pose_graph.hpp"

namespace gridslam::pose_graph {

/// Error and Jacobians of one edge; x_i, x_j and z are (x, y, theta) vectors (theta need not be
/// normalized), (cz, sz) = (cos, sin) of z's angle, precomputed by the caller. J_e_xi / J_e_xj
/// may be null when not wanted.
inline Eigen::Vector3d EdgeError(const Eigen::Vector3d& x_i, const Eigen::Vector3d& x_j,
                                 const Eigen::Vector3d& z, double cz, double sz,
                                 Eigen::Matrix3d* J_e_xi = nullptr,
                                 Eigen::Matrix3d* J_e_xj = nullptr) {
  const double ci = std::cos(x_i.z());
  const double si = std::sin(x_i.z());
  const double dx = x_j.x() - x_i.x();
  const double dy = x_j.y() - x_i.y();
  // d = R_i^T (t_j - t_i): translation of X_i^-1 X_j.
  const double d0 = ci * dx + si * dy;
  const double d1 = -si * dx + ci * dy;
  // e_t = R_z^T (d - t_z).
  const double u0 = d0 - z.x();
  const double u1 = d1 - z.y();
  const Eigen::Vector3d e(cz * u0 + sz * u1, -sz * u0 + cz * u1,
                          NormalizeAngle(x_j.z() - x_i.z() - z.z()));
  if (J_e_xi != nullptr || J_e_xj != nullptr) {
    // R_z^T R_i^T = R(theta_i + theta_z)^T.
    const double c = ci * cz - si * sz;
    const double s = si * cz + ci * sz;
    Eigen::Matrix3d J_j;
    J_j << c, s, 0.0, -s, c, 0.0, 0.0, 0.0, 1.0;
    if (J_e_xj != nullptr) {
      *J_e_xj = J_j;
    }
    if (J_e_xi != nullptr) {
      // d e_t / d theta_i = R_z^T (d1, -d0).
      *J_e_xi << -c, -s, cz * d1 - sz * d0, s, -c, -sz * d1 - cz * d0, 0.0, 0.0, -1.0;
    }
  }
  return e;
}

/// As above, computing cos and sin of z's angle.
inline Eigen::Vector3d EdgeError(const Eigen::Vector3d& x_i, const Eigen::Vector3d& x_j,
                                 const Eigen::Vector3d& z, Eigen::Matrix3d* J_e_xi = nullptr,
                                 Eigen::Matrix3d* J_e_xj = nullptr) {
  return EdgeError(x_i, x_j, z, std::cos(z.z()), std::sin(z.z()), J_e_xi, J_e_xj);
}

/// Error of edge `edge_index` of `graph` at the graph's current vertex poses.
Eigen::Vector3d EdgeError(const PoseGraph& graph, int edge_index);

/// e^T Omega e of one edge at the graph's current poses.
double EdgeChi2(const PoseGraph& graph, int edge_index);

/// Sum of EdgeChi2 over all edges (the g2o chi^2).
double Chi2(const PoseGraph& graph);

}  // namespace gridslam::pose_graph
