#include "stack_file.h"

#include "formats/texture_stack/texture_stack.h"

#include <stdexcept>
#include <string>

namespace patina::layered {

namespace fs = std::filesystem;

namespace {

    std::vector<float> floats(const std::vector<double>& v)
    {
        return std::vector<float>(v.begin(), v.end());
    }

    MaterialOptics optics_of(const formats::MaterialOptics& m)
    {
        MaterialOptics o;
        o.name = m.name;
        o.metal = m.metal;
        o.lambda_nm = floats(m.lambda_nm);
        o.absorption_per_um = floats(m.absorption_per_um);
        o.scattering_per_um = floats(m.scattering_per_um);
        o.specular = floats(m.specular);
        o.n = floats(m.n);
        o.k = floats(m.k);
        o.roughness = static_cast<float>(m.roughness);
        return o;
    }

}  // namespace

StackFile read_stack_file(const fs::path& path)
{
    const formats::TextureStack file = formats::read_texture_stack(path);
    const formats::PatinaTable& patina = formats::patina_of(file);
    StackFile stack;
    stack.path = path;
    stack.base = patina.base;
    for (const auto& [name, optics] : patina.materials)
        stack.materials.emplace(name, optics_of(optics));
    for (const formats::PatinaLayer& l : patina.layers) {
        const formats::StackMap& map = file.map(l.map);
        // A UDIM map is read through its pattern: the host's lookups pick the tile by uv.
        const fs::path map_file = map.pattern.empty() ? map.files(file.folder()).front()
                                                      : file.folder() / map.pattern;
        stack.layers.push_back({l.material, map_file, l.channel_index});
    }
    return stack;
}

}  // namespace patina::layered
