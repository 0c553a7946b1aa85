// A glTF 2.0 asset being built (Khronos glTF 2.0 specification): one binary buffer, its
// buffer views and accessors, images, textures, materials, meshes and one scene, written
// as a binary .glb (§4.4 "GLB File Format Specification") or as a .gltf with its .bin and
// image files beside it. The JSON is nlohmann::json; what goes into it is the caller's.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace patina::texgen::gltf {

// Enumerations of the specification (§5 "Properties Reference").
inline constexpr int kFloat = 5126, kUnsignedInt = 5125;
inline constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;
inline constexpr int kLinear = 9729, kLinearMipmapLinear = 9987;
inline constexpr int kClampToEdge = 33071, kRepeat = 10497;

class Document {
public:
    Document();

    /// The JSON being built (asset, scenes, nodes, meshes, materials, ... arrays).
    nlohmann::json& root() { return json_; }

    /// Appends `bytes` to the binary buffer (aligned to 4) as a new buffer view; `target` is
    /// kArrayBuffer, kElementArrayBuffer or 0 (images). Returns its index.
    int add_view(const void* data, size_t bytes, int target);
    /// An accessor over a whole view: `count` elements of `type` ("VEC3", "SCALAR", ...)
    /// of `component` (kFloat, kUnsignedInt); min and max are written when given.
    int add_accessor(int view, int component, size_t count, const char* type,
                     const std::vector<float>& min = {}, const std::vector<float>& max = {});
    /// A PNG image: its bytes go into the buffer (.glb) or into `file_name` beside the
    /// .gltf. Returns the image index.
    int add_png(const std::string& name, const std::string& file_name,
                std::vector<unsigned char> png);
    /// A texture of `image` with `sampler`.
    int add_texture(int image, int sampler);
    /// A sampler (linear, mipmapped) with the given wrap mode on both axes.
    int add_sampler(int wrap);
    /// Appends `value` to the top-level array `key`; returns its index.
    int add(const char* key, nlohmann::json value);
    /// Records an extension in extensionsUsed (once).
    void use_extension(const std::string& name);

    /// The whole asset as the bytes of one .glb.
    std::string glb() const;
    /// The whole asset as one .glb, written under a temporary name and renamed.
    void write_glb(const std::filesystem::path& path) const;
    /// The asset as `path` (.gltf), `<stem>.bin` and its images beside it, each written
    /// under a temporary name and renamed. Returns the files written.
    std::vector<std::filesystem::path> write_gltf(const std::filesystem::path& path) const;

private:
    struct Png {
        std::string name, file_name;
        std::vector<unsigned char> bytes;
    };
    nlohmann::json json_;
    std::vector<unsigned char> bin_;  // vertex and index data
    std::vector<Png> pngs_;           // placed when written: in the .glb's buffer or beside

    /// The JSON and the buffer of the file: the images appended to the buffer (`glb`) or
    /// named by their files.
    nlohmann::json finished(bool glb, std::vector<unsigned char>* bin) const;
};

}  // namespace patina::texgen::gltf
