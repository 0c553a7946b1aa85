#include "core/mesh.h"

#include "core/image_io.h"

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string_view>

namespace patina {

namespace {

    bool finite(const Imath::V3f& v)
    {
        return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
    }

    /// Assimp matrices act on column vectors; Imath's on row vectors: transpose.
    Imath::M44f to_imath(const aiMatrix4x4& m)
    {
        return Imath::M44f(m.a1, m.b1, m.c1, m.d1, m.a2, m.b2, m.c2, m.d2, m.a3, m.b3, m.c3,
                           m.d3, m.a4, m.b4, m.c4, m.d4);
    }

    float determinant3(const Imath::M44f& m)
    {
        return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
               m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    }

    /// An image Assimp holds in memory: compressed (mHeight 0: mWidth bytes of a file whose
    /// extension is achFormatHint) or mWidth x mHeight BGRA texels (assimp/texture.h).
    MaterialTexture embedded_texture(const aiTexture& image, const std::string& name)
    {
        MaterialTexture texture;
        texture.name = image.mFilename.length > 0
                           ? std::filesystem::path(image.mFilename.C_Str()).filename().string()
                           : name;
        if (image.mHeight == 0) {
            const auto* bytes = reinterpret_cast<const unsigned char*>(image.pcData);
            texture.encoded =
                std::make_shared<const std::vector<unsigned char>>(bytes, bytes + image.mWidth);
            texture.format = image.achFormatHint;
            return texture;
        }
        auto texels = std::make_shared<ImageData>();
        texels->width = static_cast<int>(image.mWidth);
        texels->height = static_cast<int>(image.mHeight);
        texels->channels = 4;
        texels->channel_names = {"R", "G", "B", "A"};
        texels->pixels.resize(static_cast<size_t>(image.mWidth) * image.mHeight * 4);
        for (size_t i = 0; i < static_cast<size_t>(image.mWidth) * image.mHeight; ++i) {
            const aiTexel& t = image.pcData[i];
            const float rgba[4] = {t.r / 255.0f, t.g / 255.0f, t.b / 255.0f, t.a / 255.0f};
            std::copy(rgba, rgba + 4, texels->pixels.begin() + static_cast<std::ptrdiff_t>(4 * i));
        }
        texture.texels = std::move(texels);
        return texture;
    }

    struct Loader {
        const std::filesystem::path& path;
        const aiScene& scene;
        int uv_set = 0;
        std::vector<TriangleMesh> meshes;

        std::string where() const { return fmt::format("mesh file '{}'", path.string()); }

        /// Embedded images already copied, by their index in the scene: a texture shared by
        /// many meshes is held once.
        std::vector<MaterialTexture> embedded = std::vector<MaterialTexture>(scene.mNumTextures);

        /// A material's texture `name`: an image embedded in the file (Assimp names those
        /// "*N", or by the file name an FBX stored them under), or a file beside the mesh.
        /// Empty when neither exists.
        MaterialTexture base_colour_texture(const std::string& name)
        {
            if (name.empty())
                return {};
            if (const auto [image, index] = scene.GetEmbeddedTextureAndIndex(name.c_str());
                image != nullptr && index >= 0) {
                MaterialTexture& held = embedded[static_cast<size_t>(index)];
                if (held.empty()) {
                    held = embedded_texture(*image, name);
                    held.container = path;
                }
                return held;
            }
            const std::filesystem::path file = std::filesystem::path(name).is_absolute()
                                                   ? std::filesystem::path(name)
                                                   : path.parent_path() / name;
            std::error_code ec;
            if (!std::filesystem::is_regular_file(file, ec))
                return {};
            MaterialTexture texture;
            texture.file = file;
            texture.name = file.filename().string();
            return texture;
        }

