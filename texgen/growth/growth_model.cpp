#include "texgen/growth/growth_model.h"

#include "texgen/growth/deposition.h"
#include "texgen/growth/noise_pattern.h"
#include "texgen/growth/percolation_depinning.h"
#include "texgen/growth/steady_thickening.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace patina::texgen {
namespace {

    constexpr std::array<std::string_view, 7> kModelNames = {
        "ST", "RD", "RDR", "BD", "DPD", "noise", "turbulence"};
    constexpr std::array<GrowthModelKind, 7> kModels = {
        GrowthModelKind::SteadyThickening,    GrowthModelKind::RandomDeposition,
        GrowthModelKind::RandomDepositionRelaxed, GrowthModelKind::BallisticDeposition,
        GrowthModelKind::DirectedPercolationDepinning, GrowthModelKind::Noise,
        GrowthModelKind::Turbulence};
    constexpr std::array<std::string_view, 4> kRateNames = {"linear", "parabolic",
                                                            "logarithmic", "cubic"};
    constexpr std::array<GrowthRate, 4> kRates = {GrowthRate::Linear, GrowthRate::Parabolic,
                                                  GrowthRate::Logarithmic, GrowthRate::Cubic};

    // Defaults in lattice cells (D&H 1996 §3.3: "the seed patches are 10 x 10 squares").
    constexpr double kPatchCells = 10.0;
    constexpr double kSeedSpacingPatches = 6.0;
    constexpr double kSpreadPatches = 10.0;
    constexpr double kStSpacingCells = 16.0;
    constexpr double kFeatureCells = 32.0;
    constexpr double kMaxLayers = 1.0e5;

    std::string number(double v)
    {
        std::string s = std::to_string(v);
        s.erase(s.find_last_not_of('0') + 1);
        if (!s.empty() && s.back() == '.')
            s.pop_back();
        return s;
    }

    [[noreturn]] void bad(const std::string& name, const std::string& rule, double value)
    {
        throw std::invalid_argument("growth parameter '" + name + "' must be " + rule +
                                    " (got " + number(value) + ")");
    }

    void check_non_negative(const char* name, double v)
    {
        if (!(v >= 0.0) || !std::isfinite(v))
            bad(name, "a finite number >= 0", v);
    }

    void check_probability(const char* name, double v)
    {
        if (!(v >= 0.0 && v <= 1.0))
            bad(name, "in [0, 1]", v);
    }

    std::vector<float> normalise(const std::vector<float>& pattern, double amount, float peak)
    {
        std::vector<float> out(pattern.size(), 0.0f);
        if (peak > 0.0f) {
            const double scale = amount / peak;
            for (size_t i = 0; i < out.size(); ++i)
                out[i] = std::min(1.0f, static_cast<float>(pattern[i] * scale));
        }
        return out;
    }

} // namespace

std::optional<GrowthModelKind> growth_model_from_name(std::string_view name)
{
    for (size_t i = 0; i < kModelNames.size(); ++i)
        if (kModelNames[i] == name)
            return kModels[i];
    return std::nullopt;
}

std::optional<GrowthRate> growth_rate_from_name(std::string_view name)
{
    for (size_t i = 0; i < kRateNames.size(); ++i)
        if (kRateNames[i] == name)
            return kRates[i];
    return std::nullopt;
}

std::span<const std::string_view> growth_model_names() { return kModelNames; }
std::span<const std::string_view> growth_rate_names() { return kRateNames; }

std::string_view growth_model_name(GrowthModelKind model)
{
    for (size_t i = 0; i < kModels.size(); ++i)
        if (kModels[i] == model)
            return kModelNames[i];
    return "?";
}

std::string_view growth_rate_name(GrowthRate rate)
{
    for (size_t i = 0; i < kRates.size(); ++i)
        if (kRates[i] == rate)
            return kRateNames[i];
    return "?";
}

double growth_rate(GrowthRate rate, double f)
{
    if (!(f >= 0.0 && f <= 1.0))
        throw std::invalid_argument("growth rate: fraction of the run " + number(f) +
                                    " is outside [0, 1]");
    switch (rate) {
    case GrowthRate::Linear: // x = k t
        return f;
    case GrowthRate::Parabolic: // x^2 = k t (diffusion through the film: Tammann, Evans)
        return std::sqrt(f);
    case GrowthRate::Cubic: // x^3 = k t
        return std::cbrt(f);
    case GrowthRate::Logarithmic: // x = k1 ln(1 + k2 t) (thin films: Evans)
        return std::log1p(kLogarithmicRateConstant * f) / std::log1p(kLogarithmicRateConstant);
    }
    return f;
}

double growth_fraction(const GrowthSpec& spec)
{
    if (spec.total <= 0)
        throw std::invalid_argument("growth total steps must be positive (got " +
                                    std::to_string(spec.total) + ")");
    if (spec.step < 0 || spec.step > spec.total)
        throw std::invalid_argument("growth step must be 0 to the total " +
                                    std::to_string(spec.total) + " (got " +
                                    std::to_string(spec.step) + ")");
    return static_cast<double>(spec.step) / spec.total;
}

double mean_cell_size(const Lattice& lattice)
{
    double sum = 0.0;
    for (float c : lattice.cell_size)
        sum += c;
    return lattice.cell_size.empty() ? 0.0 : sum / static_cast<double>(lattice.cell_size.size());
}

