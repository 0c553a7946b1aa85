// PixelReader over a plugin host's read_image (patina/abi.h, ABI 1.1): what a plugin's
// create reads a format's image files with. The host gives raw floats without channel
// names, so the format's documented channel order holds (formats/pixels.h). Header-only.
#pragma once

#include "formats/pixels.h"

#include <patina/abi.h>

namespace patina::formats {

class HostPixelReader final : public PixelReader {
public:
    /// `max_values`: the most floats one read may allocate (a guard against an absurd
    /// header, checked before the allocation).
    explicit HostPixelReader(const PatinaHost* host, double max_values = 1073741824.0)
        : host_(host), max_values_(max_values)
    {
    }

    Pixels read(const std::filesystem::path& file, int subimage = 0) const override
    {
        if (!PATINA_HOST_HAS_READ_IMAGE(host_) || !host_->read_image)
            throw std::runtime_error("the host does not offer read_image (ABI 1.1 services)");
        const std::string path = file.string();
        int dims[3] = {0, 0, 0};
        if (!host_->read_image(host_, path.c_str(), subimage, dims, nullptr, 0))
            throw std::runtime_error("cannot read '" + path + "'");
        const double count = static_cast<double>(dims[0]) * dims[1] * dims[2];
        if (!(dims[0] > 0 && dims[1] > 0 && dims[2] > 0) || count > max_values_)
            throw std::runtime_error("'" + path + "': part " + std::to_string(subimage) + " has " +
                                     std::to_string(dims[0]) + " x " + std::to_string(dims[1]) +
                                     " pixels of " + std::to_string(dims[2]) + " channels");
        Pixels p;
        p.width = dims[0];
        p.height = dims[1];
        p.channels = dims[2];
        p.values.resize(static_cast<size_t>(p.width) * p.height * p.channels);
        if (!host_->read_image(host_, path.c_str(), subimage, dims, p.values.data(), p.values.size()))
            throw std::runtime_error("cannot read '" + path + "'");
        return p;
    }

private:
    const PatinaHost* host_;
    double max_values_;
};

}  // namespace patina::formats
