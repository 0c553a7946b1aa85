#include "farm/frame_merge.h"

#include "core/color_management.h"

#include "core/image_io.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <stdexcept>

namespace patina::farm {

namespace fs = std::filesystem;

namespace {

    /// The first part's value and another part's, when they differ.
    void require_same(const RenderPart& a, const RenderPart& b, const char* what,
                      const std::string& va, const std::string& vb)
    {
        if (va != vb)
            throw std::runtime_error(fmt::format(
                "merge: part '{}' has {} {}, part '{}' has {}: they are not parts of one "
                "render", b.file.string(), what, vb, a.file.string(), va));
    }

}  // namespace

MergeResult merge_render_parts(const std::vector<fs::path>& files, const fs::path& output)
{
    if (files.empty())
        throw std::runtime_error("merge: no parts");
    std::vector<RenderPart> parts;
    parts.reserve(files.size());
    for (const fs::path& f : files)
        parts.push_back(read_render_part(f));
    const RenderPart& first = parts.front();
    for (const RenderPart& p : parts) {
        require_same(first, p, "scene hash", first.header.scene_hash, p.header.scene_hash);
        require_same(first, p, "seed", std::to_string(first.header.seed), std::to_string(p.header.seed));
        require_same(first, p, "plugins", "'" + first.header.plugins + "'", "'" + p.header.plugins + "'");
        require_same(first, p, "frame size",
                     fmt::format("{}x{}", first.full_width, first.full_height),
                     fmt::format("{}x{}", p.full_width, p.full_height));
        require_same(first, p, "channels", fmt::format("{}", fmt::join(first.channels, ",")),
                     fmt::format("{}", fmt::join(p.channels, ",")));
    }

    // Sample ranges, in order: each must start where the one before ends.
    std::map<std::pair<int, int>, std::vector<size_t>> ranges;
    for (size_t i = 0; i < parts.size(); ++i)
        ranges[{parts[i].header.sample_begin, parts[i].header.sample_end}].push_back(i);
    const RenderPart* previous = nullptr;
    for (const auto& [range, members] : ranges) {
        const RenderPart& p = parts[members.front()];
        if (previous && range.first != previous->header.sample_end)
            throw std::runtime_error(
                range.first > previous->header.sample_end
                    ? fmt::format("merge: samples {}-{} are in no part: '{}' ends at {}, '{}' "
                                  "starts at {}",
                                  previous->header.sample_end, range.first, previous->file.string(),
                                  previous->header.sample_end, p.file.string(), range.first)
                    : fmt::format("merge: '{}' (samples {}-{}) and '{}' (samples {}-{}) "
                                  "overlap",
                                  previous->file.string(), previous->header.sample_begin,
                                  previous->header.sample_end, p.file.string(), range.first,
                                  range.second));
        previous = &p;
    }

    // The pixels of each sample range: disjoint parts, and the same pixels in every range.
    const int fw = first.full_width, fh = first.full_height;
    const size_t frame = static_cast<size_t>(fw) * fh;
    std::vector<int> reference;  // the first range's owner of each frame pixel, or -1
    for (const auto& [range, members] : ranges) {
        std::vector<int> owner(frame, -1);
        for (size_t i : members) {
            const RenderPart& p = parts[i];
            if (p.x < 0 || p.y < 0 || p.x + p.width > fw || p.y + p.height > fh)
                throw std::runtime_error(fmt::format("merge: part '{}' lies outside its {}x{} "
                                                     "frame", p.file.string(), fw, fh));
            for (int y = p.y; y < p.y + p.height; ++y)
                for (int x = p.x; x < p.x + p.width; ++x) {
                    int& o = owner[static_cast<size_t>(y) * fw + x];
                    if (o >= 0)
                        throw std::runtime_error(fmt::format(
                            "merge: '{}' and '{}' both hold pixel ({}, {}) of samples {}-{}",
                            parts[static_cast<size_t>(o)].file.string(), p.file.string(), x,
                            y, range.first, range.second));
                    o = static_cast<int>(i);
                }
        }
        if (reference.empty()) {
            reference = std::move(owner);
            continue;
        }
        for (size_t px = 0; px < frame; ++px)
            if ((reference[px] < 0) != (owner[px] < 0)) {
                const size_t has = reference[px] >= 0 ? static_cast<size_t>(reference[px])
                                                      : static_cast<size_t>(owner[px]);
                throw std::runtime_error(fmt::format(
                    "merge: pixel ({}, {}) is in '{}' but in no part of samples {}-{}",
                    px % fw, px / fw, parts[has].file.string(),
                    reference[px] >= 0 ? range.first : ranges.begin()->first.first,
                    reference[px] >= 0 ? range.second : ranges.begin()->first.second));
            }
    }
    // The merged pixels: the bounding box of the parts, with no hole.
    int x0 = fw, y0 = fh, x1 = 0, y1 = 0;
    for (size_t px = 0; px < frame; ++px)
        if (reference[px] >= 0) {
            const int x = static_cast<int>(px % fw), y = static_cast<int>(px / fw);
            x0 = std::min(x0, x);
            y0 = std::min(y0, y);
            x1 = std::max(x1, x + 1);
            y1 = std::max(y1, y + 1);
        }
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x)
            if (reference[static_cast<size_t>(y) * fw + x] < 0)
                throw std::runtime_error(fmt::format(
                    "merge: pixel ({}, {}) is in no part, inside the merged window [{}, {}) x "
                    "[{}, {})", x, y, x0, x1, y0, y1));

