#include "formats/render_part/render_part.h"

#include <stdexcept>
#include <type_traits>

namespace patina::formats {

Header render_header_attributes(const RenderHeader& h)
{
    Header out{{"patina:scene", h.scene},
            {"patina:spp", h.spp},
            {"patina:sample_begin", h.sample_begin},
            {"patina:sample_end", h.sample_end},
            {"patina:scene_hash", h.scene_hash},
            {"patina:plugins", h.plugins},
            {"patina:sums_layout", h.sums_layout},
            {"patina:seed", h.seed},
            {"patina:wavelengths", h.wavelengths},
            {"patina:max_depth", h.max_depth},
            {"oiio:ColorSpace", h.colorspace},
            {"patina:colorspace", h.colorspace}};
    if (!h.display.empty()) {
        out.emplace_back("patina:display", h.display);
        out.emplace_back("patina:view", h.view);
    }
    if (h.merged_parts > 0)
        out.emplace_back("patina:merged_parts", h.merged_parts);
    return out;
}

namespace {

    const HeaderValue* find(const Header& attributes, const std::string& key)
    {
        for (const auto& [k, v] : attributes)
            if (k == key)
                return &v;
        return nullptr;
    }

    template <class T>
    void take(const Header& attributes, const std::string& key, bool required, T* out)
    {
        const HeaderValue* v = find(attributes, key);
        if (!v) {
            if (required)
                throw std::runtime_error("no " + key + " in its header");
            return;
        }
        const T* typed = std::get_if<T>(v);
        if (!typed)
            throw std::runtime_error(key + (std::is_same_v<T, int> ? " is not an integer"
                                                                     : " is not a string"));
        *out = *typed;
    }

}  // namespace

RenderHeader read_render_header(const Header& attributes)
{
    RenderHeader h;
    take(attributes, "patina:scene_hash", true, &h.scene_hash);
    take(attributes, "patina:seed", true, &h.seed);
    take(attributes, "patina:sample_begin", true, &h.sample_begin);
    take(attributes, "patina:sample_end", true, &h.sample_end);
    take(attributes, "patina:scene", false, &h.scene);
    take(attributes, "patina:spp", false, &h.spp);
    take(attributes, "patina:plugins", false, &h.plugins);
    take(attributes, "patina:sums_layout", false, &h.sums_layout);
    take(attributes, "patina:wavelengths", false, &h.wavelengths);
    take(attributes, "patina:max_depth", false, &h.max_depth);
    take(attributes, "patina:colorspace", false, &h.colorspace);
    take(attributes, "patina:merged_parts", false, &h.merged_parts);
    take(attributes, "patina:display", false, &h.display);
    take(attributes, "patina:view", false, &h.view);
    if (h.sample_end <= h.sample_begin || h.sample_begin < 0)
        throw std::runtime_error("sample range " + std::to_string(h.sample_begin) + "-" +
                                 std::to_string(h.sample_end) + " is empty");
    return h;
}

}  // namespace patina::formats
