#pragma once
// Checkpoint files (`run.checkpoint.interval`, `gran run --resume OUT.h5`; docs/reliability.md).
// OUT.h5.checkpoint holds everything a run needs to continue bit for bit: the code that wrote it,
// the scene (the file's text, its --set overrides and the resolved scene), and the state saved by
// the run loop, the engine, every driver and every observable (libgran/core/state_archive.hpp).
//
// Layout: the line "gran checkpoint 1\n", then one StateArchive of the header and the state, then
// the FNV-1a 64-bit hash of everything before it (a truncated or damaged file is refused, never
// misread). Written atomically: OUT.h5.checkpoint.tmp, fsync, rename over the previous checkpoint,
// fsync of the folder; a kill at any moment leaves the previous or the new checkpoint whole.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace gran {

struct Scene;

// A checkpoint that cannot be used (missing, damaged, other code, other scene): the message says
// which and what to do; `gran run --resume` exits 1.
class CheckpointError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

struct CheckpointHeader {
    std::string code_id;  // gran::build_info().code_id() of the writer
    std::string scene_file;
    std::string scene_text;  // the scene file as it was read
    std::vector<std::string> overrides;
    std::string resolved;  // the resolved scene (YAML), what a resumed run must reproduce
    std::vector<std::string> command_line;
    std::uint64_t writes = 0;  // checkpoints written by this run so far (this one included)
};

struct Checkpoint {
    CheckpointHeader header;
    std::vector<char> state;
};

// OUT.h5.checkpoint beside OUT.h5.
std::string checkpoint_path_for(const std::string& output);

// The header of a scene's run (code id, scene text, overrides, resolved scene).
CheckpointHeader checkpoint_header(const Scene& scene, const std::vector<std::string>& command);

// Atomic write (OutputError naming the path and the cause on failure; the previous checkpoint is
// then intact).
void write_checkpoint(const std::string& path, const Checkpoint& checkpoint);

// Reads and verifies (CheckpointError: missing, not a checkpoint, damaged).
Checkpoint read_checkpoint(const std::string& path);

// Refuses (CheckpointError) a checkpoint written by other code, or for another scene than
// `scene` (the scene rebuilt from the checkpoint, or one given on the command line): names the
// first line of the resolved scenes that differs.
void check_resumable(const Checkpoint& checkpoint, const Scene& scene);

// The scene of a checkpoint, parsed again from the text it was read from.
Scene scene_of(const Checkpoint& checkpoint);

}  // namespace gran
