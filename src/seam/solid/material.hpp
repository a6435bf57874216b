#pragma once
// Constitutive laws at a material point: energy, second Piola–Kirchhoff stress and its
// material tangent, for 3D, plane strain and plane stress.
//
// Conventions (used by every kernel of seam::solid):
//  * Voigt order of symmetric tensors: (11, 22, 33, 12, 23, 13).
//  * Strains in Voigt form carry engineering shears (2 E_12, ...), stresses do not, so that
//    W(E) has dW/dE_voigt = S_voigt and the tangent C_voigt = dS_voigt/dE_voigt is symmetric.
//  * 2D problems use the in-plane Voigt components (11, 22, 12) = indices {0, 1, 3}; the
//    out-of-plane stretch F33 is 1 (plane strain) or solved so that S33 = 0 (plane stress).
//  * linear_elastic is the geometrically linear model: the "F" passed in is I + grad u, the
//    strain is eps = sym(grad u), and S returned is the small-strain stress sigma (all stress
//    measures coincide in linear theory). Its element kernel uses the reference configuration.
#include <Eigen/Core>
#include <optional>
#include <string_view>

namespace seam::solid {

enum class MaterialModel { linear_elastic, saint_venant_kirchhoff, neo_hooke };

/// none = 3D; 2D problems are plane strain or plane stress with unit thickness.
enum class PlaneMode { none, plane_strain, plane_stress };

/// An isotropic elastic material. Energies (mu, lambda the Lamé constants):
///   linear_elastic          W = lambda/2 (tr eps)^2 + mu eps:eps,  eps = sym(grad u)
///   saint_venant_kirchhoff  W = lambda/2 (tr E)^2 + mu E:E,         E = (F^T F - I)/2
///   neo_hooke               W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2
struct Material {
  MaterialModel model = MaterialModel::linear_elastic;
  double young = 1.0;
  double poisson = 0.0;
  double density = 0.0;

  double mu() const { return young / (2.0 * (1.0 + poisson)); }
  double lambda() const { return young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson)); }
};

/// Throws seam::InputError unless young > 0, -1 < poisson < 1/2 and density >= 0.
void validate(const Material& m);

/// "linear_elastic", "saint_venant_kirchhoff", "neo_hooke".
std::string_view name(MaterialModel model);
/// Inverse of name(); std::nullopt for an unknown name.
std::optional<MaterialModel> parse_material_model(std::string_view name);

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

/// Voigt index of the symmetric pair (i, j), 0-based.
constexpr int voigt_index(int i, int j) {
  if (i == j) return i;
  const int s = i + j; // (0,1) -> 1, (1,2) -> 3, (0,2) -> 2
  return s == 1 ? 3 : (s == 3 ? 4 : 5);
}

/// The response of a material point.
struct PointResponse {
  double energy = 0.0;    ///< W per unit reference volume
  Eigen::Matrix3d stress; ///< S (2nd Piola–Kirchhoff); sigma for linear_elastic
  /// dS/dE in Voigt form. In plane stress it is the statically condensed tangent
  /// C_ab - C_a3 C_3b / C_33 on the in-plane components, with row and column 33 zero.
  Matrix6 tangent;
  /// F33 actually used: 1 in plane strain, the solution of S33 = 0 in plane stress
  /// (for linear_elastic 1 + eps33), F(2,2) as given in 3D.
  double stretch_zz = 1.0;
};

/// Outcome of a point evaluation.
enum class PointStatus {
  ok,
  inverted,        ///< det F <= 0 (hyperelastic models only)
  no_plane_stress, ///< no F33 > 0 with S33 = 0 exists or the local Newton iteration failed
};

/// Evaluates the material at deformation gradient F. In 2D modes only the in-plane block
/// F(0:1, 0:1) is read (F13 = F23 = F31 = F32 = 0 is implied) and F33 is set by the mode.
/// `tangent` is computed only when `with_tangent` is true.
PointStatus evaluate(const Material& m, PlaneMode mode, const Eigen::Matrix3d& F,
                     PointResponse& out, bool with_tangent = true);

/// Cauchy stress sigma = F S F^T / det F of a response evaluated at F (with F33 from
/// `stretch_zz` in 2D); sigma = S for linear_elastic.
Eigen::Matrix3d cauchy_stress(const Material& m, PlaneMode mode, const Eigen::Matrix3d& F,
                              const PointResponse& r);

/// Von Mises equivalent stress of a symmetric stress tensor.
double von_mises(const Eigen::Matrix3d& sigma);

} // namespace seam::solid
