#include "texgen/restore/fade_inversion.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace patina::texgen::restore {

namespace {

using Matrix3 = std::array<std::array<double, 3>, 3>;

// The largest eigenvalue of the leading n x n block of a symmetric matrix, by cyclic Jacobi
// rotations (the rest is zeroed).
double largest_eigenvalue(Matrix3 a, size_t n)
{
    for (size_t i = 0; i < 3; ++i)
        for (size_t j = 0; j < 3; ++j)
            if (i >= n || j >= n)
                a[i][j] = 0.0;
    for (int sweep = 0; sweep < 50; ++sweep) {
        double off = 0.0;
        for (size_t p = 0; p < 3; ++p)
            for (size_t q = p + 1; q < 3; ++q)
                off += a[p][q] * a[p][q];
        if (off < 1e-30)
            break;
        for (size_t p = 0; p < 3; ++p)
            for (size_t q = p + 1; q < 3; ++q) {
                if (std::abs(a[p][q]) < 1e-300)
                    continue;
                const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                const double t = (theta >= 0 ? 1.0 : -1.0) /
                                 (std::abs(theta) + std::sqrt(theta * theta + 1.0));
                const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
                for (size_t k = 0; k < 3; ++k) {
                    const double akp = a[k][p], akq = a[k][q];
                    a[k][p] = c * akp - s * akq;
                    a[k][q] = s * akp + c * akq;
                }
                for (size_t k = 0; k < 3; ++k) {
                    const double apk = a[p][k], aqk = a[q][k];
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                }
            }
    }
    return std::max({a[0][0], a[1][1], a[2][2]});
}

// How far the restored colour can move per unit the faded colour moves: the largest λ of
// N v = λ M v (M = J_f^T J_f, N = J_u^T J_u), through M's Cholesky factor, square-rooted.
// A direction M does not see (a colorant faded to nothing) makes it infinite.
double amplification(Matrix3 m, const Matrix3& nm, size_t n)
{
    double scale = 0.0;
    for (size_t i = 0; i < n; ++i)
        scale = std::max(scale, m[i][i]);
    Matrix3 l{};
    for (size_t i = 0; i < n; ++i)
        for (size_t j = 0; j <= i; ++j) {
            double v = m[i][j];
            for (size_t k = 0; k < j; ++k)
                v -= l[i][k] * l[j][k];
            if (i == j) {
                if (!(v > 1e-12 * scale))
                    return std::numeric_limits<double>::infinity();
                l[i][i] = std::sqrt(v);
            } else {
                l[i][j] = v / l[j][j];
            }
        }
    // C = L^-1 N L^-T
    Matrix3 x{};  // L^-1 N
    for (size_t c = 0; c < n; ++c)
        for (size_t i = 0; i < n; ++i) {
            double v = nm[i][c];
            for (size_t k = 0; k < i; ++k)
                v -= l[i][k] * x[k][c];
            x[i][c] = v / l[i][i];
        }
    Matrix3 cm{};  // (L^-1 (L^-1 N)^T)^T = L^-1 N L^-T
    for (size_t r = 0; r < n; ++r)
        for (size_t i = 0; i < n; ++i) {
            double v = x[r][i];
            for (size_t k = 0; k < i; ++k)
                v -= l[i][k] * cm[r][k];
            cm[r][i] = v / l[i][i];
        }
    return std::sqrt(std::max(0.0, largest_eigenvalue(cm, n)));
}

Imath::V3d lab_vector(const Lab& l) { return {l.L, l.a, l.b}; }

// The nodes hold log XYZ: closer to linear in the amounts of absorbers than XYZ itself
// (absorbance is linear in concentration), so the multilinear interpolation between
// levels errs less.
constexpr double kLogFloor = 1e-6;
Imath::V3d to_log(const Imath::V3d& v)
{
    return {std::log(std::max(v.x, kLogFloor)), std::log(std::max(v.y, kLogFloor)),
            std::log(std::max(v.z, kLogFloor))};
}
Imath::V3d from_log(const Imath::V3d& v) { return {std::exp(v.x), std::exp(v.y), std::exp(v.z)}; }

}  // namespace

