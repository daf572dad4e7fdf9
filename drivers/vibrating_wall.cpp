// Vibrating wall of infinite mass with a prescribed waveform (McNamara & Falcon 2005, Sec. II B;
// Barrat & Trizac 2002, Sec. III A; Bhateja et al. 2016): the piston of two joined parabolas, a
// sinusoid, or a sawtooth. Its contacts follow `interactions` under the driver's name: on the
// event-driven engine v_n' - u = -e (v_n - u), u the wall velocity at contact (found exactly,
// libgran/core/wall_motion.hpp), e the grain-wall restitution (constant or of |v_n - u|).
#include <numbers>

#include "drivers/wall_driver.hpp"

namespace gran {
namespace {

constexpr double kPi = std::numbers::pi;

// At t = 0 with phase 0 the wall is at its outermost position (a piston at its lowest).
WallMotion motion_for(const Params& p, int side) {
    const std::string wave = p.str("waveform");
    if (wave == "sawtooth") {
        // The real sawtooth z = A (2 frac(f t) - 1) of amplitude A and frequency f (the
        // event-driven engine takes its limit A -> 0 at v0 = 2 A f), or that limit itself when
        // only v0 is given.
        if (p.has("amplitude") && p.has("frequency")) {
            return WallMotion::sawtooth_ramp(p.real("amplitude"), p.real("frequency"),
                                             p.real("phase"), side == 0 ? +1 : -1);
        }
        if (p.has("velocity")) return WallMotion::sawtooth(p.real("velocity"));
        p.fail("waveform",
               "waveform 'sawtooth' needs `velocity` (v0) or `amplitude` and "
               "`frequency` (v0 = 2 A f)");
    }
    if (!p.has("amplitude") || !p.has("frequency")) {
        p.fail("waveform", "waveform '" + wave + "' needs `amplitude` and `frequency`");
    }
    const double a = p.real("amplitude"), f = p.real("frequency"), phase = p.real("phase");
    if (wave == "two_parabolas") {
        // wall_motion.hpp: phase 0 is the lowest position (z = -A/2).
        return WallMotion::parabolic_piston(a, f, side == 0 ? phase : phase + kPi);
    }
    // A sin(omega t + phi): outermost at phi = -pi/2 (lower wall) or +pi/2 (upper wall).
    return WallMotion::sinusoid(a, 2 * kPi * f, side == 0 ? phase - kPi / 2 : phase + kPi / 2);
}

template <int D>
class VibratingWall final : public WallDriver<D> {
  public:
    VibratingWall(const Params& p, const SceneInfo& info)
        : WallDriver<D>(p, info, "vibrating " + p.str("waveform"), motion_for(p, 0),
                        motion_for(p, 1), "waveform"),
          motion_(motion_for(p, 0)),
          waveform_(p.str("waveform")) {
        if (waveform_ == "sawtooth" && p.has("amplitude") && p.has("frequency")) {
            const double a = p.real("amplitude"), f = p.real("frequency");
            if (p.has("velocity") && std::abs(p.real("velocity") - 2 * a * f) > 1e-9 * 2 * a * f)
                p.fail("velocity", "sawtooth: velocity must equal 2 amplitude frequency");
        }
        const double v = peak_velocity();
        if (waveform_ != "sawtooth" && !(v > 0))
            p.fail("amplitude", "a vibrating wall needs amplitude > 0 and frequency > 0");
        if (waveform_ == "sawtooth") return;
        const double excursion =
            waveform_ == "two_parabolas" ? p.real("amplitude") : 2 * p.real("amplitude");
        const double length = info.box_length[std::size_t(this->axis_)];
        if (excursion + info.species->max_diameter() >= length) {
            p.fail("amplitude", fmt::format("the wall sweeps {:.4g} of the {:.4g}-long axis and "
                                            "leaves no room for particles",
                                            excursion, length));
        }
    }

