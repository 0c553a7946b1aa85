// Reading a fade stack in create: fade.toml and the table by the file-format library's
// readers (the table through host->read_image), the dose map through host->open_texture.
#include "fade_table.h"

#include "formats/fade_stack/fade_stack.h"
#include "formats/host_pixels.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace patina::spectral_km {

namespace fs = std::filesystem;

std::string FadeTable::load(const PatinaHost* host, const char* path)
{
    if (!PATINA_HOST_HAS_READ_IMAGE(host) || !host->read_image || !host->open_texture)
        return "the host does not offer read_image/open_texture (ABI 1.1 services)";
    const std::string where(path ? path : "");
    // The description, checked by the one reader of fade.toml (formats/fade_stack/fade_stack.h)
    formats::FadeDescription description;
    try {
        description = formats::read_fade_description(where);
    } catch (const std::exception& e) {
        return e.what();
    }
    const fs::path dir = fs::path(where).parent_path();
    lambda_nm_.assign(description.wavelength_nm.begin(), description.wavelength_nm.end());
    const std::vector<double>& doses = description.doses;
    rows_ = static_cast<int>(doses.size());
    columns_ = static_cast<int>(lambda_nm_.size());

    // A uniform grid (within float rounding) finds its column without a search
    const float step = columns_ > 1 ? (lambda_nm_.back() - lambda_nm_.front()) / (columns_ - 1) : 0;
    uniform_ = columns_ > 1;
    for (int i = 0; i < columns_ && uniform_; ++i)
        uniform_ = std::abs(lambda_nm_[i] - (lambda_nm_.front() + step * i)) < 1e-3f * step;
    lambda0_ = lambda_nm_.front();
    inv_step_ = uniform_ ? 1.0f / step : 0.0f;

    substrate_.assign(description.substrate.begin(), description.substrate.end());

    // The table, read and checked by the format's one reader through the host's read_image
    formats::FadeTable table;
    try {
        table = formats::read_fade_table(formats::HostPixelReader(host), description, dir);
    } catch (const std::exception& e) {
        return e.what();
    }
    r_top_ = std::move(table.r_top);
    t_ = std::move(table.t);
    r_bottom_ = std::move(table.r_bottom);
    const std::string dose_path = description.dose_map_path(dir).string();
    dose_map_ = host->open_texture(host, dose_path.c_str(), "raw");
    if (!dose_map_)
        return "cannot open the dose map '" + dose_path + "'";
    return {};
}

LayerState FadeTable::at(float row, float lambda_nm, float* rho) const
{
    // Row: clamp to the table, split into a cell and a fraction (NaN -> row 0)
    const float r = std::clamp(row >= 0.0f ? row : 0.0f, 0.0f, static_cast<float>(rows_ - 1));
    const int r0 = std::min(static_cast<int>(r), rows_ - 1);
    const int r1 = std::min(r0 + 1, rows_ - 1);
    const float fr = r - static_cast<float>(r0);

    // Column: clamp to the wavelength range
    int c0 = 0;
    float fc = 0.0f;
    if (columns_ > 1) {
        if (lambda_nm <= lambda_nm_.front()) {
            c0 = 0;
        } else if (lambda_nm >= lambda_nm_.back()) {
            c0 = columns_ - 2;
            fc = 1.0f;
        } else if (uniform_) {
            const float x = (lambda_nm - lambda0_) * inv_step_;
            c0 = std::min(static_cast<int>(x), columns_ - 2);
            fc = x - static_cast<float>(c0);
        } else {
            const auto it = std::upper_bound(lambda_nm_.begin(), lambda_nm_.end(), lambda_nm);
            c0 = static_cast<int>(it - lambda_nm_.begin()) - 1;
            fc = (lambda_nm - lambda_nm_[c0]) / (lambda_nm_[c0 + 1] - lambda_nm_[c0]);
        }
    }
    const int c1 = std::min(c0 + 1, columns_ - 1);

    auto bilinear = [&](const std::vector<float>& v) {
        const float a = v[static_cast<size_t>(r0) * columns_ + c0];
        const float b = v[static_cast<size_t>(r0) * columns_ + c1];
        const float c = v[static_cast<size_t>(r1) * columns_ + c0];
        const float d = v[static_cast<size_t>(r1) * columns_ + c1];
        const float top = a + fc * (b - a), bottom = c + fc * (d - c);
        return top + fr * (bottom - top);
    };
    if (rho)
        *rho = substrate_[c0] + fc * (substrate_[c1] - substrate_[c0]);
    return {bilinear(r_top_), bilinear(t_), bilinear(r_bottom_)};
}

float FadeTable::reflectance(float row, float lambda_nm) const
{
    float rho = 0.0f;
    const LayerState layer = at(row, lambda_nm, &rho);
    return composite(layer, rho);
}

}  // namespace patina::spectral_km
