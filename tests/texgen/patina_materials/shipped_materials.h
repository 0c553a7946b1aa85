// Fixtures shared by the patina material tests: the repository's OCIO config and the shipped
// copper material library, each loaded once per test process.
#pragma once

#include "core/color_management.h"
#include "texgen/patina/material_library.h"

#include <filesystem>

namespace patina::texgen::test {

inline const ColorManager& repository_colors()
{
    static const ColorManager cm(std::filesystem::path(PATINA_SOURCE_DIR) / "ocio" /
                                 "config.ocio");
    return cm;
}

inline const MaterialLibrary& shipped_copper_library()
{
    static const MaterialLibrary lib = [] {
        MaterialLibrary l;
        l.load(std::filesystem::path(PATINA_SOURCE_DIR) / "shaders/patina/copper.toml",
               repository_colors());
        return l;
    }();
    return lib;
}

} // namespace patina::texgen::test
