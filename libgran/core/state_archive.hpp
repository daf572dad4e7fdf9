#pragma once
// The complete state of a running simulation as bytes, for checkpoints
// (libgran/run/checkpoint.hpp). Every stateful class lists its members once, in one function used
// in both directions:
//
//   void checkpoint(StateArchive& ar) override {
//       ar.section("stochastic_thermostat");
//       ar.io(next_kick_);
//       ar.io(rng_);
//   }
//
// Saving appends each member's bytes; loading reads them back in the same order, so the order of
// the io() calls is the format. Doubles are copied bit for bit: a loaded state continues exactly as
// the saved one would have (the resume guarantee, docs/reliability.md). section() writes a name
// that loading checks, so a state written by other code, or by a plugin whose members changed, is
// refused naming the section instead of being misread. Members derived from the scene (species
// tables, contact parameters, wall motions) are rebuilt from the scene and need not be listed.
#include <array>
#include <concepts>
#include <cstdint>
#include <cstring>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "libgran/core/random.hpp"

namespace gran {

// A state that does not fit what is loading it (other code, another scene, a truncated file).
class StateMismatch : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

class StateArchive;

// A class that lists its own state.
template <class T>
concept Checkpointable = requires(T& x, StateArchive& ar) {
    x.checkpoint(ar);
};

// Fixed-size Eigen vectors and matrices (Vec<D>, AngVec<3>): their coefficients.
template <class T>
concept FixedEigen = requires(T& x) {
    { x.data() } -> std::convertible_to<const double*>;
    T::SizeAtCompileTime;
}
&&(T::SizeAtCompileTime > 0);

class StateArchive {
  public:
    static StateArchive saver() { return StateArchive(false, {}); }
    static StateArchive loader(std::vector<char> bytes) {
        return StateArchive(true, std::move(bytes));
    }

    bool loading() const { return loading_; }
    const std::vector<char>& bytes() const { return bytes_; }
    // Loading: every byte was read (a state longer than its reader is a mismatch too).
    bool at_end() const { return pos_ == bytes_.size(); }

    // A named boundary: saving writes the name, loading requires it.
    void section(std::string_view name) {
        std::string s(name);
        if (!loading_) {
            io(s);
            return;
        }
        const std::size_t at = pos_;
        std::string found;
        io_string(found, name);
        if (found != s) {
            throw StateMismatch("checkpoint state does not match this code: expected section '" +
                                s + "' at byte " + std::to_string(at) + ", found '" +
                                printable(found) + "'");
        }
    }

    // Plain values: numbers, enums, trivially copyable structs of them.
    template <class T>
    requires std::is_trivially_copyable_v<T> &&(!FixedEigen<T>)&&(!Checkpointable<T>)void io(T& x) {
        raw(&x, sizeof(T));
    }
    template <FixedEigen T>
    void io(T& x) {
        raw(x.data(), sizeof(double) * std::size_t(T::SizeAtCompileTime));
    }
    template <Checkpointable T>
    void io(T& x) {
        x.checkpoint(*this);
    }
    void io(std::string& s) { io_string(s, "a string"); }
    // The generator's whole state (Boost's exact text form: 312 words and the position).
    void io(Rng& rng) {
        std::string text;
        if (!loading_) {
            std::ostringstream os;
            os << rng;
            text = os.str();
        }
        io(text);
        if (loading_) {
            std::istringstream is(text);
            is >> rng;  // Boost's reader sets failbit at the end even when it read everything
            std::ostringstream again;
            again << rng;
            if (again.str() != text)
                throw StateMismatch("checkpoint state: unreadable random-number generator");
        }
    }
    template <class T, std::size_t N>
    void io(std::array<T, N>& a) {
        for (auto& x : a) io(x);
    }
    template <class T, class A>
    void io(std::vector<T, A>& v) {
        std::uint64_t n = v.size();
        io(n);
        if (loading_) {
            if (n > bytes_.size() - pos_) too_short("a list", n);
            v.resize(std::size_t(n));
        }
        if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>) {
            raw(v.data(), sizeof(T) * v.size());
        } else {
            for (auto& x : v) io(x);
        }
    }
    void io(std::vector<bool>& v) {
        std::vector<std::uint8_t> b(v.begin(), v.end());
        io(b);
        if (loading_) v.assign(b.begin(), b.end());
    }

  private:
    StateArchive(bool loading, std::vector<char> bytes)
        : loading_(loading), bytes_(std::move(bytes)) {}

    void raw(void* p, std::size_t n) {
        if (n == 0) return;
        if (!loading_) {
            const char* c = static_cast<const char*>(p);
            bytes_.insert(bytes_.end(), c, c + n);
            return;
        }
        if (n > bytes_.size() - pos_) too_short("a value", n);
        std::memcpy(p, bytes_.data() + pos_, n);
        pos_ += n;
    }
    void io_string(std::string& s, std::string_view what) {
        std::uint64_t n = s.size();
        io(n);
        if (loading_) {
            if (n > bytes_.size() - pos_) too_short(what, n);
            s.assign(bytes_.data() + pos_, std::size_t(n));
            pos_ += std::size_t(n);
        } else {
            raw(s.data(), s.size());
        }
    }
    [[noreturn]] void too_short(std::string_view what, std::uint64_t n) const {
        throw StateMismatch("checkpoint state ends early (or does not match this code): " +
                            std::string(what) + " of " + std::to_string(n) + " at byte " +
                            std::to_string(pos_) + " of " + std::to_string(bytes_.size()));
    }
    static std::string printable(const std::string& s) {
        std::string out;
        for (char c : s.substr(0, 60)) out += (c >= 32 && c < 127) ? c : '?';
        return out;
    }

    bool loading_;
    std::vector<char> bytes_;
    std::size_t pos_ = 0;
};

}  // namespace gran
