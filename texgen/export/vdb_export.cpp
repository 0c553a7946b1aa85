#include "texgen/export/vdb_export.h"

#include "formats/toml_location.h"
#include "formats/vdb_sequence/vdb_sequence.h"

#include "core/cancel.h"
#include "core/image_io.h"
#include "core/output_transaction.h"
#include "texgen/stone_export/volume_export.h"

#include <patina/volume/stone_albedo.h>

#include <fmt/format.h>
#include <openvdb/openvdb.h>
#include <toml++/toml.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <optional>
#include <regex>
#include <stdexcept>
#include <type_traits>

namespace patina::texgen {

namespace fs = std::filesystem;

namespace {

    /// The volume.exr files of `input` with their frame numbers (cycles), in order.
    std::vector<std::pair<int, fs::path>> volumes_of(const fs::path& input)
    {
        std::error_code ec;
        std::vector<std::pair<int, fs::path>> out;
        if (fs::is_regular_file(input / "volume.exr", ec))
            return {{-1, input / "volume.exr"}};
        const std::regex step("cycle_([0-9]+)");
        for (const fs::directory_entry& e : fs::directory_iterator(input, ec)) {
            std::smatch m;
            const std::string name = e.path().filename().string();
            if (e.is_directory() && std::regex_match(name, m, step) &&
                fs::is_regular_file(e.path() / "volume.exr", ec))
                out.emplace_back(std::stoi(m[1]), e.path() / "volume.exr");
        }
        std::sort(out.begin(), out.end());
        if (out.empty())
            throw std::runtime_error(fmt::format(
                "export of '{}': no stone volume (volume.exr, or cycle_NNNN folders holding "
                "one) written by patina-texgen stone",
                input.string()));
        return out;
    }

    /// A frame's place in the sequence, for the file's metadata (none for a lone volume).
    struct FrameTag {
        int frame = -1, cycle = -1;
    };

