// Reading a constant from a shared library without loading it. dlopen runs a library's
// constructors before the host can look at anything, so the plugin host reads the ABI
// version symbol straight from the ELF file first and refuses a wrong version unrun.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string_view>

namespace patina {

/// The 32-bit integer that the exported dynamic symbol `name` of the ELF shared library
/// `file` points to, read from the file (section headers, .dynsym, the symbol's section).
/// nullopt when the library exports no such symbol. Throws std::runtime_error "<why>" when
/// the file is not a 64-bit little-endian ELF shared object that can be read this way.
std::optional<int32_t> read_elf_int_symbol(const std::filesystem::path& file,
                                           std::string_view name);

}  // namespace patina