        void convert(const aiMesh& in, const std::string& node_name, const Imath::M44f& to_world)
        {
            const float det = determinant3(to_world);
            if (!std::isfinite(det) || std::abs(det) < 1e-30f)
                throw std::runtime_error(fmt::format("{}: node '{}' has a singular or non-finite transform",
                                                     where(), node_name));
            const Imath::M44f normal_matrix = to_world.inverse().transposed();

            TriangleMesh m;
            m.name = in.mName.length ? in.mName.C_Str() : node_name;
            if (in.mMaterialIndex < scene.mNumMaterials) {
                const aiMaterial& material = *scene.mMaterials[in.mMaterialIndex];
                m.material_name = material.GetName().C_Str();
                aiColor4D c;
                if (material.Get(AI_MATKEY_BASE_COLOR, c) == AI_SUCCESS ||
                    material.Get(AI_MATKEY_COLOR_DIFFUSE, c) == AI_SUCCESS)
                    m.base_colour = Imath::V4f(c.r, c.g, c.b, c.a);
                aiString texture;
                if (material.GetTexture(aiTextureType_BASE_COLOR, 0, &texture) == AI_SUCCESS ||
                    material.GetTexture(aiTextureType_DIFFUSE, 0, &texture) == AI_SUCCESS)
                    m.base_colour_texture = base_colour_texture(texture.C_Str());
            }
            const std::string what = fmt::format("{}: mesh '{}'", where(), m.name);

            m.positions.resize(in.mNumVertices);
            for (unsigned i = 0; i < in.mNumVertices; ++i) {
                const Imath::V3f p(in.mVertices[i].x, in.mVertices[i].y, in.mVertices[i].z);
                if (!finite(p))
                    throw std::runtime_error(fmt::format("{}: vertex {} has a non-finite position ({}, {}, {})",
                                                         what, i, p.x, p.y, p.z));
                to_world.multVecMatrix(p, m.positions[i]);
            }
            bool normals_ok = in.HasNormals();
            if (normals_ok) {
                m.normals.resize(in.mNumVertices);
                for (unsigned i = 0; i < in.mNumVertices && normals_ok; ++i) {
                    Imath::V3f n;
                    normal_matrix.multDirMatrix(
                        Imath::V3f(in.mNormals[i].x, in.mNormals[i].y, in.mNormals[i].z), n);
                    normals_ok = finite(n) && n.length2() > 0.0f;
                    m.normals[i] = normals_ok ? n.normalized() : n;
                }
            }
            const auto read_uvs = [&](unsigned set, std::vector<Imath::V2f>& out) {
                out.resize(in.mNumVertices);
                for (unsigned i = 0; i < in.mNumVertices; ++i) {
                    out[i] = Imath::V2f(in.mTextureCoords[set][i].x, in.mTextureCoords[set][i].y);
                    if (!std::isfinite(out[i].x) || !std::isfinite(out[i].y))
                        throw std::runtime_error(fmt::format("{}: vertex {} has a non-finite uv "
                                                             "in uv set {}", what, i, set));
                }
            };
            m.uv_set_count = static_cast<int>(in.GetNumUVChannels());
            m.uv_set = uv_set;
            if (uv_set > 0) {
                const unsigned sets = in.GetNumUVChannels();
                if (static_cast<unsigned>(uv_set) >= sets)
                    throw std::runtime_error(fmt::format(
                        "{}: --uv-set {} asks for uv set {} of {} (the sets count from 0); "
                        "`patina-texgen unwrap` adds one", what, uv_set, uv_set, sets));
                read_uvs(static_cast<unsigned>(uv_set), m.uvs);
                read_uvs(0, m.source_uvs);
            } else if (in.HasTextureCoords(0)) {
                read_uvs(0, m.uvs);
            }

            // A mirroring transform reverses the winding; swap two indices to keep it
            // consistent with the (correctly transformed) normals.
            const bool flip = det < 0.0f;
            m.indices.reserve(static_cast<size_t>(in.mNumFaces) * 3);
            for (unsigned f = 0; f < in.mNumFaces; ++f) {
                const aiFace& face = in.mFaces[f];
                if (face.mNumIndices != 3)
                    continue; // points and lines
                for (int k = 0; k < 3; ++k)
                    if (face.mIndices[k] >= in.mNumVertices)
                        throw std::runtime_error(fmt::format("{}: triangle {} uses vertex {} of {}",
                                                             what, f, face.mIndices[k], in.mNumVertices));
                m.indices.insert(m.indices.end(), {face.mIndices[0], face.mIndices[flip ? 2 : 1],
                                                   face.mIndices[flip ? 1 : 2]});
            }
            if (m.indices.empty())
                return;
            if (!normals_ok && in.HasNormals())
                compute_vertex_normals(m); // the file's normals were zero or NaN
            meshes.push_back(std::move(m));
        }

