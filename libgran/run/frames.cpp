#include "libgran/run/frames.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "libgran/run/result_sink.hpp"

namespace gran {

bool FrameBox::any_periodic() const {
    return std::find(boundary.begin(), boundary.end(), "periodic") != boundary.end();
}

FrameBox frame_box(const Scene& sc) {
    FrameBox box;
    box.dimension = sc.dimension;
    for (int a = 0; a < sc.dimension; ++a)
        box.boundary.push_back(sc.periodic[std::size_t(a)] ? "periodic" : "none");
    box.edges = sc.box_length;
    return box;
}

std::string frames_journal_path_for(const std::string& output) {
    return output + ".frames.part";
}

FrameWriter::FrameWriter(std::string journal, FrameBox box, std::size_t limit,
                         std::size_t expected_samples)
    : journal_(std::move(journal)),
      box_(std::move(box)),
      limit_(limit),
      every_(limit > 0 ? std::max<std::size_t>(1, expected_samples / limit) : 0) {}

FrameWriter::~FrameWriter() {
    if (file_) std::fclose(file_);
}

bool FrameWriter::due(std::size_t samples_taken) const {
    return every_ > 0 && samples_taken % every_ == 0 && frames_ < limit_;
}

// Per frame: time, step, positions, velocities, [images], [angular velocities].
std::size_t FrameWriter::frame_bytes() const {
    const std::size_t nd = layout_.particles * layout_.dimension;
    return sizeof(double) + sizeof(std::int64_t) + 2 * nd * sizeof(double) +
           (layout_.images ? nd * sizeof(std::int32_t) : 0) +
           layout_.particles * layout_.angular_width * sizeof(double);
}
// Header: particles, images flag, angular width, species.
std::size_t FrameWriter::header_bytes() const {
    return 3 * sizeof(std::uint64_t) + sizeof(std::int64_t) * layout_.particles;
}

void FrameWriter::put(const void* data, std::size_t bytes) {
    if (std::fwrite(data, 1, bytes, file_) != bytes) {
        throw OutputError(
            fmt::format("cannot write the frames to '{}': {}", journal_, std::strerror(errno)));
    }
}

void FrameWriter::open_journal(bool existing) {
    file_ = std::fopen(journal_.c_str(), existing ? "r+b" : "wb");
    if (!file_) {
        throw OutputError(
            fmt::format("cannot open the frames journal '{}': {}", journal_, std::strerror(errno)));
    }
}

void FrameWriter::append(const Frame& f) {
    if (!file_) {
        layout_.particles = f.species.size();
        layout_.dimension = std::size_t(box_.dimension);
        layout_.images = box_.any_periodic();
        layout_.angular_width = layout_.particles ? f.angular.size() / layout_.particles : 0;
        open_journal(false);
        const std::uint64_t header[3] = {layout_.particles, layout_.images ? 1u : 0u,
                                         layout_.angular_width};
        put(header, sizeof header);
        put(f.species.data(), f.species.size() * sizeof(std::int64_t));
    }
    const std::size_t nd = layout_.particles * layout_.dimension;
    put(&f.time, sizeof f.time);
    put(&f.step, sizeof f.step);
    put(f.positions.data(), nd * sizeof(double));
    put(f.velocities.data(), nd * sizeof(double));
    if (layout_.images) put(f.images.data(), nd * sizeof(std::int32_t));
    if (layout_.angular_width) put(f.angular.data(), f.angular.size() * sizeof(double));
    ++frames_;
}

void FrameWriter::sync() {
    if (!file_) return;
    if (std::fflush(file_) != 0 || ::fdatasync(::fileno(file_)) != 0) {
        throw OutputError(
            fmt::format("cannot write the frames to '{}': {}", journal_, std::strerror(errno)));
    }
}

void FrameWriter::checkpoint(StateArchive& ar) {
    ar.section("frames");
    ar.io(frames_);
    ar.io(layout_.particles);
    ar.io(layout_.dimension);
    ar.io(layout_.images);
    ar.io(layout_.angular_width);
    if (!ar.loading() || frames_ == 0) return;
    // Resuming: the frames the checkpoint counted are in the journal (synced before it was
    // written); anything after them was written by the killed run and is cut off.
    const std::size_t want = header_bytes() + frames_ * frame_bytes();
    std::error_code ec;
    const auto size = std::filesystem::file_size(journal_, ec);
    if (ec || size < want) {
        throw StateMismatch(fmt::format(
            "the frames journal '{}' holds less than the checkpoint's {} frames ({})", journal_,
            frames_, ec ? ec.message() : fmt::format("{} of {} bytes", size, want)));
    }
    std::filesystem::resize_file(journal_, want, ec);
    if (ec) throw StateMismatch(fmt::format("cannot cut '{}': {}", journal_, ec.message()));
    open_journal(true);
    std::fseek(file_, 0, SEEK_END);
}

namespace {
void get(std::FILE* in, void* data, std::size_t bytes, const std::string& journal) {
    if (bytes > 0 && std::fread(data, 1, bytes, in) != bytes)
        throw OutputError(fmt::format("the frames journal '{}' ends early", journal));
}
}  // namespace

std::FILE* FrameWriter::open_for_reading(std::vector<std::int64_t>& species) {
    std::FILE* in = std::fopen(journal_.c_str(), "rb");
    if (!in) {
        throw OutputError(
            fmt::format("cannot read the frames journal '{}': {}", journal_, std::strerror(errno)));
    }
    std::uint64_t header[3] = {};
    species.resize(layout_.particles);
    try {
        get(in, header, sizeof header, journal_);
        get(in, species.data(), species.size() * sizeof(std::int64_t), journal_);
    } catch (...) {
        std::fclose(in);
        throw;
    }
    return in;
}

void FrameWriter::read_frame(std::FILE* in, Frame& f) {
    const std::size_t nd = layout_.particles * layout_.dimension;
    f.positions.resize(nd);
    f.velocities.resize(nd);
    f.images.assign(nd, 0);
    f.angular.resize(layout_.particles * layout_.angular_width);
    get(in, &f.time, sizeof f.time, journal_);
    get(in, &f.step, sizeof f.step, journal_);
    get(in, f.positions.data(), nd * sizeof(double), journal_);
    get(in, f.velocities.data(), nd * sizeof(double), journal_);
    if (layout_.images) get(in, f.images.data(), nd * sizeof(std::int32_t), journal_);
    get(in, f.angular.data(), f.angular.size() * sizeof(double), journal_);
}

void FrameWriter::remove() {
    if (file_) {
        std::fclose(file_);
        file_ = nullptr;
    }
    std::error_code ec;
    std::filesystem::remove(journal_, ec);
}

}  // namespace gran
