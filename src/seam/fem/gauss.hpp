#pragma once
// One-dimensional Gauss rules: the building blocks of seam's tensor-product and collapsed
// (Duffy) quadrature on reference cells, and of mortar segment integration.
#include <span>

namespace seam::fem {

/// n-point Gauss-Jacobi rule on [-1, 1] for the weight (1 - x)^alpha (1 + x)^beta
/// (alpha, beta > -1): sum_q w_q p(x_q) = int_{-1}^{1} (1-x)^alpha (1+x)^beta p(x) dx for every
/// polynomial p of degree <= 2n - 1. Points ascending, weights positive; points.size() and
/// weights.size() must be n (n >= 1). Throws seam::InputError for invalid arguments.
void gauss_jacobi(int n, double alpha, double beta, std::span<double> points,
                  std::span<double> weights);

/// n-point Gauss-Legendre rule on [-1, 1] (Gauss-Jacobi with alpha = beta = 0), exact for
/// degree <= 2n - 1; the points are exactly symmetric about 0.
void gauss_legendre(int n, std::span<double> points, std::span<double> weights);

} // namespace seam::fem