        void visit(const aiNode& node, const Imath::M44f& parent)
        {
            // Row vectors: the node's local transform applies before its parent's.
            const Imath::M44f world = to_imath(node.mTransformation) * parent;
            for (unsigned i = 0; i < node.mNumMeshes; ++i)
                convert(*scene.mMeshes[node.mMeshes[i]], node.mName.C_Str(), world);
            for (unsigned i = 0; i < node.mNumChildren; ++i)
                visit(*node.mChildren[i], world);
        }
    };

    std::string lower_extension(const std::filesystem::path& path)
    {
        std::string e = path.extension().string();
        for (char& c : e)
            c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        return e;
    }

    /// A number of Assimp's metadata, whatever type the importer stored it as.
    std::optional<double> metadata_number(const aiMetadata* metadata, const char* key)
    {
        if (!metadata)
            return std::nullopt;
        for (unsigned i = 0; i < metadata->mNumProperties; ++i) {
            if (std::string_view(metadata->mKeys[i].C_Str()) != key)
                continue;
            const aiMetadataEntry& e = metadata->mValues[i];
            switch (e.mType) {
            case AI_INT32: return *static_cast<const int32_t*>(e.mData);
            case AI_UINT64: return static_cast<double>(*static_cast<const uint64_t*>(e.mData));
            case AI_FLOAT: return *static_cast<const float*>(e.mData);
            case AI_DOUBLE: return *static_cast<const double*>(e.mData);
            default: return std::nullopt;
            }
        }
        return std::nullopt;
    }

    /// FBX: the GlobalSettings' UpAxis (0, 1, 2), UpAxisSign (+1, -1) and UnitScaleFactor
    /// (centimetres per unit: FBX's own unit is the centimetre), which Assimp 5.2 reports
    /// as scene metadata without applying them.
    DeclaredConvention fbx_declaration(const std::filesystem::path& path, const aiScene& scene)
    {
        DeclaredConvention d;
        d.source = "FBX GlobalSettings";
        for (const aiMetadata* m : {scene.mMetaData, scene.mRootNode->mMetaData}) {
            const auto axis = metadata_number(m, "UpAxis");
            const auto sign = metadata_number(m, "UpAxisSign");
            const auto unit = metadata_number(m, "UnitScaleFactor");
            if (axis && !d.up) {
                if (*axis != 0 && *axis != 1 && *axis != 2)
                    throw std::runtime_error(fmt::format(
                        "mesh file '{}': its FBX GlobalSettings declare UpAxis {}, not 0, 1 or 2 "
                        "(give the up axis with --up)", path.string(), *axis));
                d.up = Axis{static_cast<int>(*axis), sign && *sign < 0 ? -1 : 1};
            }
            if (unit && !d.metres_per_unit) {
                if (!(*unit > 0.0) || !std::isfinite(*unit))
                    throw std::runtime_error(fmt::format(
                        "mesh file '{}': its FBX GlobalSettings declare UnitScaleFactor {} (give "
                        "the unit with --unit or --scale)", path.string(), *unit));
                d.metres_per_unit = 0.01 * *unit;
            }
        }
        return d;
    }

    /// The value of attribute `name` in the first element `<tag ...>` of `text`.
    std::optional<std::string> xml_attribute(std::string_view text, std::string_view tag,
                                             std::string_view name)
    {
        // Built by appending: GCC 12 warns falsely (-Wrestrict, its bug 105329) on "<" + s.
        std::string open_tag(1, '<');
        open_tag.append(tag);
        const size_t open = text.find(open_tag);
        if (open == std::string_view::npos)
            return std::nullopt;
        const size_t close = text.find('>', open);
        const std::string_view element = text.substr(open, close - open);
        std::string key(1, ' ');
        key.append(name).push_back('=');
        const size_t at = element.find(key);
        if (at == std::string_view::npos)
            return std::nullopt;
        const size_t quote = at + key.size();
        if (quote >= element.size())
            return std::nullopt;
        const size_t end = element.find(element[quote], quote + 1);
        if (end == std::string_view::npos)
            return std::nullopt;
        return std::string(element.substr(quote + 1, end - quote - 1));
    }

