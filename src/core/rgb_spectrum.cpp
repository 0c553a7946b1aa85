// RGB -> spectrum uplift, Jakob & Hanika 2019 (Computer Graphics Forum 38(2)): fit the
// sigmoid-polynomial S(A u^2 + B u + C) to a target colour by Levenberg-Marquardt on the
// CIELAB difference as they do, warm-started from a small table built lazily by continuation
// from the grey axis (their table-building scheme, coarser), then convert the coefficients to
// nanometres. Section and equation numbers are not cited: the paper is not in ../shared.
#include "core/rgb_spectrum.h"

#include "core/spectrum.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace patina {
namespace {

    using Vec3 = std::array<double, 3>;
    using Mat3 = std::array<double, 9>; // row-major

    // The fit works in u = (lambda - 595) / 235 in [-1, 1], which keeps the 3x3 system well
    // conditioned; the stored coefficients are converted to nm at the end.
    constexpr double kMidNm = 595.0;
    constexpr double kHalfNm = 235.0;
    // Stop fitting when the RGB residual is below this; float coefficients add ~1e-5.
    constexpr double kTolerance = 2e-6;
    // Bound on |A|, |B|, |C|. Rec.709-gamut colours need at most ~80; colours out of reach drive
    // the fit towards a box spectrum with unbounded coefficients, which float evaluation in nm
    // (c0 l^2 + c1 l + c2 with cancelling terms) would turn into noise.
    constexpr double kMaxCoeff = 1000.0;

    // Reflectance under D65 -> XYZ as a weighted sum over the 5 nm nodes, normalised so the
    // perfect white has Y = 1.
    struct Quadrature {
        std::vector<float> lambda;
        std::vector<double> u, wx, wy, wz;
        Vec3 white{};
    };

    // An interpolatory rule: between nodes the reflectance is the 4-point Lagrange cubic through
    // its node values, integrated against x̄ D65 (piecewise linear tables) on 50 sub-steps per
    // interval. Smooth reflectances integrate to ~1e-5 of the exact integral, where summing at
    // the 5 nm nodes (CIE 15's rule) errs by up to 1e-3 for steep sigmoids, at the same cost.
    Quadrature make_quadrature()
    {
        constexpr int n = kCieSamples;
        constexpr int kSub = 50;
        Quadrature q;
        q.wx.assign(n, 0.0);
        q.wy.assign(n, 0.0);
        q.wz.assign(n, 0.0);
        for (int i = 0; i < n; ++i) {
            const float l = kLambdaMinNm + kCieStepNm * static_cast<float>(i);
            q.lambda.push_back(l);
            q.u.push_back((l - kMidNm) / kHalfNm);
        }
        double y_sum = 0.0;
        for (int i = 0; i + 1 < n; ++i) {
            const int first = std::clamp(i - 1, 0, n - 4); // stencil of 4 nodes around [i, i+1]
            for (int s = 0; s < kSub; ++s) {
                const double x = i + (s + 0.5) / kSub; // midpoint of the sub-step, in node units
                const float l = static_cast<float>(kLambdaMinNm + kCieStepNm * x);
                const double w = d65(l) * kCieStepNm / kSub;
                y_sum += w * cie_y(l);
                for (int j = 0; j < 4; ++j) {
                    double basis = 1.0;
                    for (int m = 0; m < 4; ++m)
                        if (m != j)
                            basis *= (x - (first + m)) / double(j - m);
                    q.wx[first + j] += basis * w * cie_x(l);
                    q.wy[first + j] += basis * w * cie_y(l);
                    q.wz[first + j] += basis * w * cie_z(l);
                }
            }
        }
        for (int i = 0; i < n; ++i) {
            q.wx[i] /= y_sum;
            q.wy[i] /= y_sum;
            q.wz[i] /= y_sum;
            q.white[0] += q.wx[i];
            q.white[1] += q.wy[i];
            q.white[2] += q.wz[i];
        }
        return q;
    }

