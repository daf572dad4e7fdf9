#pragma once
// Trajectory frames (scene key `output.frames`): while the run goes on, each frame is appended to
// a journal beside the result (OUT.h5.frames.part: a header with the species, then per frame its
// time, step, positions, velocities, periodic images and angular velocities as raw numbers) and
// never held in memory. A raw append-only file survives a kill whole up to its last complete
// frame, which an HDF5 file being written does not; at each checkpoint the journal is synced and
// its frame count saved, and a resumed run cuts it back to that count. At the end the frames
// become the H5MD trajectory file with its XDMF sidecar (libgran/run/trajectory.hpp) and the
// journal is removed.
#include <array>
#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include "libgran/core/state_archive.hpp"
#include "libgran/plugins/engine_view.hpp"
#include "libgran/scene/scene.hpp"

namespace gran {

struct FrameBox {
    std::int64_t dimension = 0;
    std::vector<std::string> boundary;  // per axis: "periodic" or "none"
    std::vector<double> edges;
    bool any_periodic() const;
};

FrameBox frame_box(const Scene& sc);

// OUT.h5.frames.part beside OUT.h5.
std::string frames_journal_path_for(const std::string& output);

// One frame, by original particle index (the engine may re-sort its storage).
struct Frame {
    double time = 0;
    std::int64_t step = 0;              // the engine's events or steps so far
    std::vector<double> positions;      // N x D, wrapped into the box
    std::vector<double> velocities;     // N x D
    std::vector<std::int64_t> species;  // N
    std::vector<std::int32_t> images;   // N x D periodic images (zero on bounded axes)
    std::vector<double> angular;        // N x (1 in 2D, 3 in 3D); empty unless grains rotate
};

// What a journal holds per frame besides time, step, positions and velocities.
struct FrameLayout {
    std::size_t particles = 0;
    std::size_t dimension = 0;
    bool images = false;
    std::size_t angular_width = 0;  // 0: no angular velocities
};

class FrameWriter {
  public:
    // At most `limit` frames (none when 0), one every expected_samples / limit measurement
    // samples; the journal is made with the first frame (no frame, no journal).
    FrameWriter(std::string journal, FrameBox box, std::size_t limit, std::size_t expected_samples);
    ~FrameWriter();
    FrameWriter(const FrameWriter&) = delete;
    FrameWriter& operator=(const FrameWriter&) = delete;

    bool due(std::size_t samples_taken) const;
    // One frame; the species go into the journal's header with the first. OutputError naming
    // the journal when it cannot be written.
    void append(const Frame& frame);
    std::size_t frames() const { return frames_; }
    const std::string& journal() const { return journal_; }
    const FrameBox& box() const { return box_; }
    const FrameLayout& layout() const { return layout_; }

    // Every frame so far on disk (a checkpoint follows).
    void sync();
    // The frame count and layout; loading cuts the journal back to the count (StateMismatch
    // when it is shorter).
    void checkpoint(StateArchive& ar);
    // Reads the journal back: f(frame) for every frame in order (OutputError when it ends early).
    template <class F>
    void for_each(F&& f);
    // The journal, once the run has ended.
    void remove();

  private:
    std::size_t frame_bytes() const;
    std::size_t header_bytes() const;
    void put(const void* data, std::size_t bytes);
    void open_journal(bool existing);
    std::FILE* open_for_reading(std::vector<std::int64_t>& species);
    void read_frame(std::FILE* in, Frame& frame);

    std::string journal_;
    FrameBox box_;
    std::size_t limit_;
    std::size_t every_;
    std::size_t frames_ = 0;
    FrameLayout layout_;
    std::FILE* file_ = nullptr;
};

template <class F>
void FrameWriter::for_each(F&& f) {
    if (frames_ == 0) return;
    sync();
    Frame frame;
    std::FILE* in = open_for_reading(frame.species);
    try {
        for (std::size_t k = 0; k < frames_; ++k) {
            read_frame(in, frame);
            f(frame);
        }
    } catch (...) {
        std::fclose(in);
        throw;
    }
    std::fclose(in);
}

// The particles of a view by original index, into `frame`'s reused buffers.
template <int D>
void frame_of(const EngineView<D>& view, std::int64_t step, Frame& frame) {
    const auto& p = view.particles();
    const std::size_t n = p.size();
    frame.time = view.now();
    frame.step = step;
    frame.positions.resize(n * D);
    frame.velocities.resize(n * D);
    frame.species.resize(n);
    frame.images.resize(n * D);
    constexpr std::size_t wa = D == 2 ? 1 : 3;
    frame.angular.resize(p.rotating() ? n * wa : 0);
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t id = std::size_t(view.id(i));
        frame.species[id] = p.species[i];
        for (int a = 0; a < D; ++a) {
            frame.positions[id * D + std::size_t(a)] = p.r[i][a];
            frame.velocities[id * D + std::size_t(a)] = p.v[i][a];
            frame.images[id * D + std::size_t(a)] = p.image[i][std::size_t(a)];
        }
        if (!p.rotating()) continue;
        if constexpr (D == 2) {
            frame.angular[id] = p.w[i];
        } else {
            for (std::size_t a = 0; a < 3; ++a) frame.angular[id * 3 + a] = p.w[i][int(a)];
        }
    }
}

}  // namespace gran
