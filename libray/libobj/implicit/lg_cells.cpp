// Layer 6 of the implicit module: the per-cell trees (lg_octree.h, "Per-cell trees" in the
// module README): an object's budget of kept cells (LazyCellStore), and the blocks of a
// cell's children, filled from the plans of ExpandLazy (lg_octree.cpp: the same decisions as
// the whole-tree build) and published once by the first ray that reaches the cell.
#include <algorithm>
#include <atomic>
#include <cmath>

#include "libcommon/error.h"
#include "libcommon/stats.h"
#include "libobj/implicit/field_motion.h"
#include "libobj/implicit/lg_octree.h"
#include "libobj/implicit/lg_octree_detail.h"

namespace rs {

using lg_octree_detail::ChildBox;
using lg_octree_detail::Counters;

bool LazyCellStore::Reserve(std::size_t bytes) {
    std::size_t used = used_.load(std::memory_order_relaxed);
    do {
        if (used + bytes > budget_) {
            if (!degraded_.exchange(true, std::memory_order_relaxed)) {
                Report(Severity::Warn, {},
                       "implicit octree: memory budget of %zu bytes for the object's cells "
                       "reached; further cells are recomputed by each ray (slower, same "
                       "results)",
                       budget_);
            }
            return false;
        }
    } while (!used_.compare_exchange_weak(used, used + bytes, std::memory_order_relaxed));
    return true;
}

LGOctree::LazyBlock::~LazyBlock() {
    for (int child = 0; child < 8; ++child) {
        if ((classes >> (16 + child)) & 1) delete Cell(child).children.load();
    }
}

std::size_t LGOctree::LazyBlock::Bytes() const {
    return sizeof(LazyBlock) + std::popcount(classes & 0xffu) * sizeof(LazyCell) +
           terms.capacity() * sizeof(int32_t);
}

void LGOctree::FillLazyBlock(LazyBlock& block, std::span<const ChildPlan> plans) const {
    int live = 0;
    for (const ChildPlan& plan : plans) {
        switch (plan.decision) {
            case Decision::Empty:
                break;
            case Decision::Full:
                block.classes |= 1u << (8 + plan.child);
                break;
            case Decision::Subdivide:
                block.classes |= 1u << (16 + plan.child);
                [[fallthrough]];
            case Decision::Leaf:
                block.classes |= 1u << plan.child;
                ++live;
                break;
        }
    }
    block.cells = std::make_unique<LazyCell[]>(static_cast<size_t>(live));
    thread_local std::vector<int32_t> terms;  // the lists, copied once at their exact size
    terms.clear();
    for (const ChildPlan& plan : plans) {
        if (!((block.classes >> plan.child) & 1)) continue;
        LazyCell& cell = block.cells[std::popcount(block.classes & ((1u << plan.child) - 1))];
        cell.L = UpperFloat(plan.L);
        cell.G = UpperFloat(plan.G);
        cell.firstTerm = static_cast<uint32_t>(terms.size());
        if (plan.decision == Decision::Leaf) {
            field_.ActiveTerms(plan.box.Padded(leafPadding_), *plan.terms, terms);
        } else {
            terms.insert(terms.end(), plan.terms->begin(), plan.terms->end());
        }
        cell.termCount = static_cast<uint32_t>(terms.size()) - cell.firstTerm;
    }
    block.terms.assign(terms.begin(), terms.end());
}

const LGOctree::LazyBlock& LGOctree::Children(const LazyBlock& owner, const LazyCell& cell,
                                              const Bounds3& box, int depth, LatticePoint low,
                                              bool& keep,
                                              std::unique_ptr<LazyBlock>& scratch) const {
    if (const LazyBlock* kept = cell.children.load(std::memory_order_acquire)) return *kept;
    auto made = std::make_unique<LazyBlock>();
    // The expansion sees no ray time, as whole builds do (ImplicitObjectStats::BuildTree):
    // a moving field's point values are then its reference terms', so the children do not
    // depend on which ray expands the cell.
    auto expand = [&] {
        const RayTimeScope noTime(kNoRayTime);
        ExpandLazy(*made, box, depth, low, owner.Terms(cell));
    };
    const CellExpansionObserver* observer = lazy_->store->Observer();
    if (observer) {
        observer->Expand(expand);
    } else {
        expand();
    }
    if (keep) {
        const std::size_t bytes = made->Bytes();
        if (lazy_->store->Reserve(bytes)) {
            LazyBlock* expected = nullptr;
            if (cell.children.compare_exchange_strong(expected, made.get(),
                                                      std::memory_order_acq_rel,
                                                      std::memory_order_acquire)) {
                lazy_->bytes.fetch_add(bytes, std::memory_order_relaxed);
                if (observer) observer->Kept(std::popcount(made->classes & 0xffu), bytes);
                return *made.release();
            }
            lazy_->store->Release(bytes);  // another thread kept the same children first
            return *expected;
        }
        lazy_->degraded.store(true, std::memory_order_relaxed);
    }
    keep = false;
    scratch = std::move(made);
    return *scratch;
}

}  // namespace rs