    const Quadrature& quadrature()
    {
        static const Quadrature q = make_quadrature();
        return q;
    }

    Vec3 mul(const Mat3& m, const Vec3& v)
    {
        return {m[0] * v[0] + m[1] * v[1] + m[2] * v[2], m[3] * v[0] + m[4] * v[1] + m[5] * v[2],
                m[6] * v[0] + m[7] * v[1] + m[8] * v[2]};
    }

    Mat3 mul(const Mat3& a, const Mat3& b)
    {
        Mat3 r{};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                for (int k = 0; k < 3; ++k)
                    r[3 * i + j] += a[3 * i + k] * b[3 * k + j];
        return r;
    }

    // Inverse by the adjugate; returns false when (nearly) singular.
    bool invert(const Mat3& m, Mat3& inv)
    {
        const double c0 = m[4] * m[8] - m[5] * m[7];
        const double c1 = m[5] * m[6] - m[3] * m[8];
        const double c2 = m[3] * m[7] - m[4] * m[6];
        const double det = m[0] * c0 + m[1] * c1 + m[2] * c2;
        if (!(std::abs(det) > 1e-300) || !std::isfinite(det))
            return false;
        const double s = 1.0 / det;
        inv = {c0 * s, (m[2] * m[7] - m[1] * m[8]) * s, (m[1] * m[5] - m[2] * m[4]) * s,
               c1 * s, (m[0] * m[8] - m[2] * m[6]) * s, (m[2] * m[3] - m[0] * m[5]) * s,
               c2 * s, (m[1] * m[6] - m[0] * m[7]) * s, (m[0] * m[4] - m[1] * m[3]) * s};
        return true;
    }

    // XYZ of S(A u^2 + B u + C) and its Jacobian d XYZ / d (A, B, C), with Jakob & Hanika's
    // sigmoid S(x) = 1/2 + x / (2 sqrt(1 + x^2)), so S'(x) = (1 + x^2)^(-3/2) / 2.
    void eval_xyz(const Quadrature& q, const Vec3& c, Vec3& xyz, Mat3& jac)
    {
        // Local accumulators: writing through the references every sample would serialise
        // the loop on memory.
        double sx = 0, sy = 0, sz = 0, jx[3] = {}, jy[3] = {}, jz[3] = {};
        const size_t n = q.u.size();
        const double* u = q.u.data();
        const double* wx = q.wx.data();
        const double* wy = q.wy.data();
        const double* wz = q.wz.data();
        for (size_t i = 0; i < n; ++i) {
            const double x = (c[0] * u[i] + c[1]) * u[i] + c[2];
            const double r2 = 1.0 / (1.0 + x * x);
            const double r = std::sqrt(r2);
            const double s = 0.5 + 0.5 * x * r;
            const double ds = 0.5 * r2 * r;
            const double d[3] = {ds * u[i] * u[i], ds * u[i], ds};
            sx += wx[i] * s;
            sy += wy[i] * s;
            sz += wz[i] * s;
            for (int j = 0; j < 3; ++j) {
                jx[j] += wx[i] * d[j];
                jy[j] += wy[i] * d[j];
                jz[j] += wz[i] * d[j];
            }
        }
        xyz = {sx, sy, sz};
        jac = {jx[0], jx[1], jx[2], jy[0], jy[1], jy[2], jz[0], jz[1], jz[2]};
    }

    // CIELAB (CIE 15:2004), with its derivative for the Jacobian.
    constexpr double kLabDelta = 6.0 / 29.0;
    double lab_f(double t)
    {
        return t > kLabDelta * kLabDelta * kLabDelta
                   ? std::cbrt(t)
                   : t / (3.0 * kLabDelta * kLabDelta) + 4.0 / 29.0;
    }
    double lab_df(double t)
    {
        return t > kLabDelta * kLabDelta * kLabDelta ? 1.0 / (3.0 * std::cbrt(t * t))
                                                     : 1.0 / (3.0 * kLabDelta * kLabDelta);
    }

