#include "libgran/run/frames.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>

namespace gran {

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

std::size_t FrameWriter::frame_bytes() const {
    return sizeof(double) * (1 + 2 * particles_ * std::size_t(box_.dimension));
}
std::size_t FrameWriter::header_bytes() const {
    return sizeof(std::uint64_t) + sizeof(std::int64_t) * particles_;
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

void FrameWriter::append(double time, std::span<const double> positions,
                         std::span<const double> velocities,
                         std::span<const std::int64_t> species) {
    if (!file_) {
        particles_ = species.size();
        open_journal(false);
        const std::uint64_t n = particles_;
        put(&n, sizeof n);
        put(species.data(), species.size_bytes());
    }
    put(&time, sizeof time);
    put(positions.data(), positions.size_bytes());
    put(velocities.data(), velocities.size_bytes());
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
    ar.io(particles_);
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

void FrameWriter::write(ResultGroup root) {
    if (frames_ == 0) return;
    sync();
    std::FILE* in = std::fopen(journal_.c_str(), "rb");
    if (!in) {
        throw OutputError(
            fmt::format("cannot read the frames journal '{}': {}", journal_, std::strerror(errno)));
    }
    auto get = [&](void* data, std::size_t bytes) {
        if (std::fread(data, 1, bytes, in) != bytes) {
            std::fclose(in);
            throw OutputError(fmt::format("the frames journal '{}' ends early", journal_));
        }
    };
    const std::size_t n = particles_, d = std::size_t(box_.dimension);
    std::uint64_t n_file = 0;
    get(&n_file, sizeof n_file);
    std::vector<std::int64_t> species(n);
    get(species.data(), species.size() * sizeof(std::int64_t));

    ResultGroup all = root.file_only().group("particles").group("all");
    ResultGroup b = all.group("box");
    b.attr("dimension", box_.dimension);
    b.attr("boundary", box_.boundary);
    b.array("edges", box_.edges);
    all.array("species", std::span<const std::int64_t>(species));
    struct Quantity {
        h5::Appendable value, time, step;
    };
    auto open_quantity = [&](const std::string& name) {
        ResultGroup q = all.group(name);
        return Quantity{q.series<double>("value", {n, d}), q.series<double>("time"),
                        q.series<std::int64_t>("step")};
    };
    Quantity position = open_quantity("position"), velocity = open_quantity("velocity");
    std::vector<double> r(n * d), v(n * d);
    for (std::size_t f = 0; f < frames_; ++f) {
        double time = 0;
        get(&time, sizeof time);
        get(r.data(), r.size() * sizeof(double));
        get(v.data(), v.size() * sizeof(double));
        const std::int64_t step = std::int64_t(f);
        for (auto [q, values] : {std::pair{&position, std::span<const double>(r)},
                                 std::pair{&velocity, std::span<const double>(v)}}) {
            q->value.append(values);
            q->time.append(std::span<const double>(&time, 1));
            q->step.append(std::span<const std::int64_t>(&step, 1));
        }
    }
    std::fclose(in);
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
