// Shader instances: parameters bound from TOML with type and range checks, then `create`.
#pragma once

#include "host/plugin_registry.h"

#include <toml++/toml.h>

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <vector>
#include <string>
#include <string_view>

namespace patina {

/// An immutable instance of a plugin shader; destroys itself through the plugin.
class ShaderInstance {
public:
    ShaderInstance(const LoadedShader& shader, void* instance, std::string label)
        : shader_(&shader), instance_(instance), label_(std::move(label)) {}
    ~ShaderInstance();
    ShaderInstance(const ShaderInstance&) = delete;
    ShaderInstance& operator=(const ShaderInstance&) = delete;

    const PatinaShaderDesc& desc() const { return *shader_->desc; }
    const LoadedShader& shader() const { return *shader_; }
    const void* get() const { return instance_; }
    const std::string& label() const { return label_; }
    PatinaShaderKind kind() const { return shader_->desc->kind; }
    const PatinaBsdfFuncs* bsdf() const { return shader_->desc->bsdf; }
    const PatinaMediumFuncs* medium() const { return shader_->desc->medium; }
    const PatinaEmitterFuncs* emitter() const { return shader_->desc->emitter; }

private:
    const LoadedShader* shader_;
    void* instance_;
    std::string label_;
};

/// Where a parameter table came from, for messages and relative paths.
struct ParamSource {
    std::string file;                        ///< file name shown in messages ("" = none)
    std::filesystem::path base_dir;          ///< relative texture paths resolve against it
    std::vector<std::string> ignore_keys;    ///< keys the caller handles ("type", "name", ...)
};

/// A parameter binding or creation error; what() reads
/// "<file>:<line>:<column>: shader '<label>' (<type>): parameter '<name>': <problem>".
class ParamError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Bind `params` to the shader's declarations — every key must name a parameter (unknown
/// keys are errors, with the closest name suggested), values are checked against the
/// declared type and range, COLOR values are converted from their colour space to the
/// working space and uplifted, textures are opened through the host — fill defaults, and
/// create the instance. The registry's host must be a patina::Host.
std::shared_ptr<ShaderInstance> create_shader_instance(const PluginRegistry& registry,
                                                       std::string_view shader_name,
                                                       const toml::table& params,
                                                       std::string_view label,
                                                       const ParamSource& source = {});

/// One line per parameter: "name  type  default  [min, max]  colour space/units  help".
std::string describe_shader(const PatinaShaderDesc& desc);
/// The same as a Markdown table, one row per parameter (docs/shaders.md).
std::string describe_shader_markdown(const PatinaShaderDesc& desc);

}  // namespace patina
