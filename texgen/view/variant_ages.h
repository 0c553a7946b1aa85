// The age each material variant of an exported series shows, read from what export records
// in its materials' extras (docs/export.md): `extras.patina.time_years` (patina series) or
// `extras.patina.time_s` (fading series), not parsed back from the variant's name.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace patina::texgen {

struct VariantAges {
    /// Per variant, in the variants' order, in `unit`; empty when a variant's materials
    /// record no time (a series made elsewhere, a series by dose): then the names are all
    /// there is.
    std::vector<double> values;
    std::string unit;  ///< "y", or for times in seconds the largest of d, h, min, s that
                       ///< the last age reaches once
    /// The ages as the viewer's labels say them ("15 y"); the variants' names when `values`
    /// is empty.
    std::vector<std::string> labels;
};

/// The ages of the variants of `gltf` (its JSON). A variant's age is the recorded time of
/// any material that shows it (the primitives' KHR_materials_variants mappings); variants
/// whose materials disagree, or any variant without one, leave `values` empty.
VariantAges variant_ages(const nlohmann::json& gltf);

}  // namespace patina::texgen