FadeInversion::FadeInversion(const fade::FadeMaterial& material, const fade::Illuminant& light,
                             const fade::WavelengthGrid& grid, const forecast::ColourMeter& meter,
                             const InversionOptions& options)
    : options_(options), meter_(&meter)
{
    material.validate();
    for (size_t j = 0; j < material.colorants.size(); ++j) {
        const fade::Colorant& c = material.colorants[j];
        bool absorbs = false;
        for (double v : c.absorption_per_m.value)
            absorbs |= v > 0.0;
        const bool fades = c.fading.rate_m3_per_j > 0.0 || c.breakdown.has_value();
        const bool named = options.colorants.empty() ||
                           std::find(options.colorants.begin(), options.colorants.end(), c.name) !=
                               options.colorants.end();
        if (absorbs && fades && material.initial_fractions[j] > 0.0 && named) {
            free_.push_back(j);
            free_names_.push_back(c.name);
        }
    }
    for (const std::string& name : options.colorants)
        if (std::find(free_names_.begin(), free_names_.end(), name) == free_names_.end())
            throw std::runtime_error("restore: '" + name + "' is not a fading colorant '" +
                                     material.name + "' starts with");
    if (free_.empty())
        throw std::runtime_error("restore: no colorant of '" + material.name + "' fades: there is "
                                 "nothing to restore");
    if (free_.size() > 3)
        throw std::runtime_error(fmt::format(
            "restore: {} colorants of '{}' fade; one colour fixes at most three original amounts "
            "(name the ones to solve for)",
            free_.size(), material.name));
    if (!(options.max_amount > 0.0) || !(options.max_dose_j_m2 > 0.0) || options.entries < 2)
        throw std::runtime_error("restore: the amounts' and the doses' ranges must be > 0");
    const int default_levels[] = {33, 17, 12};
    levels_ = options.levels > 0 ? options.levels : default_levels[free_.size() - 1];
    if (levels_ < 2)
        throw std::runtime_error("restore: at least 2 levels per colorant");
    size_t nodes = 1;
    for (size_t d = 0; d < free_.size(); ++d)
        nodes *= static_cast<size_t>(levels_);

    fade::DoseTableOptions t;
    t.max_dose_j_m2 = options.max_dose_j_m2;
    t.knee_dose_j_m2 = options.max_dose_j_m2 * 1e-4;
    t.entries = options.entries;
    t.sublayers = options.sublayers;
    entries_ = static_cast<size_t>(options.entries);
    knee_ = t.knee_dose_j_m2;
    inv_du_ = (options.entries - 1) / std::log1p(t.max_dose_j_m2 / t.knee_dose_j_m2);
    node_xyz_.resize(nodes * entries_);
    tbb::parallel_for(size_t(0), nodes, [&](size_t node) {
        fade::FadeMaterial m = material;
        size_t rest = node;
        for (size_t d = free_.size(); d-- > 0;) {
            const int level = static_cast<int>(rest % levels_);
            rest /= levels_;
            // Levels at (i / (n-1))^2 of the range: dense near 0
            const double u = static_cast<double>(level) / (levels_ - 1);
            m.initial_fractions[free_[d]] *= options.max_amount * u * u;
        }
        // More than the layer holds: the binder (largest other fraction) makes room
        double total = 0.0;
        for (double f : m.initial_fractions)
            total += f;
        if (total > 1.0) {
            size_t largest = 0;
            for (size_t j = 0; j < m.initial_fractions.size(); ++j)
                if (std::find(free_.begin(), free_.end(), j) == free_.end() &&
                    m.initial_fractions[j] > m.initial_fractions[largest])
                    largest = j;
            m.initial_fractions[largest] = std::max(0.0, m.initial_fractions[largest] - (total - 1.0));
        }
        const fade::DoseTable table = fade::DoseTable::build(m, light, grid, t);
        for (size_t k = 0; k < entries_; ++k)
            node_xyz_[node * entries_ + k] = to_log(meter.xyz(table.spectra(k).reflectance));
    });
}

FadeInversion::Row FadeInversion::row(double dose) const
{
    const double u = std::min(std::log1p(std::max(dose, 0.0) / knee_) * inv_du_,
                              static_cast<double>(entries_ - 1));
    Row r;
    r.lower = std::min(static_cast<size_t>(u), entries_ - 2);
    r.weight = u - static_cast<double>(r.lower);
    return r;
}

double FadeInversion::level_coordinate(double amount) const
{
    const double u = std::sqrt(std::clamp(amount / options_.max_amount, 0.0, 1.0));
    return u * (levels_ - 1);
}

Imath::V3d FadeInversion::xyz_at(const std::array<double, 3>& amounts, const Row& r) const
{
    const size_t dims = free_.size();
    size_t base[3] = {0, 0, 0};
    double frac[3] = {0, 0, 0};
    for (size_t d = 0; d < dims; ++d) {
        const double c = level_coordinate(amounts[d]);
        base[d] = std::min(static_cast<size_t>(c), static_cast<size_t>(levels_ - 2));
        frac[d] = c - static_cast<double>(base[d]);
    }
    Imath::V3d sum(0.0);
    for (size_t corner = 0; corner < (size_t(1) << dims); ++corner) {
        double w = 1.0;
        size_t node = 0;
        for (size_t d = 0; d < dims; ++d) {
            const size_t bit = (corner >> d) & 1;
            w *= bit ? frac[d] : 1.0 - frac[d];
            node = node * levels_ + base[d] + bit;
        }
        if (w == 0.0)
            continue;
        const Imath::V3d& lo = node_xyz_[node * entries_ + r.lower];
        const Imath::V3d& hi = node_xyz_[node * entries_ + r.lower + 1];
        sum += w * (lo + (hi - lo) * r.weight);
    }
    return from_log(sum);
}