    /// COLLADA: `<unit meter="...">` and `<up_axis>` of the document's `<asset>` (defaults 1
    /// and Y_UP, COLLADA 1.4.1 specification, chapter 5 "asset"). Assimp's reader applies
    /// both to the root node; they are read here to report them and to undo them when an
    /// option overrides them.
    DeclaredConvention collada_declaration(const std::filesystem::path& path)
    {
        DeclaredConvention d;
        d.source = "COLLADA <asset>";
        d.applied_by_importer = true;
        d.up = Axis{1, 1};
        d.metres_per_unit = 1.0;
        std::ifstream in(path, std::ios::binary);
        std::string head(1 << 16, '\0');
        in.read(head.data(), static_cast<std::streamsize>(head.size()));
        head.resize(static_cast<size_t>(in.gcount()));
        const size_t begin = head.find("<asset");
        const size_t end = head.find("</asset>", begin);
        if (begin == std::string::npos || end == std::string::npos)
            return d;
        const std::string_view asset = std::string_view(head).substr(begin, end - begin);
        if (const auto meter = xml_attribute(asset, "unit", "meter")) {
            char* stop = nullptr;
            const double v = std::strtod(meter->c_str(), &stop);
            if (stop == meter->c_str() || !(v > 0.0) || !std::isfinite(v))
                throw std::runtime_error(fmt::format(
                    "mesh file '{}': <unit meter=\"{}\"> is not a length > 0 (give the unit "
                    "with --unit or --scale)", path.string(), *meter));
            d.metres_per_unit = v;
        }
        if (const size_t up = asset.find("<up_axis>"); up != std::string_view::npos) {
            const std::string_view value = asset.substr(up + 9, 4);
            if (value == "X_UP")
                d.up = Axis{0, 1};
            else if (value == "Z_UP")
                d.up = Axis{2, 1};
        }
        return d;
    }

    DeclaredConvention declaration_of(const std::filesystem::path& path, const aiScene& scene)
    {
        const std::string ext = lower_extension(path);
        if (ext == ".fbx")
            return fbx_declaration(path, scene);
        if (ext == ".dae")
            return collada_declaration(path);
        if (ext == ".gltf" || ext == ".glb")
            return {Axis{1, 1}, 1.0, "glTF (+Y up, metres by specification)", false};
        return {};
    }

    /// Assimp 5.2's PLY parser loops forever on a header without `end_header`: refuse such
    /// files before handing them over.
    void check_ply_header(const std::filesystem::path& path)
    {
        std::ifstream in(path, std::ios::binary);
        char magic[4] = {};
        in.read(magic, 4);
        if (std::string_view(magic, 3) != "ply" || (magic[3] != '\n' && magic[3] != '\r'))
            return;
        std::string line;
        for (int lines = 0; lines < 100000 && std::getline(in, line); ++lines)
            if (line.rfind("end_header", 0) == 0)
                return;
        throw std::runtime_error(fmt::format("mesh file '{}': malformed PLY header (no end_header line)",
                                             path.string()));
    }

    void check_raw_scene(const std::filesystem::path& path, const aiScene& scene)
    {
        size_t polygons = 0;
        for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
            const aiMesh& mesh = *scene.mMeshes[m];
            for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
                const aiVector3D& p = mesh.mVertices[i];
                if (!finite(Imath::V3f(p.x, p.y, p.z)))
                    throw std::runtime_error(fmt::format(
                        "mesh file '{}': mesh '{}': vertex {} has a non-finite position ({}, {}, {})",
                        path.string(), mesh.mName.C_Str(), i, p.x, p.y, p.z));
            }
            for (unsigned f = 0; f < mesh.mNumFaces; ++f)
                polygons += mesh.mFaces[f].mNumIndices >= 3;
        }
        if (polygons == 0)
            throw std::runtime_error(fmt::format("mesh file '{}' contains no triangles", path.string()));
    }

    /// Assimp's OBJ reader turns a coordinate it cannot parse ("nan", "inf", "1e999",
    /// "abc") into 0 without a word: read the vertex lines' numbers first, so that such a
    /// value is refused with its line as the documentation promises.
    void check_obj_numbers(const std::filesystem::path& path)
    {
        if (path.extension() != ".obj" && path.extension() != ".OBJ")
            return;
        std::ifstream in(path);
        std::string line;
        for (size_t number = 1; std::getline(in, line); ++number) {
            std::istringstream words(line);
            std::string keyword;
            words >> keyword;
            if (keyword != "v" && keyword != "vt" && keyword != "vn")
                continue;
            for (std::string word; words >> word;) {
                if (word[0] == '#')
                    break;  // a comment to the end of the line
                char* end = nullptr;
                const double v = std::strtod(word.c_str(), &end);
                if (end != word.c_str() + word.size() || !std::isfinite(v))
                    throw std::runtime_error(fmt::format(
                        "mesh file '{}': line {}: '{}' has a non-finite or malformed "
                        "coordinate '{}'", path.string(), number, keyword, word));
            }
        }
    }

}  // namespace

