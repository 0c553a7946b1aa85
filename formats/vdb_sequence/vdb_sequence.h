// The frames of an OpenVDB sequence `patina-texgen export` writes from a stone run
// (docs/export.md, "Stone volumes as OpenVDB"): `<stem>.frames.toml` beside the volumes,
// saying which simulation cycle each consecutively numbered frame holds.
//
//   [sequence]
//   format = 1
//   source = "out/stone/column"      the stone run the frames come from
//   [[frame]]                        in frame order
//   frame = 1                        the number in the file names (1, 2, 3, ...)
//   cycle = 0                        the simulation cycle it holds
//   volume = "column.0001.vdb"       beside this file
//   boundary = "column.0001.obj"     the eroded surface, when the run kept it (optional)
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace patina::formats {

inline constexpr int kVdbSequenceFormat = 1;

/// The OpenVDB file metadata naming a frame's cycle and frame number (Int32).
inline constexpr const char* kVdbCycleMeta = "patina_cycle";
inline constexpr const char* kVdbFrameMeta = "patina_frame";

struct VdbSequenceFrame {
    int frame = 0;
    int cycle = 0;
    std::string volume;
    std::string boundary;  ///< empty: none
};

struct VdbSequence {
    std::string source;
    std::vector<VdbSequenceFrame> frames;
};

/// The manifest of `stem` (the output's stem, "column") beside it: "column.frames.toml".
std::filesystem::path vdb_sequence_path(const std::filesystem::path& output);

/// The file name of frame `frame` of `output` ("column.vdb" -> "column.0001.vdb").
std::string vdb_frame_name(const std::filesystem::path& output, int frame,
                           std::string_view extension = ".vdb");

/// The manifest's text.
std::string vdb_sequence_text(const VdbSequence& sequence);

/// The manifest read back. Throws std::runtime_error "file:line:column: what" for a syntax
/// error, an unknown key, a missing or mistyped value, a newer format, frames not numbered
/// 1, 2, 3, ... or cycles that do not increase.
VdbSequence read_vdb_sequence(const std::filesystem::path& file);
VdbSequence parse_vdb_sequence(std::string_view text, const std::filesystem::path& source);

}  // namespace patina::formats