    const int w = x1 - x0, h = y1 - y0;
    const size_t nc = first.channels.size();
    const int total = previous->header.sample_end - ranges.begin()->first.first;
    std::vector<float> pixels(static_cast<size_t>(w) * h * nc);
    // Per pixel, the weighted mean over the sample ranges (one range: its values as they
    // are, so that tiles merge bitwise).
    std::vector<double> sum(nc);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            std::fill(sum.begin(), sum.end(), 0.0);
            float* out = &pixels[(static_cast<size_t>(y - y0) * w + (x - x0)) * nc];
            for (const auto& [range, members] : ranges) {
                for (size_t i : members) {
                    const RenderPart& p = parts[i];
                    if (x < p.x || x >= p.x + p.width || y < p.y || y >= p.y + p.height)
                        continue;
                    const float* in =
                        &p.pixels[(static_cast<size_t>(y - p.y) * p.width + (x - p.x)) * nc];
                    if (ranges.size() == 1)
                        std::copy(in, in + nc, out);
                    else
                        for (size_t c = 0; c < nc; ++c)
                            sum[c] += static_cast<double>(p.samples()) * in[c];
                    break;
                }
            }
            if (ranges.size() > 1)
                for (size_t c = 0; c < nc; ++c)
                    out[c] = static_cast<float>(sum[c] / total);
        }

    // The first part's header with the merged sample range (formats/render_part/render_part.h), then
    // any other patina:* attribute of the first part.
    formats::RenderHeader header = first.header;
    header.spp = total;
    header.sample_begin = ranges.begin()->first.first;
    header.sample_end = previous->header.sample_end;
    header.merged_parts = static_cast<int>(parts.size());
    Metadata meta = formats::render_header_attributes(header);
    for (const auto& [key, value] : first.attributes)
        if (std::none_of(meta.begin(), meta.end(), [&](const auto& m) { return m.first == key; }))
            meta.emplace_back(key, value);
    const ImageWindow window{x0, y0, fw, fh};
    // The display image the parts have (<stem>.png through the same OCIO display and view),
    // computed before anything is written.
    std::vector<float> display;
    if (!header.display.empty()) {
        const auto channel = [&](const char* name) {
            const auto it = std::find(first.channels.begin(), first.channels.end(), name);
            if (it == first.channels.end())
                throw std::runtime_error(fmt::format("merge: '{}' has no channel {} for its "
                                                     "display image", files.front().string(), name));
            return static_cast<size_t>(it - first.channels.begin());
        };
        const size_t r = channel("R"), g = channel("G"), b = channel("B");
        const size_t n = static_cast<size_t>(w) * h;
        display.resize(3 * n);
        for (size_t i = 0; i < n; ++i) {
            display[3 * i] = pixels[i * nc + r];
            display[3 * i + 1] = pixels[i * nc + g];
            display[3 * i + 2] = pixels[i * nc + b];
        }
        const ColorManager colors(ColorManager::default_config_path());
        colors.convert_display(header.colorspace.empty() ? colors.working_space() : header.colorspace,
                               header.display, header.view, display.data(), n);
    }
    write_image_atomic(output, pixels.data(), w, h, static_cast<int>(nc), first.channels,
                       first.format == OIIO::TypeDesc::HALF ? OIIO::TypeDesc::HALF
                                                            : OIIO::TypeDesc::FLOAT,
                       meta, &window);
    if (!display.empty())
        write_image_atomic(fs::path(output).replace_extension(".png"), display.data(), w, h, 3,
                           {}, OIIO::TypeDesc::UINT8);
    return {parts.size(), ranges.begin()->first.first, previous->header.sample_end, x0, y0, w, h};
}

}  // namespace patina::farm