    Vec3 xyz_to_lab(const Vec3& xyz, const Vec3& white, Mat3* jac)
    {
        double f[3], df[3];
        for (int k = 0; k < 3; ++k) {
            f[k] = lab_f(xyz[k] / white[k]);
            df[k] = lab_df(xyz[k] / white[k]) / white[k];
        }
        if (jac)
            *jac = {0.0, 116.0 * df[1], 0.0,           500.0 * df[0], -500.0 * df[1],
                    0.0, 0.0,           200.0 * df[1], -200.0 * df[2]};
        return {116.0 * f[1] - 16.0, 500.0 * (f[0] - f[1]), 200.0 * (f[1] - f[2])};
    }

    // A working space as the solver sees it: the quadrature and the white-matched matrices.
    struct Space {
        Mat3 rgb_to_xyz{}, xyz_to_rgb{};
    };

    struct Fit {
        Vec3 c;
        double rgb_error; // max abs component of the RGB residual
    };

    // Levenberg-Marquardt on the CIELAB residual (Jakob & Hanika minimise CIE76 ΔE);
    // stops when the working-space RGB residual is below `tol`.
    Fit fit(const Space& sp, const Vec3& target_rgb, Vec3 c, int max_iter, double tol)
    {
        for (double& v : c)
            v = std::clamp(v, -kMaxCoeff, kMaxCoeff);
        const Quadrature& q = quadrature();
        const Vec3 target_xyz = mul(sp.rgb_to_xyz, target_rgb);
        const Vec3 target_lab = xyz_to_lab(target_xyz, q.white, nullptr);
        auto residual = [&](const Vec3& cc, Vec3& xyz, Vec3& r, Mat3* jac) {
            Mat3 jx, jl;
            eval_xyz(q, cc, xyz, jx);
            const Vec3 lab = xyz_to_lab(xyz, q.white, &jl);
            for (int k = 0; k < 3; ++k)
                r[k] = lab[k] - target_lab[k];
            if (jac)
                *jac = mul(jl, jx);
            return r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
        };
        auto rgb_error = [&](const Vec3& xyz) {
            const Vec3 diff = {xyz[0] - target_xyz[0], xyz[1] - target_xyz[1],
                               xyz[2] - target_xyz[2]};
            const Vec3 d = mul(sp.xyz_to_rgb, diff);
            return std::max({std::abs(d[0]), std::abs(d[1]), std::abs(d[2])});
        };

        Vec3 xyz, r;
        Mat3 jac;
        double cost = residual(c, xyz, r, &jac);
        double err = rgb_error(xyz);
        double mu = 1e-6;
        for (int iter = 0; iter < max_iter && err > tol; ++iter) {
            // Normal equations (J^T J + mu diag(J^T J)) delta = -J^T r.
            Mat3 jtj{};
            Vec3 g{};
            for (int i = 0; i < 3; ++i) {
                for (int k = 0; k < 3; ++k)
                    g[i] += jac[3 * k + i] * r[k];
                for (int j = 0; j < 3; ++j)
                    for (int k = 0; k < 3; ++k)
                        jtj[3 * i + j] += jac[3 * k + i] * jac[3 * k + j];
            }
            bool accepted = false;
            for (int tries = 0; tries < 8 && !accepted; ++tries) {
                Mat3 h = jtj, hinv;
                for (int i = 0; i < 3; ++i)
                    h[4 * i] += mu * jtj[4 * i] + 1e-30;
                if (invert(h, hinv)) {
                    const Vec3 step = mul(hinv, g);
                    const Vec3 cn = {c[0] - step[0], c[1] - step[1], c[2] - step[2]};
                    Vec3 xyzn, rn;
                    Mat3 jacn;
                    const bool bounded =
                        std::max({std::abs(cn[0]), std::abs(cn[1]), std::abs(cn[2])}) <= kMaxCoeff;
                    const double cost_n = bounded ? residual(cn, xyzn, rn, &jacn) : cost;
                    if (std::isfinite(cost_n) && cost_n < cost) {
                        c = cn, xyz = xyzn, r = rn, jac = jacn, cost = cost_n;
                        err = rgb_error(xyz);
                        mu = std::max(mu * 0.1, 1e-9);
                        accepted = true;
                    }
                }
                if (!accepted)
                    mu *= 10.0;
            }
            if (!accepted)
                break; // a (local) minimum: the colour is out of the model's reach
        }
        return {c, err};
    }

