#include "texgen/stone/stone_checkpoint.h"

#include "core/file_fingerprint.h"
#include "core/image_io.h"

#include <fmt/format.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <type_traits>

namespace patina::texgen::stone {

namespace fs = std::filesystem;

namespace {

    constexpr std::string_view kMagic = "patina stone checkpoint\n";
    constexpr uint32_t kVersion = 1;

    /// Every field of the state the cycles change, in the file's order. `State` is
    /// StoneState or const StoneState; `v` is called with a name and the field.
    template <class State, class Visitor>
    void visit_fields(State& st, Visitor&& v)
    {
        v("density", st.density);
        v("porosity", st.porosity);
        v("permeability", st.permeability);
        v("head", st.head);
        v("moisture", st.moisture);
        v("pressure", st.pressure);
        for (int m = 0; m < kSpecies; ++m) {
            v(fmt::format("solid.{}", m), st.solid[m]);
            v(fmt::format("dissolved.{}", m), st.dissolved[m]);
            v(fmt::format("crust.{}", m), st.crust[m]);
            v(fmt::format("concentration.{}", m), st.concentration[m]);
            v(fmt::format("ghost_flux.{}", m), st.ghost_flux[m]);
        }
        for (auto [name, halo] : {std::pair{"density_halo", &st.density_halo},
                                  std::pair{"pressure_halo", &st.pressure_halo},
                                  std::pair{"moisture_halo", &st.moisture_halo},
                                  std::pair{"concentration_halo", &st.concentration_halo}}) {
            v(fmt::format("{}.rows", name), halo->row_changed);
            v(fmt::format("{}.layers", name), halo->layer_changed);
            v(fmt::format("{}.filled", name), halo->filled_layers);
        }
        v("concentration_zero", st.concentration_zero);
        v("ghost_hit", st.ghost_hit);
        v("ghost_hits", st.ghost_hits);
        v("seam_mark", st.seam_mark);
        v("seam_due", st.seam_due);
        v("full_stencil", st.full_stencil);
        v("black", st.black);
        v("decay", st.decay);
        v("wet_time", st.wet_time);
        v("flags", st.flags);
        v("active_depth", st.active_depth);
        v("surface_depth", st.surface_depth);
        v("pressure_preset_depth", st.pressure_preset_depth);
        v("surface_layer", st.surface_layer);
    }

    class Writer {
    public:
        template <class T>
        void value(const T& x)
        {
            static_assert(std::is_arithmetic_v<T>);
            bytes_.append(reinterpret_cast<const char*>(&x), sizeof x);
        }
        void text(std::string_view s)
        {
            value(static_cast<uint32_t>(s.size()));
            bytes_.append(s);
        }
        template <class T>
        void array(const std::vector<T>& v)
        {
            value(static_cast<uint64_t>(v.size()));
            bytes_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
        }
        template <class T>
        void operator()(const std::string& name, const std::vector<T>& v)
        {
            text(name);
            value(static_cast<uint32_t>(sizeof(T)));
            array(v);
        }
        template <class T>
        void operator()(const std::string& name, const std::vector<std::vector<T>>& v)
        {
            text(name);
            value(static_cast<uint32_t>(0));  // 0: a list of arrays follows
            value(static_cast<uint64_t>(v.size()));
            for (const std::vector<T>& inner : v) {
                value(static_cast<uint32_t>(sizeof(T)));
                array(inner);
            }
        }
        std::string& bytes() { return bytes_; }

    private:
        std::string bytes_;
    };

    class Reader {
    public:
        Reader(const fs::path& file, std::string bytes) : file_(file), bytes_(std::move(bytes)) {}

