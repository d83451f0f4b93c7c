// Layer 7 of the implicit module: an LG octree built on first use, by the first ray that
// needs it (on whichever render thread; the tree depends only on its inputs, so images do
// not depend on which thread builds it). Held by pointer, so a tree no ray reaches costs
// 16 bytes instead of an empty LGOctree's 432.
#pragma once

#include <memory>
#include <mutex>
#include <utility>

#include "libobj/implicit/lg_octree.h"

namespace rs {

class LazyOctree {
  public:
    // The tree, made by make() (returning an LGOctree) on the first call. Thread-safe.
    template <class Make>
    const LGOctree& Get(Make&& make) {
        std::call_once(once_, [&] { tree_ = std::make_unique<LGOctree>(make()); });
        return *tree_;
    }
    // Stores an already built tree (before any Get).
    void Set(LGOctree tree) { Get([&] { return std::move(tree); }); }
    // The tree once built (Get or Set), else null.
    const LGOctree* Built() const { return tree_.get(); }

  private:
    std::once_flag once_;
    std::unique_ptr<LGOctree> tree_;
};

}  // namespace rs
