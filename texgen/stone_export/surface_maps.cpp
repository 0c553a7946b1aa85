#include "texgen/stone_export/surface_maps.h"

#include "texgen/stone_export/volume_export.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string_view>

namespace patina::texgen::stone {

using Imath::V3d;
using Imath::V3f;

SurfaceReader::SurfaceReader(const StoneState& st) : st_(st)
{
    const SlabLattice& lat = *st.lattice;
    density_ = st.density;
    lat.fill_halo(density_.data());
    for (int a = 0; a < 3; ++a) {
        colour_[a].resize(st.colour.size());
        for (size_t c = 0; c < st.colour.size(); ++c)
            colour_[a][c] = st.colour[c][a];
        lat.fill_halo(colour_[a].data());
    }
    output_fractions(st, crust_, iron_, salt_);
    // March in steps of a third of the mean depth step, as deep as the shell goes.
    double depth = 0.0;
    for (double d : lat.shell().depths)
        depth = std::max(depth, d);
    const double n_d = lat.grid().n_d;
    reach_ = depth;
    step_ = depth / (3.0 * n_d);
}

SurfaceAppearance SurfaceReader::at(const V3f& Pf, const V3f& Nf) const
{
    const SlabLattice& lat = *st_.lattice;
    const V3d P(Pf.x, Pf.y, Pf.z);
    V3d N(Nf.x, Nf.y, Nf.z);
    N = N.length() > 0 ? N.normalized() : V3d(0, 1, 0);
    SurfaceAppearance a;
    std::optional<SlabPoint> last;
    for (double t = -step_; t <= reach_; t += step_) {
        const auto at = lat.locator().locate(P - t * N, 1e-6);
        if (!at)
            continue;
        last = at;
        if (lat.sample(density_.data(), *at) >= 0.5f) {
            a.erosion = float(std::max(0.0, t));
            break;
        }
        a.erosion = float(std::max(0.0, t));
    }
    if (!last)
        return a;
    // Read one half step outside the stone too: crusts sit on the surface voxels.
    a.crust = std::clamp(lat.sample(crust_.data(), *last), 0.0f, 1.0f);
    a.iron = std::clamp(lat.sample(iron_.data(), *last), 0.0f, 1.0f);
    a.salt = std::clamp(lat.sample(salt_.data(), *last), 0.0f, 1.0f);
    V3f c(lat.sample(colour_[0].data(), *last), lat.sample(colour_[1].data(), *last),
          lat.sample(colour_[2].data(), *last));
    // Iron oxide (goethite-like yellow-brown), efflorescence (white), black crust.
    const V3f rust(0.50f, 0.30f, 0.10f), white(0.85f, 0.85f, 0.83f), black(0.035f, 0.03f, 0.028f);
    c = c + (rust - c) * (0.75f * a.iron);
    c = c + (white - c) * (0.8f * a.salt);
    c = c + (black - c) * (0.9f * a.crust);
    a.colour = c;
    return a;
}

std::vector<std::filesystem::path> write_surface_maps(const std::filesystem::path& out_dir,
                                                      const StoneState& st,
                                                      const TriangleMesh& mesh, int resolution,
                                                      const Metadata& parameters)
{
    RasterOptions raster;
    raster.width = raster.height = resolution;
    raster.supersampling = 2;
    const std::vector<TexelGrid> tiles = rasterize_uv(mesh, raster);
    const SurfaceReader reader(st);
    std::vector<std::vector<float>> colour(tiles.size()), crust(tiles.size());
    for (size_t t = 0; t < tiles.size(); ++t) {
        const SampleGroups& groups = tiles[t].groups;
        const size_t n = groups.group_count();
        colour[t].assign(n * 3, 0.0f);
        crust[t].assign(n * 4, 0.0f);
        tbb::parallel_for(size_t(0), n, [&](size_t gi) {
            const size_t count = groups.group_size(gi);
            for (uint32_t s = groups.offsets[gi]; s < groups.offsets[gi + 1]; ++s) {
                const SurfaceSample& sample = groups.samples[s];
                const SurfaceAppearance a = reader.at(sample.P, sample.N);
                const float w = 1.0f / float(count);
                for (int k = 0; k < 3; ++k)
                    colour[t][gi * 3 + k] += w * a.colour[k];
                crust[t][gi * 4 + 0] += w * a.crust;
                crust[t][gi * 4 + 1] += w * a.iron;
                crust[t][gi * 4 + 2] += w * a.salt;
                crust[t][gi * 4 + 3] += w * a.erosion;
            }
        });
    }
    MapOutputOptions out;
    std::vector<std::filesystem::path> files;
    MapDescription cmap;
    cmap.name = "stone_colour";
    cmap.channels = {"R", "G", "B"};
    cmap.units = "1";
    cmap.description = "linear albedo of the weathered stone surface (fresh stone tinted by "
                       "iron oxide, whitened by salt, darkened by black crust)";
    cmap.baker = "stone";
    // The map writer prefixes parameters itself and records the baker: plain keys here.
    for (const auto& [key, value] : parameters) {
        std::string_view plain = key;
        if (plain.rfind("patina:", 0) == 0)
            plain.remove_prefix(7);
        if (plain != "baker")
            cmap.parameters.emplace_back(std::string(plain), value);
    }
    auto f1 = write_texel_map(out_dir, cmap, tiles, colour, out);
    record_in_manifest(out_dir, cmap, f1, tiles);
    MapDescription smap = cmap;
    smap.name = "stone_crust";
    smap.channels = {"crust", "iron", "salt", "erosion"};
    smap.units = "1 (erosion: m)";
    smap.description = "black crust, iron oxide and salt fractions in [0, 1] at the eroded "
                       "surface; erosion: depth of the eroded surface below the original (m)";
    auto f2 = write_texel_map(out_dir, smap, tiles, crust, out);
    record_in_manifest(out_dir, smap, f2, tiles);
    files.insert(files.end(), f1.begin(), f1.end());
    files.insert(files.end(), f2.begin(), f2.end());
    return files;
}

} // namespace patina::texgen::stone
