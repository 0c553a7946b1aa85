#include "formats/vdb_sequence/vdb_sequence.h"

#include "formats/toml_location.h"

#include <toml++/toml.h>

#include <cstdio>
#include <sstream>

namespace patina::formats {

namespace fs = std::filesystem;

fs::path vdb_sequence_path(const fs::path& output)
{
    return output.parent_path() / (output.stem().string() + ".frames.toml");
}

std::string vdb_frame_name(const fs::path& output, int frame, std::string_view extension)
{
    char number[16];
    std::snprintf(number, sizeof number, ".%04d", frame);
    std::string name = output.stem().string();
    name += number;
    name += extension;
    return name;
}

std::string vdb_sequence_text(const VdbSequence& sequence)
{
    toml::array frames;
    for (const VdbSequenceFrame& f : sequence.frames) {
        toml::table t{{"frame", f.frame}, {"cycle", f.cycle}, {"volume", f.volume}};
        if (!f.boundary.empty())
            t.insert_or_assign("boundary", f.boundary);
        frames.push_back(std::move(t));
    }
    const toml::table root{
        {"sequence", toml::table{{"format", kVdbSequenceFormat}, {"source", sequence.source}}},
        {"frame", std::move(frames)}};
    std::ostringstream text;
    text << "# The frames of an OpenVDB sequence written by patina-texgen export: the\n"
            "# simulation cycle each numbered frame holds (docs/export.md).\n"
         << root << "\n";
    return text.str();
}

namespace {

    VdbSequence read_root(const fs::path& file, const toml::table& root)
    {
        toml_check_keys(file, root, "", {"sequence", "frame"});
        const toml::table* header = root["sequence"].as_table();
        if (!header)
            toml_fail(file, nullptr, "no [sequence]");
        toml_check_keys(file, *header, "sequence.", {"format", "source"});
        const int64_t format = toml_value<int64_t>(file, *header, "format", "sequence.");
        if (format > kVdbSequenceFormat)
            toml_fail(file, header->get("format"),
                      "sequence format " + std::to_string(format) +
                          " is newer than this program reads (" +
                          std::to_string(kVdbSequenceFormat) + ")");
        VdbSequence sequence;
        sequence.source = toml_value<std::string>(file, *header, "source", "sequence.");
        for (const toml::table* t : toml_table_array(file, root, "frame")) {
            const std::string where = "frame " + std::to_string(sequence.frames.size() + 1) + ": ";
            toml_check_keys(file, *t, where, {"frame", "cycle", "volume", "boundary"});
            VdbSequenceFrame f;
            f.frame = static_cast<int>(toml_value<int64_t>(file, *t, "frame", where));
            f.cycle = static_cast<int>(toml_value<int64_t>(file, *t, "cycle", where));
            f.volume = toml_value<std::string>(file, *t, "volume", where);
            if (t->get("boundary"))
                f.boundary = toml_value<std::string>(file, *t, "boundary", where);
            if (f.frame != static_cast<int>(sequence.frames.size()) + 1)
                toml_fail(file, t->get("frame"),
                          where + "frame numbers run 1, 2, 3, ... in order");
            if (!sequence.frames.empty() && f.cycle <= sequence.frames.back().cycle)
                toml_fail(file, t->get("cycle"), where + "cycles must increase");
            sequence.frames.push_back(std::move(f));
        }
        return sequence;
    }

}  // namespace

VdbSequence read_vdb_sequence(const fs::path& file)
{
    return read_root(file, parse_toml_file(file));
}

VdbSequence parse_vdb_sequence(std::string_view text, const fs::path& source)
{
    return read_root(source, parse_toml_text(text, source));
}

}  // namespace patina::formats
