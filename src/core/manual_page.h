// Where a tool's --help sends its reader: the page of the manual (docs/) that documents it.
#pragma once

#include <string>

namespace patina {

/// The footer of a command's --help naming its manual page, e.g. "texgen-ao.md": the file
/// in docs/ of the sources and in share/doc/patina/ of an installation.
inline std::string manual_footer(const std::string& page)
{
    return "Manual: docs/" + page + " (installed: share/doc/patina/" + page + ")";
}

}  // namespace patina