    void write_vdb(const fs::path& path, const stone::WorldVolume& v, const VdbOptions& o,
                   const float albedo_rec709[4][3], FrameTag tag)
    {
        const double h = (v.bounds.max.x - v.bounds.min.x) / v.nx;  // cubic voxels
        // Index (i, j, k) is the voxel centred at min + (i + 1/2, j + 1/2, k + 1/2) h.
        openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(h);
        xform->postTranslate(openvdb::Vec3d(v.bounds.min.x + 0.5 * h, v.bounds.min.y + 0.5 * h,
                                            v.bounds.min.z + 0.5 * h));
        auto grid = [&](const char* name) {
            openvdb::FloatGrid::Ptr g = openvdb::FloatGrid::create(0.0f);
            g->setName(name);
            g->setTransform(xform);
            g->setGridClass(openvdb::GRID_FOG_VOLUME);
            return g;
        };
        openvdb::FloatGrid::Ptr density = grid("density"), crust = grid("crust"),
                                iron = grid("iron"), salt = grid("salt"),
                                moisture = grid("moisture"), decay = grid("decay");
        const bool fields = !v.moisture.empty() && !v.decay.empty();
        openvdb::Vec3SGrid::Ptr color = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
        color->setName("color");
        color->setTransform(xform);
        color->setGridClass(openvdb::GRID_FOG_VOLUME);
        auto d = density->getAccessor();
        auto c = crust->getAccessor();
        auto fe = iron->getAccessor();
        auto s = salt->getAccessor();
        auto a = color->getAccessor();
        auto wet = moisture->getAccessor();
        auto rot = decay->getAccessor();
        const float* gain = o.gain;  // crust, iron, salt: volume::kCrust, kIron, kSalt
        for (int k = 0; k < v.nz; ++k) {
            throw_if_cancelled();
            for (int j = 0; j < v.ny; ++j)
                for (int i = 0; i < v.nx; ++i) {
                    const size_t at = v.index(i, j, k);
                    if (!(v.density[at] > 0.0f))
                        continue;  // no stone: the grids' background
                    const openvdb::Coord ijk(i, j, k);
                    d.setValue(ijk, static_cast<float>(o.sigma_t * v.density[at]));
                    c.setValue(ijk, v.crust[at]);
                    fe.setValue(ijk, v.iron[at]);
                    s.setValue(ijk, v.salt[at]);
                    if (fields) {
                        wet.setValue(ijk, v.moisture[at]);
                        rot.setValue(ijk, v.decay[at]);
                    }
                    float q[volume::kCompositionCount], w[4];
                    q[volume::kCrust] = v.crust[at];
                    q[volume::kIron] = v.iron[at];
                    q[volume::kSalt] = v.salt[at];
                    volume::albedo_weights(q, gain, w);
                    openvdb::Vec3s rgb(0.0f);
                    for (int m = 0; m < 4; ++m)
                        rgb += openvdb::Vec3s(albedo_rec709[m][0], albedo_rec709[m][1],
                                              albedo_rec709[m][2]) * w[m];
                    a.setValue(ijk, rgb);  // each albedo is in [0, 1], so is their mix
                }
        }
        openvdb::GridPtrVec grids = {density, color, crust, iron, salt};
        if (fields) {
            grids.push_back(moisture);
            grids.push_back(decay);
        }
        // Staged in the run's output transaction (or one of its own), moved into place when
        // the whole export succeeded.
        std::optional<OutputTransaction> own;
        OutputTransaction* outputs = current_output_transaction();
        if (!outputs)
            outputs = &own.emplace();
        openvdb::io::File file(outputs->stage(path).string());
        file.setCompression(openvdb::io::COMPRESS_ZIP | openvdb::io::COMPRESS_ACTIVE_MASK);
        openvdb::MetaMap meta;
        if (tag.frame >= 0) {
            meta.insertMeta(formats::kVdbFrameMeta, openvdb::Int32Metadata(tag.frame));
            meta.insertMeta(formats::kVdbCycleMeta, openvdb::Int32Metadata(tag.cycle));
        }
        file.write(grids, meta);
        file.close();
        if (own)
            own->commit();
    }

}  // namespace

VdbOptions read_medium_options(const fs::path& scene, const std::string& name,
                               const ColorManager& colors)
{
    const toml::table root = formats::parse_toml_file(scene);
    const toml::table* medium = nullptr;
    if (const toml::array* shaders = root["shader"].as_array())
        for (const toml::node& node : *shaders) {
            const toml::table* t = node.as_table();
            if (t && (*t)["type"].value_or(std::string()) == "slab_volume" &&
                (name.empty() || (*t)["name"].value_or(std::string()) == name)) {
                medium = t;
                break;
            }
        }
    if (!medium)
        throw std::runtime_error(fmt::format(
            "--medium: {} has no slab_volume shader{}", scene.string(),
            name.empty() ? std::string() : fmt::format(" named '{}'", name)));
    auto where = [&](const toml::node& n) {
        return fmt::format("{}:{}:{}", scene.string(), n.source().begin.line,
                           n.source().begin.column);
    };
    VdbOptions o;
    auto number = [&](const char* key, auto* out) {
        if (const toml::node* n = medium->get(key)) {
            const std::optional<double> v = n->value<double>();
            if (!v || !(*v >= 0.0))
                throw std::runtime_error(fmt::format("{}: {} must be a number >= 0", where(*n), key));
            *out = static_cast<std::remove_pointer_t<decltype(out)>>(*v);
        }
    };
    number("sigma_t", &o.sigma_t);
    const char* gains[3] = {"crust_gain", "iron_gain", "salt_gain"};
    for (int g = 0; g < 3; ++g)
        number(gains[g], &o.gain[g]);
    const char* albedos[4] = {"stone_albedo", "crust_albedo", "iron_albedo", "salt_albedo"};
    for (int m = 0; m < 4; ++m) {
        const toml::node* n = medium->get(albedos[m]);
        if (!n)
            continue;
        const toml::node* rgb = n;
        std::string space = colors.working_space();
        if (const toml::table* t = n->as_table()) {
            rgb = t->get("rgb");
            space = (*t)["colorspace"].value_or(space);
            if (!rgb || !colors.has_colorspace(space))
                throw std::runtime_error(fmt::format(
                    "{}: {} as a table takes rgb = [r, g, b] and a colorspace of the OCIO "
                    "config", where(*n), albedos[m]));
        }
        float value[3];
        if (const auto grey = rgb->value<double>()) {
            value[0] = value[1] = value[2] = static_cast<float>(*grey);
        } else if (const toml::array* a = rgb->as_array(); a && a->size() == 3) {
            for (int c = 0; c < 3; ++c) {
                const std::optional<double> v = (*a)[static_cast<size_t>(c)].value<double>();
                if (!v)
                    throw std::runtime_error(fmt::format("{}: {} must hold three numbers",
                                                         where(*n), albedos[m]));
                value[c] = static_cast<float>(*v);
            }
        } else {
            throw std::runtime_error(fmt::format("{}: {} must be [r, g, b], a number or "
                                                 "{{ rgb = [...], colorspace = \"...\" }}",
                                                 where(*n), albedos[m]));
        }
        colors.convert(space, colors.working_space(), value, 1);
        std::copy(value, value + 3, o.albedo[m]);
    }
    return o;
}

std::vector<fs::path> export_stone_vdb(const fs::path& input, const fs::path& output,
                                       const VdbOptions& options, const ColorManager& colors)
{
    openvdb::initialize();
    const std::vector<std::pair<int, fs::path>> volumes = volumes_of(input);
    // The albedos a renderer reading Rec.709 can use: the medium's (working space) in
    // linear Rec.709, each channel clamped to [0, 1] (an albedo above 1 gains energy in a
    // renderer that does not clamp; the stone sample's sandstone, 0.99 0.96 0.90 in ACEScg,
    // is red 1.016 in Rec.709).
    float albedo[4][3];
    for (int m = 0; m < 4; ++m) {
        std::copy(options.albedo[m], options.albedo[m] + 3, albedo[m]);
        colors.convert(colors.working_space(), "lin_rec709", albedo[m], 1);
        for (float& c : albedo[m])
            c = std::clamp(c, 0.0f, 1.0f);
    }
    std::vector<fs::path> written;
    formats::VdbSequence sequence;
    sequence.source = input.string();
    const stone::WorldVolume* first = nullptr;
    std::optional<stone::WorldVolume> first_volume;
    for (size_t i = 0; i < volumes.size(); ++i) {
        const auto& [cycle, file] = volumes[i];
        // Frames numbered 1, 2, 3, ... (Blender and Houdini read consecutive numbers as a
        // sequence); the cycle each holds goes into its metadata and the manifest.
        const int frame = cycle < 0 ? -1 : static_cast<int>(i) + 1;
        const fs::path path =
            frame < 0 ? output : output.parent_path() / formats::vdb_frame_name(output, frame);
        stone::WorldVolume volume = stone::read_world_volume(file);
        if (first && (volume.nx != first->nx || volume.ny != first->ny ||
                      volume.nz != first->nz || volume.bounds != first->bounds))
            throw std::runtime_error(fmt::format(
                "export of '{}': the steps disagree: '{}' is {}x{}x{} voxels over [{:.6g}, "
                "{:.6g}, {:.6g}] to [{:.6g}, {:.6g}, {:.6g}] m, '{}' {}x{}x{} over [{:.6g}, "
                "{:.6g}, {:.6g}] to [{:.6g}, {:.6g}, {:.6g}] m; a sequence is one grid",
                input.string(), volumes.front().second.parent_path().filename().string(),
                first->nx, first->ny, first->nz, first->bounds.min.x, first->bounds.min.y,
                first->bounds.min.z, first->bounds.max.x, first->bounds.max.y,
                first->bounds.max.z, file.parent_path().filename().string(), volume.nx,
                volume.ny, volume.nz, volume.bounds.min.x, volume.bounds.min.y,
                volume.bounds.min.z, volume.bounds.max.x, volume.bounds.max.y,
                volume.bounds.max.z));
        write_vdb(path, volume, options, albedo, {frame, cycle});
        written.push_back(path);
        formats::VdbSequenceFrame entry{frame, cycle, path.filename().string(), {}};
        // The boundary (the eroded surface the run extracted from the same volume, in the
        // same frame and metres) beside it, for a renderer that wants the surface too.
        std::error_code ec;
        const fs::path boundary = file.parent_path() / "eroded.obj";
        if (fs::is_regular_file(boundary, ec)) {
            std::ifstream in(boundary, std::ios::binary);
            const std::string text((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
            if (!in && !in.eof())
                throw std::runtime_error(fmt::format("export: cannot read '{}'", boundary.string()));
            fs::path obj = path;
            obj.replace_extension(".obj");
            write_file_atomic(obj, {text}, "boundary mesh");
            written.push_back(obj);
            entry.boundary = obj.filename().string();
        }
        if (!first) {
            first_volume = std::move(volume);
            first = &*first_volume;
        }
        if (frame >= 0)
            sequence.frames.push_back(std::move(entry));
    }
    if (!sequence.frames.empty()) {
        const fs::path manifest = formats::vdb_sequence_path(output);
        write_file_atomic(manifest, {formats::vdb_sequence_text(sequence)}, "frame manifest");
        written.push_back(manifest);
    }
    return written;
}

}  // namespace patina::texgen
