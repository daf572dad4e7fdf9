#pragma once
// Trajectory frames (scene key `output.frames`) under /particles/all in the H5MD layout: position
// and velocity as {value (frames x N x D), time, step}, `box` with the attributes dimension and
// boundary and the dataset edges, and the species of every particle.
//
// While the run goes on, each frame is appended to a journal beside the result (OUT.h5.frames.part:
// the species once, then per frame its time, positions and velocities as raw doubles) and never
// held in memory. A raw append-only file survives a kill whole up to its last complete frame, which
// an HDF5 file being written does not; at each checkpoint the journal is synced and its frame count
// saved, and a resumed run cuts it back to that count. At the end the frames are copied into the
// result file and the journal is removed.
#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include "libgran/core/state_archive.hpp"
#include "libgran/plugins/engine_view.hpp"
#include "libgran/run/result_sink.hpp"
#include "libgran/scene/scene.hpp"

namespace gran {

struct FrameBox {
    std::int64_t dimension = 0;
    std::vector<std::string> boundary;  // per axis: "periodic" or "none"
    std::vector<double> edges;
};

FrameBox frame_box(const Scene& sc);

// OUT.h5.frames.part beside OUT.h5.
std::string frames_journal_path_for(const std::string& output);

class FrameWriter {
  public:
    // At most `limit` frames (none when 0), one every expected_samples / limit measurement
    // samples; the journal is made with the first frame (no frame, no journal).
    FrameWriter(std::string journal, FrameBox box, std::size_t limit, std::size_t expected_samples);
    ~FrameWriter();
    FrameWriter(const FrameWriter&) = delete;
    FrameWriter& operator=(const FrameWriter&) = delete;

    bool due(std::size_t samples_taken) const;
    // One frame: positions and velocities by original particle index (N x D each); `species` (N)
    // is written with the first frame. OutputError naming the journal when it cannot be written.
    void append(double time, std::span<const double> positions, std::span<const double> velocities,
                std::span<const std::int64_t> species);
    std::size_t frames() const { return frames_; }

    // Every frame so far on disk (a checkpoint follows).
    void sync();
    // The frame count; loading cuts the journal back to it (StateMismatch when it is shorter).
    void checkpoint(StateArchive& ar);
    // The frames into root/particles/all (nothing when there are none).
    void write(ResultGroup root);
    // The journal, once the run has ended.
    void remove();

  private:
    std::size_t frame_bytes() const;
    std::size_t header_bytes() const;
    void put(const void* data, std::size_t bytes);
    void open_journal(bool existing);

    std::string journal_;
    FrameBox box_;
    std::size_t limit_;
    std::size_t every_;
    std::size_t frames_ = 0;
    std::size_t particles_ = 0;
    std::FILE* file_ = nullptr;
};

// The particles of a view by original index (the engine may re-sort them), into reused buffers.
template <int D>
void frame_of(const EngineView<D>& view, std::vector<double>& positions,
              std::vector<double>& velocities, std::vector<std::int64_t>& species) {
    const auto& p = view.particles();
    const std::size_t n = p.size();
    positions.resize(n * D);
    velocities.resize(n * D);
    species.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t id = std::size_t(view.id(i));
        species[id] = p.species[i];
        for (int a = 0; a < D; ++a) {
            positions[id * D + std::size_t(a)] = p.r[i][a];
            velocities[id * D + std::size_t(a)] = p.v[i][a];
        }
    }
}

}  // namespace gran
