#include "texgen/flatten/patina_stack_files.h"

#include "texgen/meshes/mesh_input.h"

#include <fmt/format.h>

#include <sstream>
#include <stdexcept>

namespace patina::texgen {

namespace fs = std::filesystem;

PatinaStackFiles read_patina_stack(const fs::path& stack)
{
    // The one reader of stack.toml (formats/texture_stack/texture_stack.h) checks the format, the layers,
    // their maps and channels, the optics and that the layers' files exist.
    const formats::TextureStack file = formats::read_texture_stack(stack);
    const formats::PatinaTable& patina = formats::patina_of(file);

    PatinaStackFiles out;
    out.manifest = file.manifest;
    out.base = patina.base;
    out.time_years = patina.time_years;
    out.materials = patina.materials;
    auto take_size = [&](const formats::StackMap& map) {
        out.width = map.width;
        out.height = map.height;
        if (const auto s = map.parameters["strip_size_m"].value<double>())
            out.strip_size_m = *s;
        if (const auto d = map.parameters["domain"].value<std::string>())
            out.domain = *d;
        if (const auto m = map.parameters["mesh"].value<std::string>())
            out.mesh = (file.folder() / fs::path(*m)).lexically_normal();
        if (const MeshConventionOptions c = recorded_convention(map.parameters); !c.empty())
            out.mesh_convention = c;
        out.uv_wrap = out.uv_wrap || recorded_uv_wrap(map.parameters);
        if (const auto names = map.parameters["keep_off"].value<std::string>(); names && out.keep_off.empty()) {
            std::stringstream list(*names);
            for (std::string name; std::getline(list, name, ',');)
                if (!name.empty())
                    out.keep_off.push_back(name);
        }
    };
    for (const formats::PatinaLayer& layer : patina.layers) {
        const formats::StackMap& map = file.map(layer.map);
        out.layers.push_back({layer.material, layer.map, map.files(file.folder()), layer.channel});
        take_size(map);
    }
    if (!out.layers.empty())
        out.udims = file.map(patina.layers.front().map).udims();

    // A stack without layers (bare base) still has its total thickness map: its tiles.
    const auto total = file.maps.find(patina.total_thickness);
    if (total == file.maps.end())
        throw std::runtime_error(fmt::format("{}: map '{}' (the total thickness) is not listed "
                                             "in [maps]",
                                             file.manifest.string(), patina.total_thickness));
    for (const fs::path& f : total->second.files(file.folder()))
        if (std::error_code ec; !fs::is_regular_file(f, ec))
            throw std::runtime_error(fmt::format("{}: map '{}': file '{}' does not exist",
                                                 file.manifest.string(), total->first,
                                                 f.string()));
    take_size(total->second);
    if (out.layers.empty())
        out.udims = total->second.udims();
    else if (total->second.udims() != out.udims)
        throw std::runtime_error(fmt::format("{}: map '{}' is on other UDIM tiles than the "
                                             "layers",
                                             file.manifest.string(), total->first));
    return out;
}

}  // namespace patina::texgen
