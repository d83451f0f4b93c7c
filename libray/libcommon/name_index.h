// Names in insertion order, each found by its index: the names in one vector and a flat
// open-addressing hash table of indices beside it, so a name costs no allocation of its own
// and is stored once. For the large, flat name spaces of a scene (an implicit object's
// skeletons, by the hundred thousand); both are large buffers. Holds fewer than 2^32 − 1
// names (Insert throws std::length_error beyond).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "libcommon/large_buffer.h"

namespace rs {

class NameIndex {
  public:
    size_t Size() const { return names_.size(); }
    // The name of index `index` (< Size()).
    const std::string& Name(size_t index) const { return names_[index]; }

    // The index of `name`, or -1 when it is not in the index.
    long Find(std::string_view name) const {
        if (slots_.empty()) return -1;
        const uint32_t hash = Hash(name);
        const size_t mask = slots_.size() - 1;
        for (size_t i = hash & mask;; i = (i + 1) & mask) {
            const Slot& slot = slots_[i];
            if (slot.index == kEmpty) return -1;
            if (slot.hash == hash && names_[slot.index - 1] == name) {
                return static_cast<long>(slot.index - 1);
            }
        }
    }

    // Adds `name` with index Size() and returns true, or returns false when the index holds
    // it already.
    bool Insert(std::string_view name) {
        if (names_.size() + 1 >= UINT32_MAX) throw std::length_error("NameIndex: too many names");
        if (2 * (names_.size() + 1) > slots_.size()) {
            Rehash(std::max<size_t>(16, 2 * slots_.size()));
        }
        const uint32_t hash = Hash(name);
        const size_t mask = slots_.size() - 1;
        size_t i = hash & mask;
        for (; slots_[i].index != kEmpty; i = (i + 1) & mask) {
            const Slot& slot = slots_[i];
            if (slot.hash == hash && names_[slot.index - 1] == name) return false;
        }
        names_.emplace_back(name);
        slots_[i] = {static_cast<uint32_t>(names_.size()), hash};
        return true;
    }

  private:
    // A name's index + 1 (kEmpty: a free slot) and its Hash, which places it and is compared
    // before the name itself.
    struct Slot {
        uint32_t index;
        uint32_t hash;
    };
    static constexpr uint32_t kEmpty = 0;

    static uint32_t Hash(std::string_view name) {
        return static_cast<uint32_t>(std::hash<std::string_view>()(name));
    }

    // Rebuilds the table with `size` slots (a power of two, more than twice Size()).
    void Rehash(size_t size) {
        std::vector<Slot, LargeBufferAllocator<Slot>> old(size, Slot{kEmpty, 0});
        old.swap(slots_);
        const size_t mask = size - 1;
        for (const Slot& slot : old) {
            if (slot.index == kEmpty) continue;
            size_t i = slot.hash & mask;
            while (slots_[i].index != kEmpty) i = (i + 1) & mask;
            slots_[i] = slot;
        }
    }

    std::vector<std::string, LargeBufferAllocator<std::string>> names_;
    // Linear probing, at most half full.
    std::vector<Slot, LargeBufferAllocator<Slot>> slots_;
};

}  // namespace rs
