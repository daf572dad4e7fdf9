// The DEM engine's threaded pair forces summed into the grains in the order the single-threaded
// loop adds them (DemSettings::threads): the bits of one thread for any thread count.
#include "libgran/core/parallel.hpp"
#include "libgran/engines/dem/engine.hpp"

namespace gran {

// The touched entries of every thread, in increasing entry order (the threads' shares are
// consecutive ranges), added as the single-threaded loop adds them. Each thread reads them all
// and adds only into its own range of particles: every particle still receives its contacts in
// entry order, so the sums are the same bits for any split.
template <int D>
void DemEngine<D>::add_touched_pair_forces() {
    const bool rot = p_.rotating();
    const std::uint32_t* owner = list_.owner.data();
    const std::uint32_t* partner = list_.partner.data();
    const Vec<D>* pf = pair_force_.data();
    const AngVec<D>* pti = pair_torque_i_.data();
    const AngVec<D>* ptj = pair_torque_j_.data();
    Vec<D>* f = f_.data();
    AngVec<D>* tau = tau_.data();
    parallel_chunks(threads_, p_.size(), [&](std::size_t, std::size_t x0, std::size_t x1) {
        for (const std::vector<std::uint32_t>& part : touched_) {
            for (const std::uint32_t k : part) {
                const std::uint32_t i = owner[k], j = partner[k];
                if (i >= x0 && i < x1) {
                    f[i] += pf[k];
                    if (rot) tau[i] += pti[k];
                }
                if (j >= x0 && j < x1) {
                    f[j] -= pf[k];
                    if (rot) tau[j] += ptj[k];
                }
            }
        }
    });
}

// Each particle's pair contacts summed from the per-entry slots of the threaded force loop
// (law_loop.hpp), in the order the single-threaded loop adds them.
template <int D>
void DemEngine<D>::sum_pair_forces() {
    const bool rot = p_.rotating();
    const std::uint32_t* start = list_.start.data();
    const std::uint32_t* partner_start = list_.partner_start.data();
    const std::uint32_t* by_partner = list_.by_partner.data();
    const std::uint8_t* touching = list_.touching.data();
    const Vec<D>* pf = pair_force_.data();
    const AngVec<D>* pti = pair_torque_i_.data();
    const AngVec<D>* ptj = pair_torque_j_.data();
    Vec<D>* f = f_.data();
    AngVec<D>* tau = tau_.data();
    parallel_chunks(threads_, p_.size(), [&](std::size_t, std::size_t x0, std::size_t x1) {
        for (std::size_t x = x0; x < x1; ++x) {
            // As partner j (entries of lower-index owners: earlier rows, so first), then as
            // owner i (its own row).
            Vec<D> fx = f[x];
            for (std::uint32_t q = partner_start[x]; q < partner_start[x + 1]; ++q) {
                const std::uint32_t k = by_partner[q];
                if (touching[k]) fx -= pf[k];
            }
            for (std::uint32_t k = start[x]; k < start[x + 1]; ++k) {
                if (touching[k]) fx += pf[k];
            }
            f[x] = fx;
            if (!rot) continue;
            AngVec<D> tx = tau[x];
            for (std::uint32_t q = partner_start[x]; q < partner_start[x + 1]; ++q) {
                const std::uint32_t k = by_partner[q];
                if (touching[k]) tx += ptj[k];
            }
            for (std::uint32_t k = start[x]; k < start[x + 1]; ++k) {
                if (touching[k]) tx += pti[k];
            }
            tau[x] = tx;
        }
    });
}

template void DemEngine<2>::add_touched_pair_forces();
template void DemEngine<3>::add_touched_pair_forces();
template void DemEngine<2>::sum_pair_forces();
template void DemEngine<3>::sum_pair_forces();

}  // namespace gran
