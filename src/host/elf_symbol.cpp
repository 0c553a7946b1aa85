#include "host/elf_symbol.h"

#include <fmt/format.h>

#include <elf.h>

#include <cstring>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace patina {

namespace {

    /// Larger files are not plugins (the bundled ones are well under 1 MiB).
    constexpr std::uintmax_t kMaxLibraryBytes = 1u << 30;

    [[noreturn]] void fail(const std::string& why) { throw std::runtime_error(why); }

    /// The object of type T at `offset` of `bytes`, bounds-checked.
    template <class T>
    T read_at(const std::vector<char>& bytes, uint64_t offset, const char* what)
    {
        if (offset > bytes.size() || bytes.size() - offset < sizeof(T))
            fail(fmt::format("its {} lies outside the file", what));
        T value;
        std::memcpy(&value, bytes.data() + offset, sizeof(T));
        return value;
    }

}  // namespace

std::optional<int32_t> read_elf_int_symbol(const std::filesystem::path& file,
                                           std::string_view name)
{
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(file, ec);
    if (ec)
        fail(ec.message());
    if (size > kMaxLibraryBytes)
        fail(fmt::format("{} bytes is larger than any plugin", size));
    std::vector<char> bytes(static_cast<size_t>(size));
    std::ifstream in(file, std::ios::binary);
    if (!in.read(bytes.data(), static_cast<std::streamsize>(bytes.size())))
        fail("cannot read the file");

    // ELF header: 64-bit, little-endian, a shared object (System V gABI, "ELF Header").
    if (bytes.size() < EI_NIDENT || std::memcmp(bytes.data(), ELFMAG, SELFMAG) != 0)
        fail("not an ELF file");
    const auto header = read_at<Elf64_Ehdr>(bytes, 0, "ELF header");
    if (header.e_ident[EI_CLASS] != ELFCLASS64 || header.e_ident[EI_DATA] != ELFDATA2LSB)
        fail("not a 64-bit little-endian ELF file");
    if (header.e_type != ET_DYN)
        fail("not a shared library (ELF type is not ET_DYN)");
    if (header.e_shnum == 0 || header.e_shentsize != sizeof(Elf64_Shdr))
        fail("it has no section headers to find its symbols in");

    auto section = [&](size_t index) {
        if (index >= header.e_shnum)
            fail("a section index is out of range");
        return read_at<Elf64_Shdr>(bytes, header.e_shoff + index * sizeof(Elf64_Shdr),
                                   "section header");
    };

    // The dynamic symbol table and its string table (sh_link).
    for (size_t s = 0; s < header.e_shnum; ++s) {
        const Elf64_Shdr symbols = section(s);
        if (symbols.sh_type != SHT_DYNSYM)
            continue;
        if (symbols.sh_entsize != sizeof(Elf64_Sym))
            fail("its dynamic symbol table has an unexpected entry size");
        const Elf64_Shdr strings = section(symbols.sh_link);
        const size_t count = symbols.sh_size / sizeof(Elf64_Sym);
        for (size_t i = 0; i < count; ++i) {
            const auto sym = read_at<Elf64_Sym>(bytes, symbols.sh_offset + i * sizeof(Elf64_Sym),
                                                "symbol");
            if (sym.st_name >= strings.sh_size || sym.st_shndx == SHN_UNDEF)
                continue;
            const char* text = bytes.data() + strings.sh_offset + sym.st_name;
            const size_t room = strings.sh_size - sym.st_name;
            if (strings.sh_offset + strings.sh_size > bytes.size() ||
                strnlen(text, room) != name.size() || name.compare(0, name.size(), text, name.size()) != 0)
                continue;
            if (ELF64_ST_TYPE(sym.st_info) != STT_OBJECT || sym.st_size < sizeof(int32_t))
                fail(fmt::format("its symbol '{}' is not a 32-bit integer object", name));
            if (sym.st_shndx >= SHN_LORESERVE)
                fail(fmt::format("its symbol '{}' is not in a section", name));
            // The symbol's value is a virtual address in its section: the file offset is
            // the section's offset plus the distance from the section's address.
            const Elf64_Shdr home = section(sym.st_shndx);
            if (home.sh_type == SHT_NOBITS)
                return 0;  // in .bss: zero-initialised
            if (sym.st_value < home.sh_addr || sym.st_value - home.sh_addr + 4 > home.sh_size)
                fail(fmt::format("its symbol '{}' lies outside its section", name));
            return read_at<int32_t>(bytes, home.sh_offset + (sym.st_value - home.sh_addr),
                                    "symbol value");
        }
        return std::nullopt;
    }
    fail("it has no dynamic symbol table");
}

}  // namespace patina
