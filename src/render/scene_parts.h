// The parts of a scene file read by their own translation units (scene.cpp reads the rest).
#pragma once

#include "render/light.h"
#include "render/scene.h"
#include "render/toml_reader.h"

#include <Imath/ImathVec.h>

#include <filesystem>
#include <memory>
#include <vector>

namespace patina::render {

/// A colour (`color`, `colorspace`) of table `t` as non-negative working-space RGB.
Imath::V3f working_rgb(const TomlReader& w, const toml::table& t, std::string_view table,
                       const Host& host);

/// [environment]: a lat-long map (file, colorspace, rotation_deg) or a uniform colour.
void add_environment(const TomlReader& w, const toml::table& root,
                     const std::filesystem::path& base_dir, const Host& host,
                     std::vector<std::unique_ptr<Light>>& lights);

/// [sun]: a distant light with an angular diameter, a colour and an irradiance.
void add_sun(const TomlReader& w, const toml::table& root, const Host& host,
             std::vector<std::unique_ptr<Light>>& lights);

/// [[object]]: built-in shapes and mesh files with transforms, bound to the scene's
/// shaders (per object or per material name); adds their meshes to scene.geometry.
void add_objects(const TomlReader& w, const toml::table& root,
                 const std::filesystem::path& base_dir, Scene& scene);

}  // namespace patina::render
