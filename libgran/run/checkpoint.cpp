#include "libgran/run/checkpoint.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "libgran/core/build_info.hpp"
#include "libgran/core/state_archive.hpp"
#include "libgran/run/result_sink.hpp"
#include "libgran/scene/scene.hpp"

namespace gran {

namespace {

namespace fs = std::filesystem;

constexpr const char* kMagic = "gran checkpoint 1\n";

std::uint64_t fnv1a(const char* data, std::size_t n) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (std::size_t k = 0; k < n; ++k) {
        h ^= static_cast<unsigned char>(data[k]);
        h *= 0x100000001b3ull;
    }
    return h;
}

void archive_header(StateArchive& ar, CheckpointHeader& h) {
    ar.section("checkpoint header");
    ar.io(h.code_id);
    ar.io(h.scene_file);
    ar.io(h.scene_text);
    ar.io(h.overrides);
    ar.io(h.resolved);
    ar.io(h.command_line);
    ar.io(h.writes);
}

[[noreturn]] void write_failed(const std::string& path, int err) {
    throw OutputError(
        fmt::format("cannot write the checkpoint '{}': {}", path, std::strerror(err)));
}

// All of `bytes` into a new file, then fsync (a rename after it never exposes unwritten data).
void write_synced(const std::string& path, const std::string& bytes) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) write_failed(path, errno);
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t w = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) {
            const int err = w < 0 ? errno : ENOSPC;
            ::close(fd);
            ::unlink(path.c_str());
            write_failed(path, err);
        }
        done += std::size_t(w);
    }
    if (::fsync(fd) != 0 || ::close(fd) != 0) {
        const int err = errno;
        ::unlink(path.c_str());
        write_failed(path, err);
    }
}

// The rename itself reaches the disk only with the folder's fsync.
void sync_folder(const std::string& path) {
    const fs::path parent = fs::path(path).parent_path();
    const int fd = ::open(parent.empty() ? "." : parent.c_str(), O_RDONLY | O_DIRECTORY);
    if (fd < 0) return;
    ::fsync(fd);
    ::close(fd);
}

std::string emitted(const YAML::Node& n) {
    YAML::Emitter em;
    em << n;
    return em.c_str();
}

// The resolved scene without the keys a resume may change: the checkpoint interval, and the
// threads of a dem run (the same bits for any number).
std::string comparable(const std::string& resolved) {
    YAML::Node n = YAML::Load(resolved);
    if (n["run"] && n["run"]["checkpoint"]) n["run"].remove("checkpoint");
    if (n["engine"] && n["engine"]["threads"]) n["engine"].remove("threads");
    return emitted(n);
}

std::string first_difference(const std::string& a, const std::string& b) {
    std::istringstream ia(a), ib(b);
    std::string la, lb;
    for (int line = 1;; ++line) {
        const bool ga = bool(std::getline(ia, la)), gb = bool(std::getline(ib, lb));
        if (!ga && !gb) return "";
        if (!ga || !gb || la != lb)
            return fmt::format("line {} of the resolved scene: checkpoint '{}', now '{}'", line,
                               ga ? la : "(end)", gb ? lb : "(end)");
    }
}

}  // namespace

std::string checkpoint_path_for(const std::string& output) {
    return output + ".checkpoint";
}

CheckpointHeader checkpoint_header(const Scene& scene, const std::vector<std::string>& command) {
    CheckpointHeader h;
    h.code_id = build_info().code_id();
    h.scene_file = scene.file;
    h.scene_text = scene.source;
    h.overrides = scene.overrides;
    h.resolved = emitted(scene.resolved);
    h.command_line = command;
    return h;
}

void write_checkpoint(const std::string& path, const Checkpoint& checkpoint) {
    StateArchive ar = StateArchive::saver();
    CheckpointHeader h = checkpoint.header;
    archive_header(ar, h);
    std::vector<char> state = checkpoint.state;
    ar.io(state);
    std::string bytes = kMagic;
    bytes.append(ar.bytes().data(), ar.bytes().size());
    const std::uint64_t hash = fnv1a(bytes.data(), bytes.size());
    bytes.append(reinterpret_cast<const char*>(&hash), sizeof hash);
    const std::string tmp = path + ".tmp";
    write_synced(tmp, bytes);
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw OutputError(fmt::format("cannot write the checkpoint '{}': {}", path, ec.message()));
    }
    sync_folder(path);
}

Checkpoint read_checkpoint(const std::string& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) {
        throw CheckpointError(fmt::format(
            "{}: no checkpoint to resume from (a run writes one every run.checkpoint.interval "
            "seconds of wall-clock time and when it is interrupted)",
            path));
    }
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    if (!in) throw CheckpointError(fmt::format("{}: cannot read: {}", path, std::strerror(errno)));
    const std::string bytes = ss.str();
    const std::size_t magic = std::strlen(kMagic);
    if (bytes.size() < magic + 8 || bytes.compare(0, magic, kMagic) != 0)
        throw CheckpointError(fmt::format("{}: not a gran checkpoint", path));
    std::uint64_t hash = 0;
    std::memcpy(&hash, bytes.data() + bytes.size() - 8, 8);
    if (hash != fnv1a(bytes.data(), bytes.size() - 8))
        throw CheckpointError(
            fmt::format("{}: damaged checkpoint (its checksum does not match)", path));
    Checkpoint c;
    try {
        StateArchive ar = StateArchive::loader(
            std::vector<char>(bytes.begin() + std::ptrdiff_t(magic), bytes.end() - 8));
        archive_header(ar, c.header);
        ar.io(c.state);
        if (!ar.at_end()) throw StateMismatch("trailing bytes");
    } catch (const StateMismatch& e) {
        throw CheckpointError(fmt::format("{}: unreadable checkpoint: {}", path, e.what()));
    }
    return c;
}

void check_resumable(const Checkpoint& c, const Scene& scene) {
    const std::string here = build_info().code_id();
    if (c.header.code_id != here) {
        throw CheckpointError(fmt::format(
            "the checkpoint was written by gran {} and this is gran {}: a resumed run is "
            "bit-identical only with the same code; resume with the binary that wrote it, or "
            "start the run again",
            c.header.code_id, here));
    }
    const std::string diff =
        first_difference(comparable(c.header.resolved), comparable(emitted(scene.resolved)));
    if (!diff.empty()) {
        throw CheckpointError(fmt::format(
            "{}: the scene differs from the checkpoint's ({}); resume without a scene (the "
            "checkpoint holds its own) or start the run again",
            scene.file, diff));
    }
}

Scene scene_of(const Checkpoint& c) {
    return load_scene_text(c.header.scene_text, c.header.scene_file, c.header.overrides);
}

}  // namespace gran
