// Names in insertion order, each found by its index: the names in one vector and a flat
// open-addressing hash table of indices beside it, so a name costs no allocation of its own
// and is stored once. For the large, flat name spaces of a scene (an implicit object's
// skeletons, by the hundred thousand).
#pragma once

#include <algorithm>
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace rs {

class NameIndex {
  public:
    size_t Size() const { return names_.size(); }
    // The name of index `index` (< Size()).
    const std::string& Name(size_t index) const { return names_[index]; }

    // The index of `name`, or -1 when it is not in the index.
    long Find(std::string_view name) const {
        if (slots_.empty()) return -1;
        const size_t mask = slots_.size() - 1;
        for (size_t i = std::hash<std::string_view>()(name) & mask;; i = (i + 1) & mask) {
            const size_t slot = slots_[i];
            if (slot == kEmpty) return -1;
            if (names_[slot - 1] == name) return static_cast<long>(slot - 1);
        }
    }

    // Adds `name` with index Size() and returns true, or returns false when the index holds
    // it already.
    bool Insert(std::string_view name) {
        if (2 * (names_.size() + 1) > slots_.size()) {
            Rehash(std::max<size_t>(16, 2 * slots_.size()));
        }
        const size_t mask = slots_.size() - 1;
        size_t i = std::hash<std::string_view>()(name) & mask;
        for (; slots_[i] != kEmpty; i = (i + 1) & mask) {
            if (names_[slots_[i] - 1] == name) return false;
        }
        names_.emplace_back(name);
        slots_[i] = names_.size();
        return true;
    }

  private:
    static constexpr size_t kEmpty = 0;

    // Rebuilds the table with `size` slots (a power of two, more than twice Size()).
    void Rehash(size_t size) {
        slots_.assign(size, kEmpty);
        const size_t mask = size - 1;
        for (size_t index = 0; index < names_.size(); ++index) {
            size_t i = std::hash<std::string_view>()(names_[index]) & mask;
            while (slots_[i] != kEmpty) i = (i + 1) & mask;
            slots_[i] = index + 1;
        }
    }

    std::vector<std::string> names_;
    // Linear probing, at most half full: each slot is kEmpty or a name's index + 1.
    std::vector<size_t> slots_;
};

}  // namespace rs
