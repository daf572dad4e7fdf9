#include "libgran/run/frames.hpp"

#include <algorithm>

namespace gran {

FrameBox frame_box(const Scene& sc) {
    FrameBox box;
    box.dimension = sc.dimension;
    for (int a = 0; a < sc.dimension; ++a)
        box.boundary.push_back(sc.periodic[std::size_t(a)] ? "periodic" : "none");
    box.edges = sc.box_length;
    return box;
}

FrameWriter::FrameWriter(ResultGroup root, FrameBox box, std::size_t limit,
                         std::size_t expected_samples)
    : root_(std::move(root)),
      box_(std::move(box)),
      limit_(limit),
      every_(limit > 0 ? std::max<std::size_t>(1, expected_samples / limit) : 0) {}

bool FrameWriter::due(std::size_t samples_taken) const {
    return every_ > 0 && samples_taken % every_ == 0 && frames_ < limit_;
}

FrameWriter::Quantity FrameWriter::open_quantity(ResultGroup& all, const std::string& name,
                                                 std::size_t n) {
    ResultGroup q = all.group(name);
    const std::size_t d = std::size_t(box_.dimension);
    return Quantity{q.series<double>("value", {n, d}), q.series<double>("time"),
                    q.series<std::int64_t>("step")};
}

void FrameWriter::append(double time, std::span<const double> positions,
                         std::span<const double> velocities,
                         std::span<const std::int64_t> species) {
    if (!position_) {
        ResultGroup all = root_.file_only().group("particles").group("all");
        ResultGroup b = all.group("box");
        b.attr("dimension", box_.dimension);
        b.attr("boundary", box_.boundary);
        b.array("edges", box_.edges);
        position_ = open_quantity(all, "position", species.size());
        velocity_ = open_quantity(all, "velocity", species.size());
        all.array("species", species);
    }
    const std::int64_t step = std::int64_t(frames_);
    for (auto [q, values] :
         {std::pair{&*position_, positions}, std::pair{&*velocity_, velocities}}) {
        q->value.append(values);
        q->time.append(std::span<const double>(&time, 1));
        q->step.append(std::span<const std::int64_t>(&step, 1));
    }
    ++frames_;
}

}  // namespace gran
