#pragma once
// Lagrange multiplier bases on a slave facet (ALGORITHMS.md §3). Standard: Phi = N. Dual:
// Phi = A_e N~ with A_e = D_e M_e^{-1}, D_e = diag(int N~_j J), M_e = (int N~_j N~_k J), which
// makes int Phi_j N~_k J = delta_jk int N~_k J (biorthogonality; Wohlmuth 2000, Popp et al.
// 2010). On tri6 and quad8 some int N_j vanish or are negative, so no dual basis exists for
// N itself; the slave displacement basis is modified first (Popp, Wohlmuth, Gee, Wall 2012):
//   N~_v = N_v + a sum_{edge nodes e next to v} N_e,  N~_e = (1 - 2a) N_e,  a = 1/5,
// with nodal values d = T d~. quad9, line3 and the linear facets use a = 0 (N~ = N, T = I).
#include <span>

#include <Eigen/Core>

#include "seam/mortar/facet.hpp"

namespace seam::mortar {

enum class Multiplier { standard, dual };

/// Square or rectangular matrix of at most max_facet_nodes rows and columns, stored inline.
using SmallMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor,
                                  max_facet_nodes, max_facet_nodes>;

/// The modification parameter a: 1/5 for tri6 and quad8 with dual multipliers, else 0.
double basis_modification(fem::CellType type, Multiplier multiplier);

/// An edge (mid-side) node of a quadratic facet and the two vertices of its edge.
struct EdgeNode {
  int node = 0;
  int v0 = 0;
  int v1 = 0;
};
/// Edge nodes of tri6, quad8, quad9 and line3 (the latter: node 2 between 0 and 1); empty for
/// linear facets. The quad9 centre node is not an edge node.
std::span<const EdgeNode> edge_nodes(fem::CellType type);

/// Overwrite the standard shape values (or one column of derivatives) N with N~ for
/// modification a.
void modify_basis(fem::CellType type, double a, double* N);

/// The facet's nodal transformation d = T d~ (n x n): vertex rows are unit rows, an edge node
/// row has 1 - 2a on the diagonal and a in its two vertex columns.
SmallMatrix transformation_matrix(fem::CellType type, double a);

/// Dual coefficients A_e = D_e M_e^{-1} for the basis N~ with modification a, integrated with
/// the facet's own Jacobian J (so they follow the facet into any configuration). Throws
/// InputError for a degenerate facet (M_e singular).
template <int Dim> SmallMatrix dual_coefficients(const Facet<Dim>& facet, double a);

/// Everything needed to evaluate a slave facet's displacement and multiplier functions.
struct SlaveBasis {
  Multiplier multiplier = Multiplier::dual;
  double modification = 0.0; ///< a
  SmallMatrix A;             ///< dual coefficients (n x n); unused for standard multipliers
};

template <int Dim> SlaveBasis make_slave_basis(const Facet<Dim>& facet, Multiplier multiplier);

/// Boundary modification of the multiplier basis for "bound" slave nodes: nodes whose
/// displacement is known (every component prescribed, or a crosspoint) carry no multiplier
/// (Wohlmuth 2000, 2001; Popp, Gitterle, Gee, Wall 2010, Sect. 3.3; 4C's "bound" nodes). Their
/// multiplier function is handed to the n_free other nodes of the facet in equal parts,
///     Phi^_j = Phi_j + (1 / n_free) sum_{b bound} Phi_b  (j free),   Phi^_b = 0,
/// i.e. Phi^ = R Phi. Hence sum_j Phi^_j = sum_k Phi_k = 1 (constants are still reproduced:
/// the patch test), and for free j, k: int Phi^_j N~_k = int Phi_j N~_k = delta_jk int N~_k
/// (b != k), so D stays diagonal on the free nodes; the bound columns get
/// D_jb = D_bb / n_free and move to the known side of the constraint with M.
/// Bit i of `bound_mask` marks facet node i as bound. R is zero when every node is bound.
SmallMatrix boundary_transformation(int n_nodes, unsigned bound_mask);

/// Slave displacement functions N~ and multiplier functions Phi from the standard values N.
inline void slave_functions(const SlaveBasis& basis, fem::CellType type, int n_nodes,
                            const NodalVector& N, NodalVector& N_tilde, NodalVector& Phi) {
  N_tilde = N;
  if (basis.modification != 0.0) modify_basis(type, basis.modification, N_tilde.data());
  if (basis.multiplier == Multiplier::dual) {
    Phi.setZero();
    Phi.head(n_nodes).noalias() = basis.A * N_tilde.head(n_nodes);
  } else {
    Phi = N_tilde;
  }
}

} // namespace seam::mortar