    // Maximum wall speed: V = 4 A f for the two parabolas (McNamara & Falcon 2005), A omega for a
    // sinusoid, v0 for the sawtooth.
    double peak_velocity() const override {
        if (waveform_ == "sawtooth") return std::abs(motion_.v0);
        if (waveform_ == "two_parabolas") return 4 * motion_.amplitude * motion_.omega / (2 * kPi);
        return motion_.amplitude * motion_.omega;
    }

    double drive_period() const override {
        if (waveform_ == "sawtooth") return motion_.omega > 0 ? 2 * kPi / motion_.omega : 0.0;
        return 2 * kPi / motion_.omega;
    }

    void write(ResultGroup& g) const override {
        WallDriver<D>::write(g);
        g.attr("waveform", waveform_);
        g.value("peak_velocity", peak_velocity());
        if (waveform_ != "sawtooth") {
            g.file_only().value("frequency", motion_.omega / (2 * kPi));
            g.file_only().value("amplitude", motion_.amplitude);
        }
    }

  private:
    WallMotion motion_;
    std::string waveform_;
};

const char* const kDescription =
    R"md(
A wall moving with a prescribed waveform (default `side: lower`); contacts are found exactly
(no missed hit: piecewise-quadratic roots for the parabolas, bracketed monotone Newton for the
sinusoid, `libgran/core/wall_motion.hpp`). The wall's whole excursion lies inside the box: a lower
wall moves between 0 and its peak-to-peak excursion (particles live above), an upper one between L
minus the excursion and L. `phase` 0 puts the wall at its outermost position (a floor at its
lowest) at t = 0. Besides its hits it reports its peak velocity.

Waveforms: `two_parabolas` is the piston of McNamara & Falcon 2005, Sec. II B,
z = +-(A/2)((t - t_n)^2/t0^2 - 1), t0 = 1/(4f), peak velocity V = 4 A f; `sinusoid`:
z = A sin(2 pi f t + phi), peak velocity 2 pi f A; `sawtooth`: as `sawtooth_wall`, with `velocity`
v0, or `amplitude` A and `frequency` f giving v0 = 2 A f.

On the dem engine a wall needs a position: `sawtooth` there is the real sawtooth
z = A (2 frac(f t) - 1) (rising at v0 = 2 A f, jumping back once per period), of which the
event-driven sawtooth is the limit A -> 0; it needs `amplitude` and `frequency`, and reproduces the
limit when the wall contact is much shorter than the period (v0 t_c << 2 A) and A is much smaller
than the mean free path (`DemRun.RealSawtoothWallGivesTheTemperatureOfTheEventDrivenSawtoothLimit`).)md";

const bool registered = register_plugin<Driver, VibratingWall>(
    "vibrating_wall",
    "wall of infinite mass moving with a prescribed waveform: two joined parabolas (McNamara & "
    "Falcon 2005 piston), sinusoid, or sawtooth",
    wall_schema(
        [] {
            Schema s{
                choice(
                    "waveform", "two_parabolas", {"two_parabolas", "sinusoid", "sawtooth"},
                    "wall motion: two_parabolas z = +-(A/2)((t-t_n)^2/t0^2 - 1), t0 = 1/(4f), peak "
                    "velocity 4 A f; sinusoid z = A sin(2 pi f t + phi), peak velocity 2 pi f A; "
                    "sawtooth: fixed position, every particle meets it at speed v0 (event_driven; "
                    "on the "
                    "dem engine a real sawtooth z = A (2 frac(f t) - 1), v0 = 2 A f)"),
                optional(
                    real("amplitude", "", "length",
                         "A: peak-to-peak excursion for two_parabolas, half of it (A of A sin) "
                         "for sinusoid",
                         0, 1e308, true)),
                optional(real("frequency", "", "1/time", "vibration frequency f", 0, 1e308, true)),
                real("phase", "0", "rad", "phase; 0: the wall starts at its outermost position",
                     -1e308, 1e308),
                optional(
                    real("velocity", "", "velocity",
                         "sawtooth: wall speed v0 (or give amplitude and frequency: v0 = 2 A f)", 0,
                         1e308, true))};
            return s;
        }(),
        "lower"),
    wall_description(kDescription));

}  // namespace
}  // namespace gran
