#include "texgen/patina/stack_writer.h"

#include "formats/texture_stack/texture_stack.h"

#include "core/output_transaction.h"
#include "core/image_io.h"
#include "texgen/patina/stack_materials.h"
#include "texgen/patina/stack_preview.h"
#include "texgen/stack/manifest.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <sstream>

namespace patina::texgen {

namespace fs = std::filesystem;

namespace {

    constexpr const char* kBaker = "patina";
    /// The stack's multi-channel thickness map: one channel per layer.
    constexpr const char* kThicknessMap = "thickness";
    /// Largest side of preview.png (texels).
    constexpr int kPreviewSize = 1024;

    /// Drop the entries (and files) of an earlier patina run from the manifest, so that a
    /// stack of fewer layers does not list stale ones.
    void forget_earlier_run(const fs::path& out_dir)
    {
        for (const std::string& file : forget_maps_of(out_dir, kBaker, "patina"))
            remove_output(out_dir / file);
    }

    struct LayerStats {
        double mean = 0, max = 0, coverage = 0;
    };

    LayerStats stats_of(const std::vector<float>& t, const std::vector<float>& weight)
    {
        LayerStats s;
        double w_sum = 0;
        for (size_t i = 0; i < t.size(); ++i) {
            w_sum += weight[i];
            s.mean += weight[i] * t[i];
            s.max = std::max(s.max, static_cast<double>(t[i]));
            if (t[i] > 0.0f)
                s.coverage += weight[i];
        }
        if (w_sum > 0) {
            s.mean /= w_sum;
            s.coverage /= w_sum;
        }
        return s;
    }

