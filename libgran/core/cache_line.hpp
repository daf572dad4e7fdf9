#pragma once
// Storage aligned to 64-byte cache lines, for arrays whose blocks are read as units in hot loops
// (a cell's slots, a heap node's children): a block that never straddles two lines costs one
// memory access instead of two.
#include <cstddef>
#include <new>

namespace gran {

inline constexpr std::size_t kCacheLine = 64;

template <class T>
struct CacheLineAllocator {
    using value_type = T;
    static constexpr std::align_val_t kAlign{kCacheLine};
    CacheLineAllocator() = default;
    template <class U>
    CacheLineAllocator(const CacheLineAllocator<U>&) {}
    T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), kAlign)); }
    void deallocate(T* p, std::size_t) { ::operator delete(p, kAlign); }
    bool operator==(const CacheLineAllocator&) const { return true; }
};

}  // namespace gran
