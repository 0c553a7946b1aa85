#include "core/mesh_export.h"

#include "core/image_io.h"
#include "core/output_transaction.h"

#include <assimp/Exporter.hpp>
#include <assimp/scene.h>

#include <fmt/format.h>

#include <memory>
#include <stdexcept>
#include <system_error>

namespace patina {

namespace {

std::string format_id_for(const std::filesystem::path& path)
{
    std::string ext = path.extension().string();
    for (char& c : ext)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext == ".obj")
        return "objnomtl";  // no .mtl beside it: Patina binds shaders in its own files
    if (ext == ".ply")
        return "plyb";
    if (ext == ".glb")
        return "glb2";
    if (ext == ".gltf")
        return "gltf2";
    if (ext == ".stl")
        return "stlb";
    throw std::runtime_error(fmt::format("cannot write mesh '{}': unknown extension '{}' (use "
                                         ".obj, .ply, .glb, .gltf or .stl)",
                                         path.string(), ext));
}

// An aiScene owning one mesh; aiScene's destructor frees what it points to.
std::unique_ptr<aiScene> make_scene(const TriangleMesh& mesh)
{
    auto scene = std::make_unique<aiScene>();
    scene->mMaterials = new aiMaterial*[1]{new aiMaterial()};
    scene->mNumMaterials = 1;

    auto* m = new aiMesh();
    scene->mMeshes = new aiMesh*[1]{m};
    scene->mNumMeshes = 1;
    m->mName = aiString(mesh.name.empty() ? std::string("mesh") : mesh.name);
    m->mMaterialIndex = 0;
    m->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
    const auto n = static_cast<unsigned>(mesh.positions.size());
    m->mNumVertices = n;
    m->mVertices = new aiVector3D[n];
    for (unsigned i = 0; i < n; ++i)
        m->mVertices[i] = {mesh.positions[i].x, mesh.positions[i].y, mesh.positions[i].z};
    if (mesh.has_normals()) {
        m->mNormals = new aiVector3D[n];
        for (unsigned i = 0; i < n; ++i)
            m->mNormals[i] = {mesh.normals[i].x, mesh.normals[i].y, mesh.normals[i].z};
    }
    if (mesh.has_uvs()) {
        m->mTextureCoords[0] = new aiVector3D[n];
        m->mNumUVComponents[0] = 2;
        for (unsigned i = 0; i < n; ++i)
            m->mTextureCoords[0][i] = {mesh.uvs[i].x, mesh.uvs[i].y, 0.0f};
    }
    const auto faces = static_cast<unsigned>(mesh.triangle_count());
    m->mNumFaces = faces;
    m->mFaces = new aiFace[faces];
    for (unsigned f = 0; f < faces; ++f) {
        m->mFaces[f].mNumIndices = 3;
        m->mFaces[f].mIndices = new unsigned[3]{mesh.indices[3 * f], mesh.indices[3 * f + 1],
                                                mesh.indices[3 * f + 2]};
    }

    scene->mRootNode = new aiNode();
    scene->mRootNode->mNumMeshes = 1;
    scene->mRootNode->mMeshes = new unsigned[1]{0};
    return scene;
}

}  // namespace

void save_mesh(const std::filesystem::path& path, const TriangleMesh& mesh)
{
    validate_mesh(mesh, fmt::format("cannot write mesh '{}'", path.string()));
    const std::string format = format_id_for(path);
    const std::unique_ptr<aiScene> scene = make_scene(mesh);
    StagedOutput staged(path);
    Assimp::Exporter exporter;
    if (exporter.Export(scene.get(), format, staged.path().string()) != aiReturn_SUCCESS)
        throw std::runtime_error(fmt::format("cannot write mesh '{}': {}", path.string(),
                                             exporter.GetErrorString()));
    staged.done();
}

}  // namespace patina
