// Reflectance plots drawn with OIIO's ImageBufAlgo (lines, boxes, text) and written as PNG.
#include "texgen/fade/fade_plot.h"

#include "core/image_io.h"

#include <OpenImageIO/imagebufalgo.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace patina::texgen::fade {

namespace {

    namespace IBA = OIIO::ImageBufAlgo;

    // DejaVu Sans from the Debian package when present, else whatever OIIO finds.
    std::string font_name()
    {
        const char* candidates[] = {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
                                    "/usr/share/fonts/TTF/DejaVuSans.ttf"};
        for (const char* c : candidates)
            if (std::filesystem::exists(c))
                return c;
        return "";
    }

    // "Nice" tick step: 1, 2 or 5 times a power of ten, about `count` ticks over `span`.
    double tick_step(double span, int count)
    {
        const double raw = span / std::max(count, 1);
        const double power = std::pow(10.0, std::floor(std::log10(raw)));
        for (double m : {1.0, 2.0, 5.0, 10.0})
            if (m * power >= raw)
                return m * power;
        return 10.0 * power;
    }

    class Canvas {
    public:
        Canvas(int width, int height)
            : buf_(OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::FLOAT)), font_(font_name())
        {
            const float white[3] = {1.0f, 1.0f, 1.0f};
            IBA::fill(buf_, white);
        }
        void line(double x0, double y0, double x1, double y1, const float* rgb, int thickness = 1)
        {
            // A thick line as parallel one-pixel lines, offset across its main direction
            const bool steep = std::abs(y1 - y0) > std::abs(x1 - x0);
            for (int k = 0; k < thickness; ++k) {
                const int o = k - thickness / 2;
                const int dx = steep ? o : 0, dy = steep ? 0 : o;
                IBA::render_line(buf_, static_cast<int>(std::lround(x0)) + dx,
                                 static_cast<int>(std::lround(y0)) + dy,
                                 static_cast<int>(std::lround(x1)) + dx,
                                 static_cast<int>(std::lround(y1)) + dy, {rgb, 3});
            }
        }
        void text(int x, int y, const std::string& s, int size, IBA::TextAlignX ax,
                  IBA::TextAlignY ay)
        {
            if (no_text_)
                return;
            const float black[3] = {0.1f, 0.1f, 0.1f};
            if (!IBA::render_text(buf_, x, y, s, size, font_, {black, 3}, ax, ay)) {
                no_text_ = true;
                std::fprintf(stderr, "fade plot: warning: no font for the labels (%s)\n",
                             buf_.geterror().c_str());
            }
        }
        const OIIO::ImageBuf& buf() const { return buf_; }

    private:
        OIIO::ImageBuf buf_;
        std::string font_;
        bool no_text_ = false;
    };

}  // namespace

std::array<float, 3> time_ramp_color(size_t index, size_t count)
{
    if (count <= 1)
        return {0.0f, 0.0f, 0.0f};
    // From dark brown-red through orange to a yellow still readable on white
    const float t = static_cast<float>(index) / static_cast<float>(count - 1);
    return {0.35f + 0.55f * t, 0.05f + 0.65f * t, 0.05f + 0.05f * t};
}

std::array<float, 3> categorical_color(size_t index)
{
    static constexpr std::array<std::array<float, 3>, 8> kPalette = {{{0.12f, 0.35f, 0.75f},
                                                                     {0.85f, 0.33f, 0.10f},
                                                                     {0.20f, 0.60f, 0.25f},
                                                                     {0.55f, 0.25f, 0.65f},
                                                                     {0.80f, 0.65f, 0.05f},
                                                                     {0.05f, 0.60f, 0.65f},
                                                                     {0.60f, 0.35f, 0.20f},
                                                                     {0.90f, 0.40f, 0.60f}}};
    return kPalette[index % kPalette.size()];
}

std::string duration_label(double seconds)
{
    auto fmt_value = [](double v, const char* unit) {
        return std::abs(v - std::round(v)) < 1e-6 * std::max(1.0, std::abs(v))
                   ? fmt::format("{}{}", static_cast<long long>(std::llround(v)), unit)
                   : fmt::format("{:.3g}{}", v, unit);
    };
    if (seconds <= 0.0)
        return "0h";
    if (seconds < 86400.0)
        return fmt_value(seconds / 3600.0, "h");
    if (seconds < 365.0 * 86400.0)
        return fmt_value(seconds / 86400.0, "d");
    return fmt_value(seconds / (365.0 * 86400.0), "y");
}