ImageData read_material_texture(const MaterialTexture& texture)
{
    if (texture.texels)
        return *texture.texels;
    if (texture.encoded)
        return read_image(*texture.encoded, texture.format,
                          fmt::format("{}' embedded in '{}", texture.name,
                                      texture.container.string()));
    if (texture.file.empty())
        throw std::invalid_argument("read_material_texture: the material has no texture");
    return read_image(texture.file);
}

std::vector<TriangleMesh> load_meshes(const std::filesystem::path& path,
                                      const MeshConventionOptions& options,
                                      MeshConvention* applied, const Imath::M44f& transform)
{
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
        throw std::runtime_error(fmt::format("mesh file '{}': file not found", path.string()));
    if (!std::filesystem::is_regular_file(path, ec))
        throw std::runtime_error(fmt::format("mesh file '{}': not a regular file", path.string()));

    check_ply_header(path);
    check_obj_numbers(path);
    Assimp::Importer importer;
    importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    const aiScene* scene = importer.ReadFile(path.string(), aiProcess_ValidateDataStructure);
    if (!scene || !scene->mRootNode)
        throw std::runtime_error(fmt::format("mesh file '{}': {}", path.string(),
                                             importer.GetErrorString()));
    // Check the raw data before post-processing: JoinIdenticalVertices merges NaN
    // vertices into others, which would hide them.
    check_raw_scene(path, *scene);
    // Assimp 5.2's JoinIdenticalVertices merges vertices that differ only in their second or
    // later uv set (a Blender glTF with two sets: set 1's uv area grew from 0.57 to 9.8 of the
    // tile): files with several sets are left as they are indexed.
    bool several_uv_sets = false;
    for (unsigned m = 0; m < scene->mNumMeshes; ++m)
        several_uv_sets = several_uv_sets || scene->mMeshes[m]->GetNumUVChannels() > 1;
    scene = importer.ApplyPostProcessing(
        aiProcess_Triangulate | (several_uv_sets ? 0u : unsigned{aiProcess_JoinIdenticalVertices}) |
        aiProcess_SortByPType | aiProcess_ValidateDataStructure);
    if (!scene || !scene->mRootNode)
        throw std::runtime_error(fmt::format("mesh file '{}': {}", path.string(),
                                             importer.GetErrorString()));
    const DeclaredConvention declared = declaration_of(path, *scene);
    MeshConvention convention = resolve_convention(declared, options);
    Imath::M44f to_world = convention.file_to_world * transform;
    if (declared.applied_by_importer) {
        // Assimp has applied the declaration already: undo it where the options differ.
        const MeshConvention by_importer = resolve_convention(declared, {});
        if (!(by_importer.up == convention.up &&
              by_importer.metres_per_unit == convention.metres_per_unit))
            to_world = by_importer.file_to_world.inverse() * to_world;
        else
            to_world = transform;
    }
    if (options.uv_set < 0 || options.uv_set >= static_cast<int>(AI_MAX_NUMBER_OF_TEXTURECOORDS))
        throw std::runtime_error(fmt::format("mesh file '{}': --uv-set {} is not a uv set (0 to "
                                             "{})", path.string(), options.uv_set,
                                             AI_MAX_NUMBER_OF_TEXTURECOORDS - 1));
    Loader loader{path, *scene, options.uv_set, {}};
    loader.visit(*scene->mRootNode, to_world);
    if (loader.meshes.empty())
        throw std::runtime_error(fmt::format("mesh file '{}' contains no triangles", path.string()));
    for (const TriangleMesh& m : loader.meshes)
        validate_mesh(m, loader.where() + ": mesh '" + m.name + "'");
    if (applied)
        *applied = std::move(convention);
    return std::move(loader.meshes);
}