    /// The stack's own table in stack.toml, after its maps were recorded; returns it.
    formats::PatinaTable record_patina_table(const fs::path& out_dir, const PatinaStep& step,
                             const PatinaDomain& domain, const PatinaOutputOptions& options,
                             const std::vector<std::string>& layer_maps,
                             const std::vector<std::string>& channels,
                             const ColorManager& colors)
    {
        const fs::path path = manifest_path(out_dir);
        toml::table root = read_manifest_for_update(path);  // as just recorded
        formats::PatinaTable patina;
        patina.script = options.script;
        patina.time_years = step.time_years;
        patina.base = step.base->name;
        if (options.preview)
            patina.preview = "preview.png";
        for (size_t l = 0; l < step.layers.size(); ++l) {
            const ResultLayer& layer = step.layers[l];
            const LayerStats s = stats_of(layer.thickness_um, domain.area_weight);
            formats::PatinaLayer entry;
            entry.material = layer.material->name;
            entry.map = kThicknessMap;
            entry.channel = channels[l];
            entry.channel_index = static_cast<int>(l);
            entry.layer_map = layer_maps[l];
            entry.made_by = layer.made_by;
            entry.mean_um = s.mean;
            entry.max_um = s.max;
            entry.coverage = s.coverage;
            patina.layers.push_back(std::move(entry));
        }
        // The optics of every material the stack uses, per wavelength, so that a renderer
        // needs nothing but this file (plugins/layered reads it).
        auto add_material = [&](const PatinaMaterial& m) {
            if (!patina.materials.count(m.name))
                patina.materials.emplace(m.name, stack_optics(m, colors));
        };
        add_material(*step.base);
        for (const ResultLayer& layer : step.layers)
            add_material(*layer.material);
        root.insert_or_assign("patina", formats::to_toml(patina));
        write_manifest(path, root);
        return patina;
    }

}  // namespace

std::string layer_map_name(size_t index, const PatinaMaterial& material)
{
    return fmt::format("layer{:02}_{}", index, formats::name_part(material.name));
}

std::string layer_channel_name(size_t index, size_t layer_count, const PatinaMaterial& material)
{
    const int width = std::max(2, static_cast<int>(std::to_string(layer_count).size()));
    return fmt::format("layer{:0{}}_{}", index, width, formats::name_part(material.name));
}

std::vector<fs::path> write_patina_step(const fs::path& out_dir, const PatinaStep& step,
                                        const PatinaDomain& domain,
                                        const PatinaOutputOptions& options,
                                        const ColorManager& colors)
{
    forget_earlier_run(out_dir);
    std::vector<fs::path> written;
    Metadata parameters = options.parameters;
    parameters.emplace_back("patina:time_years", static_cast<float>(step.time_years));

    auto write_map = [&](const std::string& name, const std::vector<std::string>& channels,
                         const std::string& description,
                         const std::vector<std::vector<float>>& tiles) {
        MapDescription map;
        map.name = name;
        map.channels = channels;
        map.units = "um";
        map.description = description;
        map.baker = kBaker;
        map.parameters = parameters;
        const auto files = write_texel_map(out_dir, map, domain.grids, tiles, options.maps);
        record_in_manifest(out_dir, map, files, domain.grids);
        written.insert(written.end(), files.begin(), files.end());
    };

    const size_t n = step.layers.size();
    std::vector<std::string> layer_maps, channels;
    for (size_t l = 0; l < n; ++l) {
        const ResultLayer& layer = step.layers[l];
        layer_maps.push_back(layer_map_name(l + 1, *layer.material));
        channels.push_back(layer_channel_name(l + 1, n, *layer.material));
        write_map(layer_maps.back(), {"thickness"},
                  fmt::format("thickness of layer {} ({}, {}) in micrometres", l + 1,
                              layer.material->name, layer.made_by),
                  domain.per_tile(layer.thickness_um));
    }
    // The same thicknesses in one map, a channel per layer, so that a renderer reads the
    // whole stack with one texture lookup (plugins/layered). OpenEXR keeps channels sorted
    // by name; the zero-padded layer numbers make that the layer order, the order of the
    // `channels` list in stack.toml.
    if (n > 0) {
        std::vector<std::vector<float>> tiles;
        for (size_t l = 0; l < n; ++l) {
            const std::vector<std::vector<float>> layer_tiles =
                domain.per_tile(step.layers[l].thickness_um);
            tiles.resize(layer_tiles.size());
            for (size_t t = 0; t < layer_tiles.size(); ++t) {
                tiles[t].resize(layer_tiles[t].size() * n);
                for (size_t g = 0; g < layer_tiles[t].size(); ++g)
                    tiles[t][g * n + l] = layer_tiles[t][g];
            }
        }
        write_map(kThicknessMap, channels,
                  "thickness of every layer in micrometres, one channel per layer, bottom to "
                  "top (the layers' maps in one file)",
                  tiles);
    }
    write_map("total_thickness", {"thickness"},
              "total thickness of the layers over the base in micrometres (for displacement or "
              "bump, D&H 1996 §4.3)",
              domain.per_tile(step.total_um));
    const formats::PatinaTable patina =
        record_patina_table(out_dir, step, domain, options, layer_maps, channels, colors);
    written.push_back(manifest_path(out_dir));

    if (options.preview) {
        // The preview shows the first tile as an image, every `stride`-th texel so that it
        // stays at most kPreviewSize wide (a quick look, not a map): each texel's KM colour.
        const TexelGrid& grid = domain.grids.front();
        const int stride = (std::max(grid.width, grid.height) + kPreviewSize - 1) / kPreviewSize;
        const int w = (grid.width + stride - 1) / stride, h = (grid.height + stride - 1) / stride;
        std::vector<int32_t> node_of_pixel(static_cast<size_t>(w) * h, -1);
        std::vector<size_t> nodes;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                if (const int32_t g = grid.group_of_texel[static_cast<size_t>(y) * stride *
                                                              grid.width + x * stride];
                    g >= 0) {
                    node_of_pixel[static_cast<size_t>(y) * w + x] =
                        static_cast<int32_t>(nodes.size());
                    nodes.push_back(static_cast<size_t>(g));
                }
        // The optics just recorded: the preview is what flatten makes of this stack.
        std::vector<std::vector<float>> thickness(step.layers.size());
        for (size_t l = 0; l < step.layers.size(); ++l)
            for (size_t n : nodes)
                thickness[l].push_back(step.layers[l].thickness_um[n]);
        const std::vector<Imath::V3f> node_colors =
            stack_diffuse_color(band_stack(patina, manifest_path(out_dir)), thickness,
                                nodes.size(), BandsToRgb(colors));
        std::vector<Imath::V3f> image(node_of_pixel.size());
        std::vector<uint8_t> covered(node_of_pixel.size(), 0);
        for (size_t p = 0; p < node_of_pixel.size(); ++p) {
            if (const int32_t k = node_of_pixel[p]; k >= 0) {
                image[p] = node_colors[k];
                covered[p] = 1;
            }
        }
        const fs::path png = out_dir / "preview.png";
        write_preview_png(png, image, w, h, covered, colors);
        written.push_back(png);
    }
    return written;
}

}  // namespace patina::texgen