void write_reflectance_plot(const std::filesystem::path& path,
                            const std::vector<PlotCurve>& curves, const PlotOptions& options)
{
    if (curves.empty())
        throw std::runtime_error("plot '" + path.string() + "': no curves to draw");
    double x_min = options.x_min, x_max = options.x_max;
    double y_min = options.y_min, y_max = options.y_max;
    const bool auto_x = !(x_max > x_min), auto_y = !(y_max > y_min);
    if (auto_x) {
        x_min = curves.front().x.empty() ? 0.0 : curves.front().x.front();
        x_max = x_min;
    }
    if (auto_y) {
        y_min = 0.0;
        y_max = 0.0;
    }
    for (const PlotCurve& c : curves) {
        if (c.x.size() < 2 || c.x.size() != c.y.size())
            throw std::runtime_error("plot '" + path.string() + "': curve '" + c.label +
                                     "' needs two or more points with one value each");
        for (size_t i = 0; i < c.x.size(); ++i) {
            if (!std::isfinite(c.x[i]) || !std::isfinite(c.y[i]))
                throw std::runtime_error("plot '" + path.string() + "': curve '" + c.label +
                                         "' holds a non-finite value at point " +
                                         std::to_string(i));
            if (auto_x) {
                x_min = std::min(x_min, c.x[i]);
                x_max = std::max(x_max, c.x[i]);
            }
            if (auto_y)
                y_max = std::max(y_max, c.y[i]);
        }
    }
    if (auto_y) {
        const double step = tick_step(std::max(y_max, 1e-3), 5);
        y_max = std::ceil(y_max / step) * step;
    }
    if (!(x_max > x_min) || !(y_max > y_min))
        throw std::runtime_error("plot '" + path.string() + "': empty range");

    // Layout: plot area inside margins for the tick labels, axis labels and the title
    const int w = options.width, h = options.height;
    const int left = 90, right = w - options.legend_width, top = 50, bottom = h - 70;
    auto px = [&](double x) { return left + (x - x_min) / (x_max - x_min) * (right - left); };
    auto py = [&](double y) { return bottom - (y - y_min) / (y_max - y_min) * (bottom - top); };

    Canvas canvas(w, h);
    const float axis[3] = {0.1f, 0.1f, 0.1f};
    const float grid[3] = {0.88f, 0.88f, 0.88f};
    using AX = IBA::TextAlignX;
    using AY = IBA::TextAlignY;

    // Grid lines and ticks with their values
    const double xs = tick_step(x_max - x_min, 8), ys = tick_step(y_max - y_min, 5);
    for (double x = std::ceil(x_min / xs) * xs; x <= x_max + 1e-9 * xs; x += xs) {
        canvas.line(px(x), top, px(x), bottom, grid);
        canvas.line(px(x), bottom, px(x), bottom + 6, axis);
        canvas.text(static_cast<int>(px(x)), bottom + 10, fmt::format("{:g}", x), 15, AX::Center,
                    AY::Top);
    }
    for (double y = std::ceil(y_min / ys) * ys; y <= y_max + 1e-9 * ys; y += ys) {
        canvas.line(left, py(y), right, py(y), grid);
        canvas.line(left - 6, py(y), left, py(y), axis);
        canvas.text(left - 10, static_cast<int>(py(y)), fmt::format("{:g}", y), 15, AX::Right,
                    AY::Center);
    }
    canvas.line(left, top, left, bottom, axis, 2);
    canvas.line(left, bottom, right, bottom, axis, 2);
    canvas.text((left + right) / 2, h - 12, options.x_label, 17, AX::Center, AY::Bottom);
    canvas.text(12, top - 18, options.y_label, 17, AX::Left, AY::Bottom);
    if (!options.title.empty())
        canvas.text((left + right) / 2, 10, options.title, 19, AX::Center, AY::Top);

    // Curves, clipped to the plot area, then the legend to the right
    for (size_t k = 0; k < curves.size(); ++k) {
        const PlotCurve& c = curves[k];
        for (size_t i = 1; i < c.x.size(); ++i) {
            auto clip_y = [&](double y) { return std::clamp(y, y_min, y_max); };
            if (c.x[i] < x_min || c.x[i - 1] > x_max)
                continue;
            canvas.line(px(std::max(c.x[i - 1], x_min)), py(clip_y(c.y[i - 1])),
                        px(std::min(c.x[i], x_max)), py(clip_y(c.y[i])), c.rgb.data(), 3);
        }
        const int ly = top + 10 + static_cast<int>(k) * 24;
        canvas.line(right + 15, ly, right + 45, ly, c.rgb.data(), 3);
        canvas.text(right + 52, ly, c.label, 15, AX::Left, AY::Center);
    }

    const OIIO::ImageBuf& buf = canvas.buf();
    std::vector<float> pixels(static_cast<size_t>(w) * h * 3);
    buf.get_pixels(OIIO::ROI(0, w, 0, h, 0, 1, 0, 3), OIIO::TypeDesc::FLOAT, pixels.data());
    write_image_atomic(path, pixels.data(), w, h, 3, {}, OIIO::TypeDesc::UINT8);
}

}  // namespace patina::texgen::fade
