// An allocator for large buffers that are filled once and read often (a frame's pixel
// states, images), and that are never read before being written (see construct). On Linux, buffers of 2 MiB and more are aligned to 2 MiB and marked for
// transparent huge pages, so the kernel maps them with one fault per 2 MiB instead of one
// per 4 KiB. On virtual machines a page fault can cost tens of microseconds: the 21 MB of
// pixel states of a 1024×1024 frame took about 0.12 s of faults with small pages and a few
// milliseconds with huge ones. Smaller buffers, and systems without the hint, get ordinary
// memory.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <utility>

#include <sys/mman.h>

namespace rs {

template <class T>
struct LargeBufferAllocator {
    using value_type = T;
    static constexpr std::size_t kHugePage = std::size_t{2} << 20;

    LargeBufferAllocator() = default;
    template <class U>
    LargeBufferAllocator(const LargeBufferAllocator<U>&) {}

    T* allocate(std::size_t n) {
        if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_alloc();
        const std::size_t bytes = n * sizeof(T);
        if (bytes < kHugePage) return static_cast<T*>(::operator new(bytes));
        const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
        void* p = std::aligned_alloc(kHugePage, rounded);
        if (!p) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
        madvise(p, rounded, MADV_HUGEPAGE);  // a hint: failure just means small pages
#endif
        return static_cast<T*>(p);
    }

    // Default-initialises: resize(n) leaves trivially constructible elements (bytes,
    // PixelState) unwritten, so their first touch happens where the owner fills them (in
    // parallel, for a frame). Owners write every element before reading it.
    template <class U>
    void construct(U* p) noexcept(noexcept(::new (static_cast<void*>(p)) U)) {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }

    void deallocate(T* p, std::size_t n) {
        if (n * sizeof(T) < kHugePage) {
            ::operator delete(p);
        } else {
            std::free(p);
        }
    }

    template <class U>
    bool operator==(const LargeBufferAllocator<U>&) const {
        return true;
    }
};

// Marks the whole 2 MiB pages inside [data, data + bytes) for transparent huge pages, as
// LargeBufferAllocator does for its buffers: for a large buffer whose allocator cannot be
// chosen (a std::vector or std::string of a type other code shares), right after reserving
// it and before writing it. A hint: without it, or where it fails, pages stay small.
inline void AdviseHugePages(const void* data, std::size_t bytes) {
#ifdef MADV_HUGEPAGE
    constexpr std::size_t kHugePage = LargeBufferAllocator<char>::kHugePage;
    const std::uintptr_t start = reinterpret_cast<std::uintptr_t>(data);
    const std::uintptr_t begin = (start + kHugePage - 1) / kHugePage * kHugePage;
    const std::uintptr_t end = (start + bytes) / kHugePage * kHugePage;
    if (begin < end) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
    (void)data;
    (void)bytes;
#endif
}

}  // namespace rs