        [[noreturn]] void fail(const std::string& what) const
        {
            throw std::runtime_error(
                fmt::format("stone checkpoint '{}': {}", file_.string(), what));
        }
        template <class T>
        T value()
        {
            T x;
            take(&x, sizeof x);
            return x;
        }
        std::string text()
        {
            const uint32_t n = value<uint32_t>();
            std::string s(n, '\0');
            take(s.data(), n);
            return s;
        }
        template <class T>
        void array(std::vector<T>& v, const std::string& name)
        {
            if (value<uint32_t>() != sizeof(T))
                fail(fmt::format("field '{}' has another element size", name));
            const uint64_t n = value<uint64_t>();
            if (n > (bytes_.size() - at_) / sizeof(T))
                fail(fmt::format("field '{}' runs past the end of the file", name));
            v.resize(static_cast<size_t>(n));
            take(v.data(), v.size() * sizeof(T));
        }
        void expect_name(const std::string& name)
        {
            const std::string got = text();
            if (got != name)
                fail(fmt::format("expected the field '{}', found '{}'", name, got));
        }
        template <class T>
        void operator()(const std::string& name, std::vector<T>& v)
        {
            expect_name(name);
            array(v, name);
        }
        template <class T>
        void operator()(const std::string& name, std::vector<std::vector<T>>& v)
        {
            expect_name(name);
            if (value<uint32_t>() != 0)
                fail(fmt::format("field '{}' is not a list of arrays", name));
            const uint64_t n = value<uint64_t>();
            if (n > bytes_.size() - at_)
                fail(fmt::format("field '{}' runs past the end of the file", name));
            v.resize(static_cast<size_t>(n));
            for (std::vector<T>& inner : v)
                array(inner, name);
        }
        bool done() const { return at_ == bytes_.size(); }

    private:
        void take(void* out, size_t n)
        {
            if (n > bytes_.size() - at_)
                fail("the file ends early");
            std::memcpy(out, bytes_.data() + at_, n);
            at_ += n;
        }

        fs::path file_;
        std::string bytes_;
        size_t at_ = 0;
    };

}  // namespace

void write_stone_checkpoint(const fs::path& file, const StoneState& st, const std::string& setup)
{
    Writer w;
    w.bytes().append(kMagic);
    w.value(kVersion);
    w.text(setup);
    w.value(static_cast<uint64_t>(st.lattice->grid().cell_count()));
    w.value(static_cast<int32_t>(st.cycles_done));
    w.value(static_cast<int32_t>(st.transport_interval));
    w.value(st.time);
    w.value(st.dt);
    w.value(static_cast<uint8_t>(st.pressure_preset_wet));
    visit_fields(st, w);
    // The checksum of everything before: a damaged or cut file is refused, not resumed.
    const std::string sum = bytes_fingerprint(w.bytes());
    w.bytes().append(sum);
    write_file_atomic(file, {w.bytes()}, "stone checkpoint");
}

void read_stone_checkpoint(const fs::path& file, StoneState& st, const std::string& setup)
{
    std::ifstream in(file, std::ios::binary);
    if (!in)
        throw std::runtime_error(fmt::format("stone checkpoint '{}': cannot be read", file.string()));
    std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    constexpr size_t kSum = 16;  // the fingerprint's hex digits
    if (bytes.size() < kMagic.size() + kSum || bytes.compare(0, kMagic.size(), kMagic) != 0)
        throw std::runtime_error(fmt::format(
            "stone checkpoint '{}': not a stone checkpoint (written by `patina-texgen stone "
            "--checkpoint`)", file.string()));
    const std::string sum = bytes.substr(bytes.size() - kSum);
    bytes.resize(bytes.size() - kSum);
    if (bytes_fingerprint(bytes) != sum)
        throw std::runtime_error(fmt::format(
            "stone checkpoint '{}': damaged (its checksum does not match its contents)",
            file.string()));
    Reader r(file, bytes.substr(kMagic.size()));
    if (const uint32_t version = r.value<uint32_t>(); version != kVersion)
        r.fail(fmt::format("version {}, this program reads version {}", version, kVersion));
    if (const std::string written = r.text(); written != setup)
        r.fail(fmt::format("written by a run with other inputs (setup {}, this run's {}): the "
                           "mesh, the maps, the quarry, the lattice and the parameters must be "
                           "the ones it was started with",
                           written, setup));
    if (r.value<uint64_t>() != st.lattice->grid().cell_count())
        r.fail("written for another slab lattice");
    st.cycles_done = r.value<int32_t>();
    st.transport_interval = r.value<int32_t>();
    st.time = r.value<double>();
    st.dt = r.value<double>();
    st.pressure_preset_wet = r.value<uint8_t>() != 0;
    visit_fields(st, r);
    if (!r.done())
        r.fail("bytes after the last field");
}

}  // namespace patina::texgen::stone