Imath::Box3f bounds_of(const TriangleMesh& mesh)
{
    Imath::Box3f box;
    for (const Imath::V3f& p : mesh.positions)
        box.extendBy(p);
    return box;
}

Imath::Box3f bounds_of(const std::vector<TriangleMesh>& meshes)
{
    Imath::Box3f box;
    for (const TriangleMesh& m : meshes)
        box.extendBy(bounds_of(m));
    return box;
}

void validate_mesh(const TriangleMesh& mesh, const std::string& context)
{
    const size_t n = mesh.positions.size();
    if (mesh.indices.size() % 3 != 0)
        throw std::runtime_error(fmt::format("{}: {} indices is not a multiple of 3", context, mesh.indices.size()));
    if (!mesh.normals.empty() && mesh.normals.size() != n)
        throw std::runtime_error(fmt::format("{}: {} normals for {} vertices", context, mesh.normals.size(), n));
    if (!mesh.uvs.empty() && mesh.uvs.size() != n)
        throw std::runtime_error(fmt::format("{}: {} uvs for {} vertices", context, mesh.uvs.size(), n));
    if (!mesh.triangle_material.empty() &&
        (mesh.triangle_material.size() != mesh.indices.size() / 3 ||
         std::any_of(mesh.triangle_material.begin(), mesh.triangle_material.end(),
                     [&](uint16_t k) { return k >= mesh.materials.size(); })))
        throw std::runtime_error(fmt::format("{}: {} triangle materials for {} triangles of {} "
                                             "materials", context, mesh.triangle_material.size(),
                                             mesh.indices.size() / 3, mesh.materials.size()));
    if (!mesh.source_uvs.empty() && mesh.source_uvs.size() != n)
        throw std::runtime_error(fmt::format("{}: {} source uvs for {} vertices", context,
                                             mesh.source_uvs.size(), n));
    for (size_t i = 0; i < n; ++i)
        if (!finite(mesh.positions[i]))
            throw std::runtime_error(fmt::format("{}: vertex {} has a non-finite position", context, i));
    for (size_t i = 0; i < mesh.indices.size(); ++i)
        if (mesh.indices[i] >= n)
            throw std::runtime_error(fmt::format("{}: triangle {} uses vertex {} of {}", context,
                                                 i / 3, mesh.indices[i], n));
}

void compute_vertex_normals(TriangleMesh& mesh)
{
    mesh.normals.assign(mesh.positions.size(), Imath::V3f(0.0f));
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
        // The unnormalised cross product weighs each face by twice its area.
        const Imath::V3f n = (mesh.positions[b] - mesh.positions[a]).cross(mesh.positions[c] - mesh.positions[a]);
        mesh.normals[a] += n;
        mesh.normals[b] += n;
        mesh.normals[c] += n;
    }
    for (Imath::V3f& n : mesh.normals)
        n = n.length2() > 0.0f ? n.normalized() : Imath::V3f(0.0f);
}

double surface_area(const TriangleMesh& mesh)
{
    double area = 0.0;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const Imath::V3d a(mesh.positions[mesh.indices[t]]), b(mesh.positions[mesh.indices[t + 1]]),
            c(mesh.positions[mesh.indices[t + 2]]);
        area += 0.5 * (b - a).cross(c - a).length();
    }
    return area;
}

