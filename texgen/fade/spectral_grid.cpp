#include "texgen/fade/spectral_grid.h"

#include "core/limits.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace patina::texgen::fade {

double TabulatedSpectrum::at(double lambda_nm) const
{
    if (nm.empty())
        return 0.0;
    if (lambda_nm <= nm.front())
        return value.front();
    if (lambda_nm >= nm.back())
        return value.back();
    const size_t hi = static_cast<size_t>(std::upper_bound(nm.begin(), nm.end(), lambda_nm) -
                                          nm.begin());
    const size_t lo = hi - 1;
    const double t = (lambda_nm - nm[lo]) / (nm[hi] - nm[lo]);
    return value[lo] + t * (value[hi] - value[lo]);
}

WavelengthGrid WavelengthGrid::uniform(double first_nm, double last_nm, double step_nm)
{
    if (!(step_nm > 0.0) || !(last_nm >= first_nm))
        throw std::runtime_error("wavelength grid: need step > 0 and last >= first");
    WavelengthGrid g;
    const double count = std::floor((last_nm - first_nm) / step_nm + 1e-9) + 1;
    check_limit(fmt::format("wavelength grid {}:{}:{}", first_nm, last_nm, step_nm), count,
                kMaxWavelengths, "wavelengths");
    const int n = static_cast<int>(count);
    g.nm.reserve(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i)
        g.nm.push_back(first_nm + i * step_nm);
    return g;
}

std::vector<double> WavelengthGrid::trapezoid_weights() const
{
    std::vector<double> w(nm.size(), 0.0);
    if (nm.size() == 1) {
        w[0] = 1.0;
        return w;
    }
    for (size_t i = 0; i + 1 < nm.size(); ++i) {
        const double half = 0.5 * (nm[i + 1] - nm[i]);
        w[i] += half;
        w[i + 1] += half;
    }
    return w;
}

std::vector<double> WavelengthGrid::sample(const TabulatedSpectrum& s) const
{
    std::vector<double> out(nm.size());
    for (size_t i = 0; i < nm.size(); ++i)
        out[i] = s.at(nm[i]);
    return out;
}

}  // namespace patina::texgen::fade