    // Coefficients of the constant spectrum g (0 < g < 1).
    Vec3 grey_coeffs(double g)
    {
        g = std::clamp(g, 1e-4, 1.0 - 1e-4);
        return {0.0, 0.0, (g - 0.5) / std::sqrt(g * (1.0 - g))}; // S^-1(g)
    }

    // Fit from `start`; when that stalls in a local minimum (a poor warm start next to colours
    // the model cannot reach), walk the target from a grey of the same luminance, which the
    // model reaches exactly, to the goal in adaptive steps (a homotopy), so that every fit starts
    // next to its solution. Out-of-reach colours end at the closest point found.
    Fit solve(const Space& sp, const Vec3& target, const Vec3& start, double tol)
    {
        const Fit direct = fit(sp, target, start, 16, tol);
        if (direct.rgb_error <= tol)
            return direct;

        constexpr double kStepTol = 1e-4;
        // The white has Y = 1; keep the grey inside (0, 1), where S^-1 is finite.
        const double grey = std::clamp(mul(sp.rgb_to_xyz, target)[1], 1e-4, 1.0 - 1e-4);
        Vec3 c = grey_coeffs(grey);
        const Vec3 from = {grey, grey, grey}; // exact: the matrices are white-matched
        double t = 0.0, step = 0.25;
        while (t < 1.0 && step > 1.0 / 64.0) {
            const double tn = std::min(1.0, t + step);
            Vec3 goal;
            for (int k = 0; k < 3; ++k)
                goal[k] = from[k] + tn * (target[k] - from[k]);
            const Fit f = fit(sp, goal, c, 8, kStepTol);
            if (f.rgb_error <= kStepTol) {
                c = f.c;
                t = tn;
                step = std::min(2.0 * step, 0.5);
            } else {
                step *= 0.5;
            }
        }
        const Fit walked = fit(sp, target, c, 16, tol);
        return walked.rgb_error < direct.rgb_error ? walked : direct;
    }

} // namespace

// Warm starts: coefficients on a res^3 grid per largest channel (Jakob & Hanika's layout):
// z = max(rgb) on a smoothstep-squared scale, x, y = the other two channels / z.
struct RgbToSpectrum::Table {
    static constexpr int kRes = 16;
    Space space;
    std::once_flag once;
    std::vector<Vec3> coeffs; // [l][k (z)][j (y)][i (x)]
    std::vector<char> valid;  // the fit reached the entry's colour (else out of reach)
    double z_grid[kRes] = {};

    static int index(int l, int k, int j, int i) { return ((l * kRes + k) * kRes + j) * kRes + i; }
    Vec3& at(int l, int k, int j, int i) { return coeffs[index(l, k, j, i)]; }

