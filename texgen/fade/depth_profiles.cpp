#include "texgen/fade/depth_profiles.h"

#include "texgen/fade/fade_plot.h"

#include <fmt/format.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace patina::texgen::fade {

DepthProfiles run_depth_profiles(const FadeMaterial& material, const Illuminant& illuminant,
                                 const WavelengthGrid& grid, const ProfileRun& run)
{
    if (!(run.time_step_s > 0.0) || !std::isfinite(run.time_step_s))
        throw std::runtime_error(fmt::format("--time-step must be > 0, got {} s", run.time_step_s));
    if (run.steps < 1)
        throw std::runtime_error(fmt::format("--steps must be >= 1, got {}", run.steps));
    if (!(run.irradiance_w_m2 >= 0.0) || !std::isfinite(run.irradiance_w_m2))
        throw std::runtime_error(fmt::format("--irradiance must be a finite number of W/m^2 >= 0, "
                                             "got {}", run.irradiance_w_m2));
    std::vector<int> at_step;
    for (double t : run.times_s) {
        const double k = t / run.time_step_s;
        const double whole = std::round(k);
        if (!(t >= 0.0) || whole > run.steps || std::abs(k - whole) > 1e-6 * std::max(1.0, k))
            throw std::runtime_error(fmt::format(
                "--profiles-at {}: each time must be a whole number of --time-step ({}) up to "
                "{} steps", duration_label(t), duration_label(run.time_step_s), run.steps));
        at_step.push_back(static_cast<int>(whole));
    }

    FadeSimulation sim(material, grid, run.sublayers);
    const Illumination light = illuminant.illumination(grid, run.irradiance_w_m2, run.both_sides);
    DepthProfiles out;
    for (const Colorant& c : material.colorants)
        out.colorants.push_back(c.name);
    out.thickness_m = material.thickness_m;
    out.sublayers = run.sublayers;
    out.wavelength_nm = grid.nm;
    auto keep = [&](double t) {
        out.snapshots.push_back({t, sim.fractions(), sim.reflectance()});
    };
    keep(0.0);
    int step = 0;
    for (size_t i = 0; i < at_step.size(); ++i) {
        for (; step < at_step[i]; ++step)
            sim.step(light, run.time_step_s);
        keep(run.times_s[i]);
    }
    return out;
}

std::string profiles_csv(const DepthProfiles& p)
{
    std::ostringstream s;
    s << "time_s,sublayer,depth_um";
    for (const std::string& c : p.colorants)
        s << "," << c;
    s << "\n";
    const size_t j_count = p.colorants.size();
    const double dz_um = p.thickness_m * 1e6 / p.sublayers;
    for (const ProfileSnapshot& snap : p.snapshots)
        for (int i = 0; i < p.sublayers; ++i) {
            s << fmt::format("{:.6g},{},{:.6g}", snap.time_s, i, (i + 0.5) * dz_um);
            for (size_t j = 0; j < j_count; ++j)
                s << fmt::format(",{:.9g}", snap.fractions[static_cast<size_t>(i) * j_count + j]);
            s << "\n";
        }
    return s.str();
}

std::string reflectance_csv(const DepthProfiles& p)
{
    std::ostringstream s;
    s << "wavelength_nm";
    for (const ProfileSnapshot& snap : p.snapshots)
        s << fmt::format(",t_{:.6g}s", snap.time_s);
    s << "\n";
    for (size_t w = 0; w < p.wavelength_nm.size(); ++w) {
        s << fmt::format("{:.6g}", p.wavelength_nm[w]);
        for (const ProfileSnapshot& snap : p.snapshots)
            s << fmt::format(",{:.9g}", snap.reflectance[w]);
        s << "\n";
    }
    return s.str();
}

void write_profiles_plot(const std::filesystem::path& path, const DepthProfiles& p,
                         const std::string& title)
{
    const size_t j_count = p.colorants.size();
    const double dz_um = p.thickness_m * 1e6 / p.sublayers;
    std::vector<PlotCurve> curves;
    for (size_t j = 0; j < j_count; ++j) {
        const ProfileSnapshot& first = p.snapshots.front();
        bool changes = false;
        for (const ProfileSnapshot& snap : p.snapshots)
            for (int i = 0; i < p.sublayers; ++i)
                changes |= snap.fractions[i * j_count + j] != first.fractions[i * j_count + j];
        if (!changes)
            continue;
        // A breakdown product starts at 0: its fraction is shown relative to its largest
        double scale = 0.0;
        for (const ProfileSnapshot& snap : p.snapshots)
            for (int i = 0; i < p.sublayers; ++i)
                scale = std::max(scale, snap.fractions[i * j_count + j]);
        const size_t shown = curves.size() / (p.snapshots.size() - 1);
        for (size_t k = 1; k < p.snapshots.size(); ++k) {
            PlotCurve c;
            c.label = fmt::format("{} {}", p.colorants[j], duration_label(p.snapshots[k].time_s));
            for (int i = 0; i < p.sublayers; ++i) {
                c.x.push_back((i + 0.5) * dz_um);
                const double f0 = first.fractions[i * j_count + j];
                const double f = p.snapshots[k].fractions[i * j_count + j];
                c.y.push_back(f0 > 0.0 ? f / f0 : f / scale);
            }
            // A hue per colorant, lighter for later times
            const float lighten = 0.6f * static_cast<float>(k - 1) /
                                  static_cast<float>(std::max<size_t>(p.snapshots.size() - 2, 1));
            c.rgb = categorical_color(shown);
            for (float& v : c.rgb)
                v += (1.0f - v) * lighten;
            curves.push_back(std::move(c));
        }
    }
    if (curves.empty())
        throw std::runtime_error("plot '" + path.string() + "': no colorant changes over the run");
    PlotOptions o;
    o.title = title;
    o.x_label = "depth (um)";
    o.y_label = "fraction / unexposed";
    o.y_min = 0.0;
    o.y_max = 1.05;
    o.width = 1280;
    o.height = 640;
    o.legend_width = 360;
    write_reflectance_plot(path, curves, o);
}

}  // namespace patina::texgen::fade