Imath::V3d FadeInversion::xyz(const std::array<double, 3>& amounts, double dose) const
{
    return xyz_at(amounts, row(dose));
}

Inversion FadeInversion::invert(const Imath::V3d& observed_xyz, double dose) const
{
    const size_t dims = free_.size();
    const Row r = row(dose);
    const Imath::V3d target = lab_vector(meter_->lab_of_xyz(observed_xyz));
    const double prior = options_.prior_weight;
    auto lab_at = [&](const std::array<double, 3>& s) {
        return lab_vector(meter_->lab_of_xyz(xyz_at(s, r)));
    };
    // Gauss-Newton on |Lab(s) - target|^2 + prior^2 |s - 1|^2, s within [0, max]
    std::array<double, 3> s{1.0, 1.0, 1.0};
    const double h = 1e-3 * options_.max_amount;
    std::array<Imath::V3d, 3> jac{};
    auto jacobian = [&](const std::array<double, 3>& at) {
        for (size_t d = 0; d < dims; ++d) {
            std::array<double, 3> up = at, down = at;
            up[d] = std::min(at[d] + h, options_.max_amount);
            down[d] = std::max(at[d] - h, 0.0);
            jac[d] = (lab_at(up) - lab_at(down)) / (up[d] - down[d]);
        }
    };
    for (int iteration = 0; iteration < 40; ++iteration) {
        const Imath::V3d e = lab_at(s) - target;
        jacobian(s);
        // Normal equations (J^T J + prior^2 I) ds = -(J^T e + prior^2 (s - 1))
        std::array<std::array<double, 3>, 3> a{};
        std::array<double, 3> b{};
        for (size_t p = 0; p < dims; ++p) {
            for (size_t q = 0; q < dims; ++q)
                a[p][q] = jac[p].dot(jac[q]) + (p == q ? prior * prior : 0.0);
            b[p] = -(jac[p].dot(e) + prior * prior * (s[p] - 1.0));
        }
        // Solve by Gaussian elimination (dims <= 3, the matrix is positive definite)
        std::array<double, 3> ds{};
        for (size_t p = 0; p < dims; ++p) {
            for (size_t q = p + 1; q < dims; ++q) {
                const double f = a[q][p] / a[p][p];
                for (size_t k = p; k < dims; ++k)
                    a[q][k] -= f * a[p][k];
                b[q] -= f * b[p];
            }
        }
        for (size_t p = dims; p-- > 0;) {
            double v = b[p];
            for (size_t k = p + 1; k < dims; ++k)
                v -= a[p][k] * ds[k];
            ds[p] = v / a[p][p];
        }
        double step = 0.0;
        for (size_t d = 0; d < dims; ++d) {
            const double next = std::clamp(s[d] + ds[d], 0.0, options_.max_amount);
            step = std::max(step, std::abs(next - s[d]));
            s[d] = next;
        }
        if (step < 1e-7)
            break;
    }

    Inversion out;
    out.amounts = s;
    out.faded_xyz = xyz_at(s, r);
    out.unfaded_xyz = xyz_at(s, row(0.0));
    out.residual = delta_e2000(meter_->lab_of_xyz(out.faded_xyz), meter_->lab_of_xyz(observed_xyz));
    // How well the faded colour pins the restored one: the Jacobians of both in CIELAB
    jacobian(s);
    const std::array<Imath::V3d, 3> faded = jac;
    const Row unexposed = row(0.0);
    for (size_t d = 0; d < dims; ++d) {
        std::array<double, 3> up = s, down = s;
        up[d] = std::min(s[d] + h, options_.max_amount);
        down[d] = std::max(s[d] - h, 0.0);
        jac[d] = (lab_vector(meter_->lab_of_xyz(xyz_at(up, unexposed))) -
                  lab_vector(meter_->lab_of_xyz(xyz_at(down, unexposed)))) /
                 (up[d] - down[d]);
    }
    Matrix3 m{}, nm{};
    for (size_t p = 0; p < dims; ++p)
        for (size_t q = 0; q < dims; ++q) {
            m[p][q] = faded[p].dot(faded[q]);
            nm[p][q] = jac[p].dot(jac[q]);
        }
    out.amplification = amplification(m, nm, dims);
    out.unique = out.amplification <= options_.max_amplification &&
                 out.residual <= options_.max_residual;
    return out;
}

}  // namespace patina::texgen::restore
