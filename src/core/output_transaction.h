// A run's outputs as one transaction. Every file a command writes goes first into a private
// staging folder beside its target, and moves into place only when the whole run has
// succeeded; an error, an exception or a signal before that leaves every earlier output byte
// for byte as it was, and nothing behind.
//
// The staging folder is made by mkdtemp(3) in the nearest existing folder of the target:
// an unpredictable name (`.patina-staging-XXXXXX`), created exclusively, mode 0700. No other
// user can create a file or plant a symlink inside it, so the writers (OpenImageIO, Assimp,
// std::ofstream) may open their files there by name. The final rename(2) replaces the target
// itself, never what a symlink at the target points to.
//
// A command makes one transaction, makes it current (CurrentOutputs) for the run, and
// commits it at the end; the writers of image_io.h, mesh_export.h and the texgen stacks stage
// into the current transaction (StagedOutput). A writer called with no current transaction
// makes one of its own for its one file.
//
//   patina::OutputTransaction outputs;
//   patina::CurrentOutputs scope(outputs);
//   outputs.reserve(out_dir / "ao.exr");     // a bad output location fails before the work
//   ... compute, write_image_atomic(out_dir / "ao.exr", ...), ...
//   outputs.commit();                       // every file moves in, or none does
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace patina {

class OutputTransaction {
public:
    OutputTransaction();
    /// Without commit(): removes the staging folders; the targets are as they were.
    ~OutputTransaction();
    OutputTransaction(const OutputTransaction&) = delete;
    OutputTransaction& operator=(const OutputTransaction&) = delete;

    /// Check that `target` can be written and make its staging folder now, so that a bad
    /// output location (a parent that is a file, a target that is a folder, a folder that
    /// cannot be written) fails before any work is done. Throws std::runtime_error
    /// "cannot write '<target>': ...".
    void reserve(const std::filesystem::path& target);

    /// The path to write `target`'s new content to: a file in the staging folder, its parent
    /// folders made. Writing the same target twice writes the same staged file.
    std::filesystem::path stage(const std::filesystem::path& target);

    /// The file that holds `target`'s content as this run sees it: the staged file when this
    /// transaction wrote one, else `target` itself. Readers of a run's own outputs (a
    /// manifest updated twice) read through this.
    std::filesystem::path current(const std::filesystem::path& target) const;

    /// Delete `target` at commit (a layer file the new stack no longer lists); nothing is
    /// deleted before. A later stage() of the same target cancels the deletion.
    void remove_at_commit(const std::filesystem::path& target);

    /// A writer failed half-way through a staged file: commit() will refuse.
    void mark_failed(const std::string& why);

    /// Move every staged file into place and carry out the deletions, in the order they were
    /// staged. Refuses (throws) when the run was cancelled or a write failed. A signal during
    /// the moves is held until they are done. If one move fails, the moves already made are
    /// undone (the old files are kept as hard links until the end) and the error is thrown.
    void commit();

    /// The same for what is staged so far, and the transaction stays open for more: a long
    /// run's checkpoint goes into place with the outputs it belongs to. Unlike commit() it
    /// does not refuse after a signal (it is how a run keeps its work when stopped).
    void commit_so_far();

    /// Files staged so far (deletions not counted).
    size_t staged_count() const;

private:
    struct Entry;
    struct Staging;
    Staging& staging_for(const std::filesystem::path& target);
    /// The entry of `target`, made (as a write or a deletion) when there is none.
    Entry& entry_for(const std::filesystem::path& target, bool remove);
    Entry* find(const std::filesystem::path& key);
    /// commit()'s work: the moves (undone on failure), then the staging folders removed.
    void move_staged_into_place();
    const Entry* find(const std::filesystem::path& key) const;

    mutable std::mutex mutex_;
    std::vector<std::unique_ptr<Staging>> stagings_;
    std::vector<Entry> entries_;
    std::optional<std::string> failure_;
    bool committed_ = false;
};

/// Makes `transaction` the one every writer of this process stages into while this object
/// lives (one at a time; a nested one throws std::logic_error).
class CurrentOutputs {
public:
    explicit CurrentOutputs(OutputTransaction& transaction);
    ~CurrentOutputs();
    CurrentOutputs(const CurrentOutputs&) = delete;
    CurrentOutputs& operator=(const CurrentOutputs&) = delete;
};

/// The current transaction, or null.
OutputTransaction* current_output_transaction();

/// The file to read `target` from: current_output_transaction()->current(target), or
/// `target` when there is no current transaction.
std::filesystem::path output_to_read(const std::filesystem::path& target);

/// current_output_transaction()->reserve(target); nothing when there is no current one.
void reserve_output(const std::filesystem::path& target);

/// Delete `target` when the current transaction commits (at once when there is none).
void remove_output(const std::filesystem::path& target);

/// One writer's file. Stages `target` in the current transaction or, when there is none or
/// `own_transaction` is set (a cache that must be readable at once), in a transaction of its
/// own that done() commits. Destroyed without done(), it marks the transaction failed: a
/// half-written staged file can never be committed.
class StagedOutput {
public:
    explicit StagedOutput(const std::filesystem::path& target, bool own_transaction = false);
    ~StagedOutput();
    StagedOutput(const StagedOutput&) = delete;
    StagedOutput& operator=(const StagedOutput&) = delete;

    /// Where the writer writes.
    const std::filesystem::path& path() const { return path_; }
    /// The file is complete.
    void done();

private:
    std::optional<OutputTransaction> own_;
    OutputTransaction* transaction_ = nullptr;
    std::filesystem::path target_;
    std::filesystem::path path_;
    bool done_ = false;
};

}  // namespace patina
