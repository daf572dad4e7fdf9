#pragma once
// Trajectory frames (scene key `output.frames`) under /particles/all in the H5MD layout: position
// and velocity as {value (frames x N x D), time, step}, `box` with the attributes dimension and
// boundary and the dataset edges, and the species of every particle. Each frame is appended to the
// open result file when it is taken, so frames never pile up in memory.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

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

class FrameWriter {
  public:
    // At most `limit` frames (none when 0), one every expected_samples / limit measurement
    // samples, under root/particles/all (made with the first frame: no frame, no group).
    FrameWriter(ResultGroup root, FrameBox box, std::size_t limit, std::size_t expected_samples);

    bool due(std::size_t samples_taken) const;
    // One frame: positions and velocities by original particle index (N x D each); `species` (N)
    // is written with the first frame.
    void append(double time, std::span<const double> positions, std::span<const double> velocities,
                std::span<const std::int64_t> species);
    std::size_t frames() const { return frames_; }

  private:
    struct Quantity {
        h5::Appendable value, time, step;
    };
    Quantity open_quantity(ResultGroup& all, const std::string& name, std::size_t n);

    ResultGroup root_;
    FrameBox box_;
    std::size_t limit_;
    std::size_t every_;
    std::size_t frames_ = 0;
    std::optional<Quantity> position_, velocity_;
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