    void build()
    {
        coeffs.assign(3 * kRes * kRes * kRes, Vec3{});
        valid.assign(coeffs.size(), 0);
        auto smoothstep = [](double t) { return t * t * (3.0 - 2.0 * t); };
        for (int k = 0; k < kRes; ++k)
            z_grid[k] = smoothstep(smoothstep(k / double(kRes - 1)));
        for (int l = 0; l < 3; ++l) {
            for (int k = 0; k < kRes; ++k) {
                // Keep the grey corner strictly inside (0, 1) where S^-1 is finite.
                const double z = std::clamp(z_grid[k], 1e-3, 1.0 - 1e-3);
                // March from the grey corner (i = j = res-1) towards saturated colours, each
                // solve starting from its solved neighbour.
                for (int j = kRes - 1; j >= 0; --j) {
                    for (int i = kRes - 1; i >= 0; --i) {
                        Vec3 start;
                        if (i == kRes - 1 && j == kRes - 1)
                            start = grey_coeffs(z);
                        else if (i == kRes - 1)
                            start = at(l, k, j + 1, i);
                        else
                            start = at(l, k, j, i + 1);
                        Vec3 rgb;
                        rgb[l] = z;
                        rgb[(l + 1) % 3] = z * i / double(kRes - 1);
                        rgb[(l + 2) % 3] = z * j / double(kRes - 1);
                        const Fit f = fit(space, rgb, start, 24, 1e-6);
                        at(l, k, j, i) = f.c;
                        valid[index(l, k, j, i)] = f.rgb_error < 1e-4;
                    }
                }
            }
        }
    }

    // Trilinear interpolation of the table's coefficients at rgb (max component > 0), over
    // the corners whose fit succeeded; a grey of equal luminance if none did.
    Vec3 warm_start(const Vec3& rgb) const
    {
        const int l = (rgb[0] >= rgb[1] && rgb[0] >= rgb[2]) ? 0 : (rgb[1] >= rgb[2] ? 1 : 2);
        const double z = rgb[l];
        const double x = std::clamp(rgb[(l + 1) % 3] / z, 0.0, 1.0) * (kRes - 1);
        const double y = std::clamp(rgb[(l + 2) % 3] / z, 0.0, 1.0) * (kRes - 1);
        const int k =
            std::clamp(int(std::upper_bound(z_grid, z_grid + kRes, z) - z_grid) - 1, 0, kRes - 2);
        const double tz = std::clamp((z - z_grid[k]) / (z_grid[k + 1] - z_grid[k]), 0.0, 1.0);
        const int i = std::min(int(x), kRes - 2), j = std::min(int(y), kRes - 2);
        const double tx = x - i, ty = y - j;
        Vec3 c{};
        double w_sum = 0.0;
        for (int dk = 0; dk < 2; ++dk)
            for (int dj = 0; dj < 2; ++dj)
                for (int di = 0; di < 2; ++di) {
                    const int e = index(l, k + dk, j + dj, i + di);
                    if (!valid[e])
                        continue;
                    const double w = (dk ? tz : 1 - tz) * (dj ? ty : 1 - ty) * (di ? tx : 1 - tx);
                    for (int m = 0; m < 3; ++m)
                        c[m] += w * coeffs[e][m];
                    w_sum += w;
                }
        if (w_sum > 1e-6)
            return {c[0] / w_sum, c[1] / w_sum, c[2] / w_sum};
        return grey_coeffs(mul(space.rgb_to_xyz, rgb)[1]);
    }
};

RgbToSpectrum::RgbToSpectrum(const Matrix3& rgb_to_xyz)
    : rgb_to_xyz_(rgb_to_xyz), table_(std::make_shared<Table>())
{
    // Match the matrix's white to the tables' D65 white (a rescale of X, Y, Z by a few
    // 1e-4 for the usual D65 matrices), so that a grey's constant spectrum maps back to
    // exactly that grey and near-greys stay continuous with it.
    const Vec3 white = quadrature().white;
    Space& sp = table_->space;
    for (int i = 0; i < 3; ++i) {
        const double row =
            double(rgb_to_xyz[3 * i]) + rgb_to_xyz[3 * i + 1] + rgb_to_xyz[3 * i + 2];
        for (int j = 0; j < 3; ++j)
            sp.rgb_to_xyz[3 * i + j] = rgb_to_xyz[3 * i + j] * (row != 0.0 ? white[i] / row : 1.0);
    }
    if (!invert(sp.rgb_to_xyz, sp.xyz_to_rgb))
        throw std::invalid_argument("RgbToSpectrum: the RGB -> XYZ matrix is singular");
    for (int i = 0; i < 9; ++i)
        xyz_to_rgb_[i] = static_cast<float>(sp.xyz_to_rgb[i]);
}

