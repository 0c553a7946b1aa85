#include "texgen/export/gltf_document.h"

#include "core/image_io.h"

#include <cstring>
#include <stdexcept>

namespace patina::texgen::gltf {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

    void pad_to_4(std::vector<unsigned char>& bytes, unsigned char fill)
    {
        while (bytes.size() % 4)
            bytes.push_back(fill);
    }

    void put_u32(std::string& out, uint32_t v)
    {
        for (int i = 0; i < 4; ++i)
            out.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
    }

}  // namespace

Document::Document()
{
    json_ = {{"asset", {{"version", "2.0"}, {"generator", "patina-texgen export"}}},
             {"scene", 0}};
}

int Document::add(const char* key, json value)
{
    json& array = json_[key];
    if (array.is_null())
        array = json::array();
    array.push_back(std::move(value));
    return static_cast<int>(array.size()) - 1;
}

void Document::use_extension(const std::string& name)
{
    json& used = json_["extensionsUsed"];
    if (used.is_null())
        used = json::array();
    for (const json& e : used)
        if (e == name)
            return;
    used.push_back(name);
}

int Document::add_view(const void* data, size_t bytes, int target)
{
    pad_to_4(bin_, 0);
    json view = {{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", bytes}};
    if (target)
        view["target"] = target;
    const auto* p = static_cast<const unsigned char*>(data);
    bin_.insert(bin_.end(), p, p + bytes);
    return add("bufferViews", std::move(view));
}

int Document::add_accessor(int view, int component, size_t count, const char* type,
                           const std::vector<float>& min, const std::vector<float>& max)
{
    json a = {{"bufferView", view}, {"componentType", component}, {"count", count},
              {"type", type}};
    if (!min.empty())
        a["min"] = min;
    if (!max.empty())
        a["max"] = max;
    return add("accessors", std::move(a));
}

int Document::add_png(const std::string& name, const std::string& file_name,
                      std::vector<unsigned char> png)
{
    pngs_.push_back({name, file_name, std::move(png)});
    return static_cast<int>(pngs_.size()) - 1;
}

int Document::add_texture(int image, int sampler)
{
    return add("textures", {{"source", image}, {"sampler", sampler}});
}

int Document::add_sampler(int wrap)
{
    return add("samplers", {{"magFilter", kLinear},
                            {"minFilter", kLinearMipmapLinear},
                            {"wrapS", wrap},
                            {"wrapT", wrap}});
}

json Document::finished(bool glb, std::vector<unsigned char>* bin) const
{
    json out = json_;
    *bin = bin_;
    json images = json::array();
    for (const Png& png : pngs_) {
        if (glb) {
            pad_to_4(*bin, 0);
            json view = {{"buffer", 0}, {"byteOffset", bin->size()},
                         {"byteLength", png.bytes.size()}};
            bin->insert(bin->end(), png.bytes.begin(), png.bytes.end());
            json& views = out["bufferViews"];
            if (views.is_null())
                views = json::array();
            views.push_back(std::move(view));
            images.push_back({{"name", png.name},
                              {"mimeType", "image/png"},
                              {"bufferView", views.size() - 1}});
        } else {
            images.push_back({{"name", png.name}, {"uri", png.file_name}});
        }
    }
    if (!images.empty())
        out["images"] = std::move(images);
    if (!bin->empty())
        out["buffers"] = json::array({{{"byteLength", bin->size()}}});
    return out;
}

std::string Document::glb() const
{
    std::vector<unsigned char> bin;
    const json doc = finished(true, &bin);
    std::string text = doc.dump();
    while (text.size() % 4)
        text.push_back(' ');  // the JSON chunk is padded with spaces (§4.4.3.1)
    pad_to_4(bin, 0);         // the BIN chunk with zeros (§4.4.3.2)
    const uint32_t length = 12 + 8 + static_cast<uint32_t>(text.size()) +
                            (bin.empty() ? 0 : 8 + static_cast<uint32_t>(bin.size()));
    std::string header;
    put_u32(header, 0x46546C67);  // "glTF"
    put_u32(header, 2);
    put_u32(header, length);
    put_u32(header, static_cast<uint32_t>(text.size()));
    put_u32(header, 0x4E4F534A);  // "JSON"
    std::string bin_header;
    if (!bin.empty()) {
        put_u32(bin_header, static_cast<uint32_t>(bin.size()));
        put_u32(bin_header, 0x004E4942);  // "BIN\0"
    }
    const std::string_view bytes(reinterpret_cast<const char*>(bin.data()), bin.size());
    std::string glb;
    glb.reserve(header.size() + text.size() + bin_header.size() + bytes.size());
    glb.append(header).append(text).append(bin_header).append(bytes);
    return glb;
}

void Document::write_glb(const fs::path& path) const
{
    write_file_atomic(path, {glb()}, "glTF binary");
}

std::vector<fs::path> Document::write_gltf(const fs::path& path) const
{
    std::vector<unsigned char> bin;
    json doc = finished(false, &bin);
    std::vector<fs::path> written;
    const fs::path dir = path.parent_path();
    if (!bin.empty()) {
        const std::string bin_name = path.stem().string() + ".bin";
        doc["buffers"][0]["uri"] = bin_name;
        write_file_atomic(dir / bin_name,
                          {std::string_view(reinterpret_cast<const char*>(bin.data()), bin.size())},
                          "glTF buffer");
        written.push_back(dir / bin_name);
    }
    for (const Png& png : pngs_) {
        write_file_atomic(dir / png.file_name,
                          {std::string_view(reinterpret_cast<const char*>(png.bytes.data()),
                                            png.bytes.size())},
                          "texture");
        written.push_back(dir / png.file_name);
    }
    write_file_atomic(path, {doc.dump(2), "\n"}, "glTF");
    written.push_back(path);
    return written;
}

}  // namespace patina::texgen::gltf
