// The reference for the O(N) two-flux solves: the system of Kimmel et al. 2013 §4.1
// assembled as a dense matrix and solved by Gaussian elimination.
#pragma once

#include "texgen/fade/two_flux.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace patina::texgen::fade::test {

// (I - M) E = E_0 assembled literally from Eqs. (29)-(34) and solved by Gaussian
// elimination with partial pivoting: the O(N^3) reference.
inline void dense_solve(const std::vector<double>& rho, const std::vector<double>& tau,
                        const TwoFluxBoundary& bc, std::vector<double>& down,
                        std::vector<double>& up)
{
    const size_t n = rho.size();
    const size_t dim = 2 * (n + 1);
    std::vector<double> A(dim * dim, 0.0), b(dim, 0.0);
    auto rho_at = [&](long i) {
        return i < 0 ? 0.0 : (static_cast<size_t>(i) == n ? bc.ground_reflectance : rho[i]);
    };
    // M: R_i = [[0, rho_i], [rho_{i-1}, 0]] on the diagonal (Eq. 32), T^u_i = [[tau_i, 0],
    // [0, 0]] above (Eq. 33), T^d_i = [[0, 0], [0, tau_i]] below (Eq. 34).
    std::vector<double> M(dim * dim, 0.0);
    for (size_t i = 0; i <= n; ++i) {
        const size_t r = 2 * i;
        M[r * dim + r + 1] = rho_at(static_cast<long>(i));
        M[(r + 1) * dim + r] = rho_at(static_cast<long>(i) - 1);
        if (i < n) {
            M[r * dim + r + 2] = tau[i];                   // T^u_i: E^u_i <- E^u_{i+1}
            M[(r + 3) * dim + r + 1] = tau[i];             // T^d_i: E^d_{i+1} <- E^d_i
        }
    }
    for (size_t i = 0; i < dim * dim; ++i)
        A[i] = (i % (dim + 1) == 0 ? 1.0 : 0.0) - M[i];
    b[1] = bc.top_irradiance;          // Eq. (30)
    b[2 * n] = bc.bottom_irradiance;   // light entering from below
    for (size_t c = 0; c < dim; ++c) {
        size_t p = c;
        for (size_t r = c + 1; r < dim; ++r)
            if (std::abs(A[r * dim + c]) > std::abs(A[p * dim + c]))
                p = r;
        for (size_t k = 0; k < dim; ++k)
            std::swap(A[c * dim + k], A[p * dim + k]);
        std::swap(b[c], b[p]);
        for (size_t r = c + 1; r < dim; ++r) {
            const double m = A[r * dim + c] / A[c * dim + c];
            for (size_t k = c; k < dim; ++k)
                A[r * dim + k] -= m * A[c * dim + k];
            b[r] -= m * b[c];
        }
    }
    std::vector<double> x(dim);
    for (size_t r = dim; r-- > 0;) {
        double s = b[r];
        for (size_t k = r + 1; k < dim; ++k)
            s -= A[r * dim + k] * x[k];
        x[r] = s / A[r * dim + r];
    }
    down.resize(n + 1);
    up.resize(n + 1);
    for (size_t i = 0; i <= n; ++i) {
        up[i] = x[2 * i];
        down[i] = x[2 * i + 1];
    }
}

}  // namespace patina::texgen::fade::test