PatinaRgbSpectrum RgbToSpectrum::uplift(const std::array<float, 3>& rgb_in, bool illuminant) const
{
    PatinaRgbSpectrum out{0.0f, 0.0f, 0.0f, 0.0f, illuminant ? 1 : 0};
    // Reflectances are clamped to [0, 1]; emission only to >= 0 (NaN counts as 0).
    std::array<float, 3> rgb;
    for (int i = 0; i < 3; ++i) {
        const float v = std::isnan(rgb_in[i]) ? 0.0f : std::max(rgb_in[i], 0.0f);
        rgb[i] = illuminant ? std::min(v, 1e30f) : std::min(v, 1.0f);
    }
    // A grey is the constant 2g * S(0) = g exactly (illuminants: times the white).
    if (rgb[0] == rgb[1] && rgb[1] == rgb[2]) {
        out.scale = 2.0f * rgb[0];
        return out;
    }
    // Illuminants: fit rgb / (2 max) so the reflectance stays well inside [0, 1].
    const double max_c = std::max({rgb[0], rgb[1], rgb[2]});
    const double norm = illuminant ? 2.0 * max_c : 1.0;
    const Vec3 target = {rgb[0] / norm, rgb[1] / norm, rgb[2] / norm};

    Table& t = *table_;
    std::call_once(t.once, [&t] { t.build(); });
    const Fit f = solve(t.space, target, t.warm_start(target), kTolerance);

    // x = A u^2 + B u + C with u = (l - m) / h, expanded in powers of l (nm).
    const double a = f.c[0], b = f.c[1], c = f.c[2], m = kMidNm, h = kHalfNm;
    out.c0 = static_cast<float>(a / (h * h));
    out.c1 = static_cast<float>(b / h - 2.0 * a * m / (h * h));
    out.c2 = static_cast<float>(a * m * m / (h * h) - b * m / h + c);
    out.scale = static_cast<float>(norm);
    return out;
}

namespace {
    // 1 / Y of the embedded D65 table as a radiance (a function-local static: safe to use
    // from other translation units' static initialisers).
    float d65_unit_luminance()
    {
        static const float k = static_cast<float>(1.0 / emission_to_xyz(d65)[1]);
        return k;
    }
}  // namespace

float RgbToSpectrum::eval(const PatinaRgbSpectrum& s, float lambda_nm)
{
    const float v = patina_rgb_spectrum_eval(&s, lambda_nm);
    // Illuminants carry the white (D65) normalised to luminance Y = 1, so that an emission
    // colour (1, 1, 1) renders as working-space (1, 1, 1), as rgb_of assumes.
    return s.illuminant ? v * d65(lambda_nm) * d65_unit_luminance() : v;
}

float RgbToSpectrum::unit_d65(float lambda_nm)
{
    return d65(lambda_nm) * d65_unit_luminance();
}

float RgbToSpectrum::d65_to_unit_luminance()
{
    return d65_unit_luminance();
}

std::array<float, 3> RgbToSpectrum::rgb_of(const PatinaRgbSpectrum& s) const
{
    // The emission case reduces to the same sum: (scale S D65) / D65 normalisation.
    const Quadrature& q = quadrature();
    Vec3 xyz{};
    for (size_t i = 0; i < q.lambda.size(); ++i) {
        const double v = patina_rgb_spectrum_eval(&s, q.lambda[i]);
        xyz[0] += q.wx[i] * v;
        xyz[1] += q.wy[i] * v;
        xyz[2] += q.wz[i] * v;
    }
    const Vec3 rgb = mul(table_->space.xyz_to_rgb, xyz);
    return {static_cast<float>(rgb[0]), static_cast<float>(rgb[1]), static_cast<float>(rgb[2])};
}

} // namespace patina
