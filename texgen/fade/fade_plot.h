// Reflectance curves over time as a PNG, like Kimmel et al. 2013 figures 9-13: reflectance
// against wavelength, one line per exposure time (0h, 6h, 1d, 7d), with axes, ticks, axis
// labels, a title and a legend. Lines and text are drawn into an OIIO ImageBuf
// (ImageBufAlgo::render_line / render_text, DejaVu Sans when installed) and written with
// write_image_atomic.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace patina::texgen::fade {

struct PlotCurve {
    std::string label;                ///< legend entry, e.g. "1d"
    std::vector<double> x;            ///< wavelength, nm (increasing)
    std::vector<double> y;            ///< reflectance
    std::array<float, 3> rgb{0, 0, 0};  ///< line colour (display values in [0, 1])
};

struct PlotOptions {
    int width = 960;
    int height = 600;
    std::string title;
    std::string x_label = "wavelength (nm)";
    std::string y_label = "reflectance";
    double x_min = 0.0, x_max = 0.0;  ///< x range; equal: the curves' range
    double y_min = 0.0, y_max = 1.0;  ///< y range; y_max <= y_min: from the curves
    int legend_width = 150;           ///< pixels right of the plot for the legend
};

/// A colour per curve from dark red-brown (first) to light yellow (last), after the
/// progression the paper's plots use for increasing exposure; a single curve is black.
std::array<float, 3> time_ramp_color(size_t index, size_t count);

/// One of eight distinct colours for the index-th of several things (policies, colorants),
/// repeating after eight.
std::array<float, 3> categorical_color(size_t index);

/// Draw `curves` and write `path` (PNG, 8 bit) atomically. Throws std::runtime_error when
/// there is nothing to draw (no curve, a curve with fewer than two points or mismatched
/// x and y, non-finite values) or the file cannot be written. Text is left out, with one
/// warning on stderr, when no font is found.
void write_reflectance_plot(const std::filesystem::path& path,
                            const std::vector<PlotCurve>& curves, const PlotOptions& options);

/// "6h", "1d", "7d", "2.5y": a duration in seconds in the units the paper's legends use.
std::string duration_label(double seconds);

}  // namespace patina::texgen::fade
