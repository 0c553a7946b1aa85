// `patina-texgen view`: a self-contained static folder that shows an exported glTF time
// series in a browser (docs/viewer.md): index.html, the viewer's bundle (three.js, built by
// the project from viewer/), and data.js holding the asset, its ages, the display
// transforms of the OCIO config as OCIO's own GLSL, and the environments. data.js is a
// script, not fetched data, so the page opens from a local folder (file://) as from a
// server.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace patina {
class ColorManager;
}

namespace patina::texgen {

struct ViewerOptions {
    std::filesystem::path model;   ///< a .glb of `patina-texgen export`
    std::filesystem::path out;     ///< the folder to write
    std::string title;             ///< default: the model's stem
    int environment_width = 256;   ///< texels around of each environment
};

struct ViewerSummary {
    std::vector<std::string> ages;    ///< the asset's ages ("15 y"), in its variants' order
    std::vector<std::string> views;   ///< the display's views
};

/// Where the built viewer (viewer.js, index.html) is: $PATINA_VIEWER_DIR, else
/// <exe>/../share/patina/viewer. Throws naming the places it looked.
std::filesystem::path viewer_bundle_dir();

/// The default display's views as data.js holds them (a JSON array): per view its name and
/// either OCIO's GLSL or a 3D LUT baked by OCIO with the GLSL that looks it up
/// (docs/viewer.md "Colour"). Throws for a config without linear Rec.709.
std::string display_views_json(const ColorManager& colors);

/// Writes the folder. Throws std::runtime_error naming the file for a model that is not a
/// .glb with at least one material variant (an exported series), and for a config with no
/// linear Rec.709 colour space (the page's working space).
ViewerSummary write_viewer(const ViewerOptions& options, const ColorManager& colors);

}  // namespace patina::texgen