GrowthParameters resolve_growth_parameters(const Lattice& lattice, const GrowthParameters& in)
{
    if (lattice.size() == 0)
        throw std::invalid_argument("growth: the lattice has no nodes");
    GrowthParameters p = in;
    if (!(p.layers > 0.0 && p.layers <= kMaxLayers))
        bad("layers", "in (0, " + number(kMaxLayers) + "]", p.layers);
    check_non_negative("relaxation_radius", p.relaxation_radius);
    check_non_negative("patch_size", p.patch_size);
    check_probability("blocked_fraction", p.blocked_fraction);
    check_non_negative("seed_density", p.seed_density);
    check_non_negative("new_seed_ratio", p.new_seed_ratio);
    check_non_negative("spread_distance", p.spread_distance);
    check_probability("advance_unblocked", p.advance_unblocked);
    if (!(p.advance_unblocked > 0.0))
        bad("advance_unblocked", "in (0, 1]", p.advance_unblocked);
    check_probability("advance_blocked", p.advance_blocked);
    if (p.levels < 1 || p.levels > 255)
        bad("levels", "an integer from 1 to 255", p.levels);
    check_non_negative("st_spacing", p.st_spacing);
    check_non_negative("noise_amplitude", p.noise_amplitude);
    check_non_negative("feature_size", p.feature_size);
    if (p.octaves < 1 || p.octaves > 16)
        bad("octaves", "an integer from 1 to 16", p.octaves);

    const double cell = mean_cell_size(lattice);
    if (!(cell > 0.0) || !std::isfinite(cell))
        throw std::invalid_argument("growth: the lattice's mean cell size is " + number(cell));
    if (p.patch_size == 0.0)
        p.patch_size = kPatchCells * cell;
    if (p.seed_density == 0.0)
        p.seed_density = 1.0 / std::pow(kSeedSpacingPatches * p.patch_size, 2.0);
    if (p.spread_distance == 0.0)
        p.spread_distance = kSpreadPatches * p.patch_size;
    if (p.st_spacing == 0.0)
        p.st_spacing = kStSpacingCells * cell;
    if (p.feature_size == 0.0)
        p.feature_size = kFeatureCells * cell;
    return p;
}

std::vector<std::vector<float>> grow(const Lattice& lattice, const GrowthSpec& spec,
                                     uint64_t seed, std::span<const double> fractions)
{
    growth_fraction(spec); // checks step and total
    const GrowthParameters p = resolve_growth_parameters(lattice, spec.parameters);
    // The amount grown by each fraction, then the run's end for the normalisation.
    std::vector<double> amounts;
    for (double f : fractions) {
        if (!(f >= 0.0 && f <= 1.0))
            throw std::invalid_argument("growth fraction " + number(f) + " of the " +
                                        std::string(growth_model_name(spec.model)) +
                                        " run is outside [0, 1]");
        amounts.push_back(growth_rate(spec.rate, f));
    }
    const size_t n = lattice.size();
    std::vector<std::vector<float>> maps;
    maps.reserve(fractions.size());

    switch (spec.model) {
    case GrowthModelKind::RandomDeposition:
    case GrowthModelKind::RandomDepositionRelaxed:
    case GrowthModelKind::BallisticDeposition: {
        // layers * nodes particles over the run; a snapshot at each amount's share of them.
        const auto total = static_cast<uint64_t>(std::llround(p.layers * static_cast<double>(n)));
        std::vector<uint64_t> counts;
        for (double a : amounts)
            counts.push_back(static_cast<uint64_t>(std::llround(a * static_cast<double>(total))));
        counts.push_back(std::max<uint64_t>(total, 1));
        std::vector<uint64_t> sorted = counts;
        std::sort(sorted.begin(), sorted.end());
        sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
        const auto heights = deposit_heights(lattice, spec.model, p, seed, sorted);
        const auto& end = heights.back();
        const int32_t peak = *std::max_element(end.begin(), end.end());
        const float scale = peak > 0 ? 1.0f / static_cast<float>(peak) : 0.0f;
        for (size_t k = 0; k < amounts.size(); ++k) {
            const size_t at = std::lower_bound(sorted.begin(), sorted.end(), counts[k]) -
                              sorted.begin();
            std::vector<float> map(n);
            for (size_t i = 0; i < n; ++i)
                map[i] = static_cast<float>(heights[at][i]) * scale;
            maps.push_back(std::move(map));
        }
        break;
    }
    case GrowthModelKind::DirectedPercolationDepinning: {
        std::vector<double> times = amounts;
        times.push_back(1.0);
        const auto levels = percolation_depinning_levels(lattice, p, seed, times);
        const uint8_t peak = *std::max_element(levels.back().begin(), levels.back().end());
        const float scale = peak > 0 ? 1.0f / peak : 0.0f;
        for (size_t k = 0; k < amounts.size(); ++k) {
            std::vector<float> map(n);
            for (size_t i = 0; i < n; ++i)
                map[i] = static_cast<float>(levels[k][i]) * scale;
            maps.push_back(std::move(map));
        }
        break;
    }
    case GrowthModelKind::SteadyThickening:
    case GrowthModelKind::Noise:
    case GrowthModelKind::Turbulence: {
        // A fixed pattern scaled by the amount grown.
        const std::vector<float> pattern =
            spec.model == GrowthModelKind::SteadyThickening
                ? steady_thickening_pattern(lattice, p, seed)
                : noise_pattern(lattice, p, seed, spec.model == GrowthModelKind::Turbulence);
        const float peak = *std::max_element(pattern.begin(), pattern.end());
        for (double a : amounts)
            maps.push_back(normalise(pattern, a, peak));
        break;
    }
    }
    return maps;
}

} // namespace patina::texgen
