// Shader instances: parameters bound from TOML with type and range checks, then `create`.
#pragma once

#include "core/plugin_registry.h"

#include <toml++/toml.h>

#include <memory>
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

/// Bind `params` (every key is a parameter name; `ignore_keys` lists keys the caller
/// handles, e.g. "type" and "name") to the shader's declarations, checking names, types and
/// ranges, filling defaults, and create the instance. Throws std::runtime_error with a
/// message "<source>:<line>: shader '<label>' (<type>): parameter '<name>': ..." on any error.
std::shared_ptr<ShaderInstance> create_shader_instance(
    const PluginRegistry& registry, std::string_view shader_name, const toml::table& params,
    std::string_view label, std::string_view source_name,
    std::initializer_list<std::string_view> ignore_keys = {});

}  // namespace patina
