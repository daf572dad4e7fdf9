// Two contacts per SSE2 instruction (libgran/engines/dem/two_contacts.hpp): each lane must give,
// bit for bit, what the one-contact code (Eigen) gives, or the settled bed's results would change
// with the pairing of its contacts.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <random>

#include "libgran/engines/dem/two_contacts.hpp"

namespace gran {
namespace {

using namespace two_contacts;

Vec<3> random_vector(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    return Vec<3>(u(rng), u(rng), u(rng));
}

// Bitwise equality (a plain == would let -0 pass for +0).
void expect_same_bits(const Vec<3>& lane, const Vec<3>& one) {
    for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(std::bit_cast<std::uint64_t>(lane[a]), std::bit_cast<std::uint64_t>(one[a]))
            << "component " << a << ": " << lane[a] << " against " << one[a];
    }
}

TEST(TwoContacts, EachLaneOfDotAndCrossHasTheBitsOfEigen) {
    std::mt19937_64 rng(3);
    for (int trial = 0; trial < 1000; ++trial) {
        const Vec<3> a0 = random_vector(rng), a1 = random_vector(rng);
        const Vec<3> b0 = random_vector(rng), b1 = random_vector(rng);
        const Vec2<3> a = lanes<3>(a0, a1), b = lanes<3>(b0, b1);
        const Lane d = dot(a, b);
        EXPECT_EQ(std::bit_cast<std::uint64_t>(first(d)), std::bit_cast<std::uint64_t>(a0.dot(b0)));
        EXPECT_EQ(std::bit_cast<std::uint64_t>(second(d)),
                  std::bit_cast<std::uint64_t>(a1.dot(b1)));
        const Vec2<3> c = cross(a, b);
        expect_same_bits(first(c), a0.cross(b0));
        expect_same_bits(second(c), a1.cross(b1));
    }
}

TEST(TwoContacts, EachLaneOfTheContactVelocityHasTheBitsOfTheOneContactCode) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> lever(0.2, 1.5);
    for (int trial = 0; trial < 1000; ++trial) {
        Vec<3> v_i[2], v_j[2], w_i[2], w_j[2], n[2];
        double l_i[2], l_j[2];
        for (int c = 0; c < 2; ++c) {
            v_i[c] = random_vector(rng);
            v_j[c] = random_vector(rng);
            w_i[c] = random_vector(rng);
            w_j[c] = random_vector(rng);
            n[c] = random_vector(rng).normalized();
            l_i[c] = lever(rng);
            l_j[c] = lever(rng);
        }
        const Vec2<3> g =
            contact_velocity(lanes<3>(v_i[0], v_i[1]), lanes<3>(v_j[0], v_j[1]),
                             lanes<3>(w_i[0], w_i[1]), lanes<3>(w_j[0], w_j[1]),
                             lanes(l_i[0], l_i[1]), lanes(l_j[0], l_j[1]), lanes<3>(n[0], n[1]));
        expect_same_bits(first(g), gran::contact_velocity<3>(v_i[0], v_j[0], w_i[0], w_j[0], l_i[0],
                                                             l_j[0], n[0]));
        expect_same_bits(second(g), gran::contact_velocity<3>(v_i[1], v_j[1], w_i[1], w_j[1],
                                                              l_i[1], l_j[1], n[1]));
    }
}

}  // namespace
}  // namespace gran
