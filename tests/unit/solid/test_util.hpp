#pragma once
// Shared helpers of the solid unit tests: materials, random states, rotations.
#include "seam/fem/cell.hpp"
#include "seam/solid/material.hpp"

#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace seam::solid::test {

inline Material make_material(MaterialModel model, double nu = 0.3) {
  Material m;
  m.model = model;
  m.young = 210.0;
  m.poisson = nu;
  m.density = 7.8;
  return m;
}

inline constexpr std::array<MaterialModel, 3> all_models = {
    MaterialModel::linear_elastic, MaterialModel::saint_venant_kirchhoff, MaterialModel::neo_hooke};
inline constexpr std::array<PlaneMode, 3> all_modes = {PlaneMode::none, PlaneMode::plane_strain,
                                                       PlaneMode::plane_stress};

inline bool hyperelastic(MaterialModel m) {
  return m != MaterialModel::linear_elastic;
}

/// Rotation about the unit axis `a` by angle `t` (Rodrigues).
inline Eigen::Matrix3d rotation(Eigen::Vector3d a, double t) {
  a.normalize();
  Eigen::Matrix3d K;
  K << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return Eigen::Matrix3d::Identity() + std::sin(t) * K + (1 - std::cos(t)) * K * K;
}

/// Symmetric square root of a symmetric positive definite matrix.
inline Eigen::Matrix3d spd_sqrt(const Eigen::Matrix3d& A) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(A);
  return es.eigenvectors() * es.eigenvalues().cwiseSqrt().asDiagonal() *
         es.eigenvectors().transpose();
}

/// A deformation gradient whose strain measure (Green–Lagrange for the hyperelastic models,
/// small strain for linear_elastic) is E: the right stretch U = sqrt(I + 2E), or I + E.
inline Eigen::Matrix3d F_of_strain(MaterialModel model, const Eigen::Matrix3d& E) {
  if (model == MaterialModel::linear_elastic) return Eigen::Matrix3d::Identity() + E;
  return spd_sqrt(Eigen::Matrix3d::Identity() + 2.0 * E);
}

/// Symmetric strain tensor from Voigt components with engineering shears.
inline Eigen::Matrix3d strain_from_voigt(const Vector6& e) {
  Eigen::Matrix3d E;
  E << e(0), e(3) / 2, e(5) / 2, e(3) / 2, e(1), e(4) / 2, e(5) / 2, e(4) / 2, e(2);
  return E;
}

inline Vector6 stress_to_voigt(const Eigen::Matrix3d& S) {
  Vector6 s;
  s << S(0, 0), S(1, 1), S(2, 2), S(0, 1), S(1, 2), S(0, 2);
  return s;
}

/// Voigt components that are free in a mode: all six in 3D, (11, 22, 12) in 2D.
inline std::vector<int> free_components(PlaneMode mode) {
  if (mode == PlaneMode::none) return {0, 1, 2, 3, 4, 5};
  return {0, 1, 3};
}

inline constexpr std::array<fem::CellType, 5> cells_2d = {
    fem::CellType::tri3, fem::CellType::tri6, fem::CellType::quad4, fem::CellType::quad8,
    fem::CellType::quad9};
inline constexpr std::array<fem::CellType, 5> cells_3d = {fem::CellType::tet4, fem::CellType::tet10,
                                                          fem::CellType::hex8, fem::CellType::hex20,
                                                          fem::CellType::hex27};

/// Node coordinates of a cell (or facet) of type t embedded in `dim` >= dimension(t) space:
/// X = c + A (xi, 0...) + noise, with A a fixed well-conditioned matrix with det > 0 and noise
/// uniform in [-distortion, distortion] per coordinate (seeded).
inline std::vector<double> cell_coordinates(fem::CellType t, int dim, double distortion,
                                            unsigned seed = 1) {
  const int p = fem::dimension(t), n = fem::n_nodes(t);
  const auto ref = fem::reference_nodes(t);
  Eigen::Matrix3d A;
  A << 1.1, 0.2, -0.1, -0.15, 0.9, 0.2, 0.1, -0.05, 1.2;
  const Eigen::Vector3d c(0.3, -0.2, 0.5);
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> d(-distortion, distortion);
  std::vector<double> X(static_cast<std::size_t>(n * dim));
  for (int a = 0; a < n; ++a) {
    Eigen::Vector3d xi = Eigen::Vector3d::Zero();
    for (int k = 0; k < p; ++k) xi(k) = ref[static_cast<std::size_t>(a * p + k)];
    const Eigen::Vector3d x = c + A * xi;
    for (int i = 0; i < dim; ++i) X[static_cast<std::size_t>(a * dim + i)] = x(i) + d(gen);
  }
  return X;
}

/// Random vector with entries uniform in [-amplitude, amplitude].
inline std::vector<double> random_vector(std::size_t n, double amplitude, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> d(-amplitude, amplitude);
  std::vector<double> v(n);
  for (auto& x : v) x = d(gen);
  return v;
}

inline double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

} // namespace seam::solid::test
