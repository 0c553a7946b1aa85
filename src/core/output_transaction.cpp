#include "core/output_transaction.h"

#include "core/cancel.h"

#include <fmt/format.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include <fcntl.h>
#include <unistd.h>

namespace patina {

namespace fs = std::filesystem;

/// One folder a transaction stages into: `<anchor>/.patina-staging-XXXXXX`.
struct OutputTransaction::Staging {
    fs::path anchor;  ///< the existing folder it sits in (absolute)
    fs::path folder;
};

/// One target: a file to move in, or (remove) a file to delete.
struct OutputTransaction::Entry {
    fs::path key;      ///< absolute, lexically normal: what identifies the target
    fs::path target;   ///< as the caller spelt it, for messages
    fs::path staged;   ///< where the new content is (for a deletion: a name that stays empty)
    Staging* staging = nullptr;
    bool remove = false;
};

namespace {

std::atomic<OutputTransaction*> g_current{nullptr};

fs::path key_of(const fs::path& target)
{
    return fs::absolute(target).lexically_normal();
}

[[noreturn]] void fail(const fs::path& target, const std::string& why)
{
    throw std::runtime_error(fmt::format("cannot write '{}': {}", target.string(), why));
}

/// The nearest existing folder of `key`'s parent; throws when a component is not a folder.
fs::path existing_anchor(const fs::path& key, const fs::path& target)
{
    for (fs::path p = key.parent_path();; p = p.parent_path()) {
        std::error_code ec;
        const fs::file_status status = fs::status(p, ec);
        if (fs::exists(status)) {
            if (!fs::is_directory(status))
                fail(target, fmt::format("'{}' is not a folder", p.string()));
            return p;
        }
        if (p == p.parent_path())
            fail(target, "no existing folder above it");
    }
}

fs::path make_staging_folder(const fs::path& anchor, const fs::path& target)
{
    std::string name = (anchor / ".patina-staging-XXXXXX").string();
    // mkdtemp: an unpredictable name, created exclusively (never an existing file or
    // symlink), mode 0700.
    if (!::mkdtemp(name.data()))
        fail(target, fmt::format("cannot create a staging folder in '{}': {}", anchor.string(),
                                 std::strerror(errno)));
    return name;
}

}  // namespace

OutputTransaction::OutputTransaction() = default;

OutputTransaction::~OutputTransaction()
{
    for (const auto& staging : stagings_) {
        std::error_code ec;
        fs::remove_all(staging->folder, ec);
    }
}

OutputTransaction::Staging& OutputTransaction::staging_for(const fs::path& target)
{
    const fs::path key = key_of(target);
    std::error_code ec;
    if (fs::is_directory(fs::symlink_status(key, ec)))
        fail(target, "it is a folder");
    const fs::path anchor = existing_anchor(key, target);
    for (const auto& staging : stagings_)
        if (staging->anchor == anchor)
            return *staging;
    stagings_.push_back(std::make_unique<Staging>(Staging{anchor, make_staging_folder(anchor, target)}));
    return *stagings_.back();
}

OutputTransaction::Entry* OutputTransaction::find(const fs::path& key)
{
    for (Entry& e : entries_)
        if (e.key == key)
            return &e;
    return nullptr;
}

const OutputTransaction::Entry* OutputTransaction::find(const fs::path& key) const
{
    for (const Entry& e : entries_)
        if (e.key == key)
            return &e;
    return nullptr;
}

void OutputTransaction::reserve(const fs::path& target)
{
    const std::lock_guard lock(mutex_);
    staging_for(target);
}

OutputTransaction::Entry& OutputTransaction::entry_for(const fs::path& target, bool remove)
{
    const fs::path key = key_of(target);
    if (Entry* entry = find(key))
        return *entry;
    Staging& staging = staging_for(target);
    entries_.push_back({key, target, staging.folder / key.lexically_relative(staging.anchor),
                        &staging, remove});
    return entries_.back();
}

fs::path OutputTransaction::stage(const fs::path& target)
{
    const std::lock_guard lock(mutex_);
    if (committed_)
        throw std::logic_error("OutputTransaction::stage after commit");
    Entry* entry = &entry_for(target, false);
    entry->remove = false;
    std::error_code ec;
    fs::create_directories(entry->staged.parent_path(), ec);
    if (ec)
        fail(target, fmt::format("cannot create '{}': {}", entry->staged.parent_path().string(),
                                 ec.message()));
    return entry->staged;
}

fs::path OutputTransaction::current(const fs::path& target) const
{
    const std::lock_guard lock(mutex_);
    const Entry* entry = find(key_of(target));
    return entry ? entry->staged : target;
}

void OutputTransaction::remove_at_commit(const fs::path& target)
{
    const std::lock_guard lock(mutex_);
    Entry& entry = entry_for(target, true);
    std::error_code ec;
    fs::remove(entry.staged, ec);  // a version this run staged earlier
    entry.remove = true;
}

void OutputTransaction::mark_failed(const std::string& why)
{
    const std::lock_guard lock(mutex_);
    if (!failure_)
        failure_ = why;
}

size_t OutputTransaction::staged_count() const
{
    const std::lock_guard lock(mutex_);
    size_t n = 0;
    for (const Entry& e : entries_)
        n += !e.remove;
    return n;
}

namespace {

/// What commit() did to one target, so that it can be undone.
struct Move {
    fs::path key;
    fs::path backup;                 ///< the old file, kept here (empty: there was none)
    std::vector<fs::path> made_dirs; ///< parent folders created for it, outermost first
};

std::vector<fs::path> make_parents(const fs::path& key)
{
    std::vector<fs::path> missing;
    for (fs::path p = key.parent_path(); !fs::exists(p); p = p.parent_path())
        missing.insert(missing.begin(), p);
    for (const fs::path& p : missing) {
        std::error_code ec;
        fs::create_directory(p, ec);
        if (ec)
            throw fs::filesystem_error("cannot create the folder", p, ec);
    }
    return missing;
}

/// Keep the old file at `backup`: a hard link when the file system allows one (the target
/// is then replaced in one rename, never missing), else moved aside.
void keep_old(const fs::path& key, const fs::path& backup)
{
    // linkat without AT_SYMLINK_FOLLOW: a symlink at the target is kept as a symlink.
    if (::linkat(AT_FDCWD, key.c_str(), AT_FDCWD, backup.c_str(), 0) == 0)
        return;
    fs::rename(key, backup);
}

void undo(const std::vector<Move>& moves)
{
    for (auto m = moves.rbegin(); m != moves.rend(); ++m) {
        std::error_code ec;
        if (!m->backup.empty())
            fs::rename(m->backup, m->key, ec);
        else
            fs::remove(m->key, ec);
        for (auto d = m->made_dirs.rbegin(); d != m->made_dirs.rend(); ++d)
            fs::remove(*d, ec);  // only when empty
    }
}

}  // namespace

void OutputTransaction::commit()
{
    const std::lock_guard lock(mutex_);
    if (committed_)
        throw std::logic_error("OutputTransaction::commit twice");
    throw_if_cancelled();
    move_staged_into_place();
    committed_ = true;
}

void OutputTransaction::commit_so_far()
{
    const std::lock_guard lock(mutex_);
    if (committed_)
        throw std::logic_error("OutputTransaction::commit_so_far after commit");
    move_staged_into_place();
}

void OutputTransaction::move_staged_into_place()
{
    if (failure_)
        throw std::runtime_error(fmt::format("{}; no output was written", *failure_));
    for (const Entry& e : entries_) {
        std::error_code ec;
        if (!e.remove && fs::is_directory(fs::symlink_status(e.key, ec)))
            fail(e.target, "it is a folder; no output was written");
        if (!e.remove && !fs::exists(e.staged, ec))
            fail(e.target, "its writer produced no file; no output was written");
    }

    const HoldTermination hold;
    std::vector<Move> moves;
    size_t index = 0;
    for (const Entry& e : entries_) {
        const fs::path backup = e.staging->folder / fmt::format(".old-{}", index++);
        try {
            std::error_code ec;
            const bool had_old = fs::exists(fs::symlink_status(e.key, ec));
            if (e.remove) {
                if (had_old) {
                    fs::rename(e.key, backup);
                    moves.push_back({e.key, backup, {}});
                }
                continue;
            }
            Move move{e.key, {}, make_parents(e.key)};
            if (had_old) {
                keep_old(e.key, backup);
                move.backup = backup;
            }
            try {
                fs::rename(e.staged, e.key);
            } catch (...) {
                moves.push_back(move);
                throw;
            }
            moves.push_back(move);
        } catch (const std::exception& error) {
            undo(moves);
            fail(e.target, fmt::format("{}; the earlier outputs were restored", error.what()));
        }
    }
    entries_.clear();
    for (const auto& staging : stagings_) {
        std::error_code ec;
        fs::remove_all(staging->folder, ec);
    }
    stagings_.clear();
}

CurrentOutputs::CurrentOutputs(OutputTransaction& transaction)
{
    OutputTransaction* expected = nullptr;
    if (!g_current.compare_exchange_strong(expected, &transaction))
        throw std::logic_error("CurrentOutputs: a transaction is current already");
}

CurrentOutputs::~CurrentOutputs() { g_current.store(nullptr); }

OutputTransaction* current_output_transaction() { return g_current.load(); }

fs::path output_to_read(const fs::path& target)
{
    OutputTransaction* t = current_output_transaction();
    return t ? t->current(target) : target;
}

void reserve_output(const fs::path& target)
{
    if (OutputTransaction* t = current_output_transaction())
        t->reserve(target);
}

void remove_output(const fs::path& target)
{
    if (OutputTransaction* t = current_output_transaction()) {
        t->remove_at_commit(target);
        return;
    }
    std::error_code ec;
    fs::remove(target, ec);
}

StagedOutput::StagedOutput(const fs::path& target, bool own_transaction) : target_(target)
{
    transaction_ = own_transaction ? nullptr : current_output_transaction();
    if (!transaction_)
        transaction_ = &own_.emplace();
    path_ = transaction_->stage(target);
}

StagedOutput::~StagedOutput()
{
    if (done_ || own_)
        return;  // an own transaction removes its staging folder itself
    try {
        transaction_->mark_failed(fmt::format("writing '{}' failed", target_.string()));
    } catch (...) {
    }
}

void StagedOutput::done()
{
    done_ = true;
    if (own_)
        own_->commit();
    else
        signal_point("write");
}

}  // namespace patina