TriangleMesh make_uv_sphere(const Imath::V3f& center, float radius, int rings, int segments)
{
    if (rings < 2 || segments < 3 || !(radius > 0.0f))
        throw std::runtime_error(fmt::format("make_uv_sphere: need rings >= 2, segments >= 3 and "
                                             "radius > 0 (got {}, {}, {})", rings, segments, radius));
    constexpr float kPi = std::numbers::pi_v<float>;
    TriangleMesh m;
    m.name = "sphere";
    // Row i goes from the north pole (i = 0) to the south pole (i = rings).
    for (int i = 0; i <= rings; ++i) {
        const float theta = kPi * static_cast<float>(i) / static_cast<float>(rings);
        for (int j = 0; j <= segments; ++j) {
            const float phi = 2.0f * kPi * static_cast<float>(j) / static_cast<float>(segments);
            Imath::V3f n(std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi));
            if (i == 0 || i == rings)
                n = Imath::V3f(0.0f, i == 0 ? 1.0f : -1.0f, 0.0f); // exact poles
            m.positions.push_back(center + radius * n);
            m.normals.push_back(n);
            m.uvs.emplace_back(static_cast<float>(j) / static_cast<float>(segments),
                               1.0f - static_cast<float>(i) / static_cast<float>(rings));
        }
    }
    const auto id = [&](int i, int j) { return static_cast<uint32_t>(i * (segments + 1) + j); };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            // Counter-clockwise in (u, v), hence outward; skip the triangles that collapse
            // onto a pole.
            const uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
            if (i != rings - 1)
                m.indices.insert(m.indices.end(), {b, c, d});
            if (i != 0)
                m.indices.insert(m.indices.end(), {b, d, a});
        }
    return m;
}

TriangleMesh make_plane(const Imath::V3f& center, float size, int subdivisions, const Imath::V3f& normal)
{
    if (subdivisions < 1 || !(size > 0.0f) || !(normal.length2() > 0.0f))
        throw std::runtime_error(fmt::format("make_plane: need size > 0, subdivisions >= 1 and a "
                                             "non-zero normal (got {}, {})", size, subdivisions));
    const Imath::V3f n = normal.normalized();
    // Tangent frame with cross(du, dv) = n; du is +x for an up-facing plane.
    const Imath::V3f helper = std::abs(n.x) < 0.9f ? Imath::V3f(1, 0, 0) : Imath::V3f(0, 0, -1);
    const Imath::V3f du = (helper - n * n.dot(helper)).normalized();
    const Imath::V3f dv = n.cross(du);
    TriangleMesh m;
    m.name = "plane";
    const int k = subdivisions;
    for (int i = 0; i <= k; ++i)
        for (int j = 0; j <= k; ++j) {
            const float u = static_cast<float>(j) / static_cast<float>(k);
            const float v = static_cast<float>(i) / static_cast<float>(k);
            m.positions.push_back(center + size * ((u - 0.5f) * du + (v - 0.5f) * dv));
            m.normals.push_back(n);
            m.uvs.emplace_back(u, v);
        }
    for (int i = 0; i < k; ++i)
        for (int j = 0; j < k; ++j) {
            const uint32_t a = static_cast<uint32_t>(i * (k + 1) + j), b = a + 1,
                           c = a + static_cast<uint32_t>(k) + 2, d = c - 1;
            m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
        }
    return m;
}

TriangleMesh make_quad(const Imath::V3f& center, float size, const Imath::V3f& normal)
{
    TriangleMesh m = make_plane(center, size, 1, normal);
    m.name = "quad";
    return m;
}

TriangleMesh make_box(const Imath::V3f& center, const Imath::V3f& size)
{
    if (!(size.x > 0.0f && size.y > 0.0f && size.z > 0.0f))
        throw std::runtime_error(fmt::format("make_box: edge lengths must be positive (got {}, {}, {})",
                                             size.x, size.y, size.z));
    TriangleMesh m;
    m.name = "box";
    const Imath::V3f half = 0.5f * size;
    for (int axis = 0; axis < 3; ++axis)
        for (float sign : {1.0f, -1.0f}) {
            Imath::V3f n(0.0f), du(0.0f);
            n[axis] = sign;
            du[(axis + 1) % 3] = 1.0f;
            const Imath::V3f dv = n.cross(du); // cross(du, dv) = n: counter-clockwise outside
            const uint32_t base = static_cast<uint32_t>(m.positions.size());
            for (const auto& [u, v] : {std::pair{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}}) {
                const Imath::V3f offset = n + (2.0f * u - 1.0f) * du + (2.0f * v - 1.0f) * dv;
                m.positions.push_back(center + Imath::V3f(offset.x * half.x, offset.y * half.y, offset.z * half.z));
                m.normals.push_back(n);
                m.uvs.emplace_back(u, v);
            }
            m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
        }
    return m;
}

}  // namespace patina
