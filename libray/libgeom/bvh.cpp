#include "libgeom/bvh.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "libcommon/parallel_build.h"

namespace rs {

namespace {

// Half the surface area of a box (the SAH only compares areas); 0 for an empty box.
double HalfArea(const Bounds3& b) {
    if (b.IsEmpty()) return 0;
    const Vec3 e = b.Extent();
    return e.x * e.y + e.y * e.z + e.z * e.x;
}

// Passes over the items of a node at least this large run in chunks of kPassChunk items on
// the build's threads (the top levels, above the parallel subtrees, are otherwise serial:
// on a quarter of a million items they were a fifth of the build). Their results are
// unions and counts, the same in any order, so the tree does not depend on the chunks.
constexpr int kParallelPassItems = 65536, kPassChunk = 16384;

// Calls pass(part, from, to) on ranges covering [begin, end) and merge(result, part) on
// their parts in order; a range smaller than kParallelPassItems is one pass into `result`.
template <class Part, class Pass, class Merge>
void ChunkedPass(int begin, int end, Part& result, Pass&& pass, Merge&& merge) {
    const int count = end - begin;
    if (count < kParallelPassItems) {
        pass(result, begin, end);
        return;
    }
    std::vector<Part> parts(static_cast<size_t>((count + kPassChunk - 1) / kPassChunk));
    RunBuildLoop(static_cast<long>(parts.size()), [&](long c) {
        const int from = begin + static_cast<int>(c) * kPassChunk;
        pass(parts[c], from, std::min(end, from + kPassChunk));
    });
    for (const Part& part : parts) merge(result, part);
}

}  // namespace

void BoundingVolumeHierarchy::Build(const std::vector<Bounds3>& boxes, Split split) {
    nodes_.clear();
    wide_.reset();
    wideCount_ = 0;
    expectedCost_ = 0;
    const int count = static_cast<int>(boxes.size());
    items_.resize(boxes.size());
    for (int i = 0; i < count; ++i) items_[i] = i;
    if (boxes.empty()) return;
    BuildInput input{boxes, {}};
    std::unique_ptr<SahBox[]> sahBoxes;
    if (split == Split::SurfaceArea) {
        // Each written once (the array is not initialised first), in chunks on the build's
        // threads: on a quarter of a million items a serial fill was 7 ms of tree's
        // two-thread setup with the second thread idle.
        sahBoxes = std::make_unique_for_overwrite<SahBox[]>(boxes.size());
        RunBuildLoopInChunks(boxes.size(), kPassChunk, [&](size_t begin, size_t end) {
            for (size_t i = begin; i < end; ++i) sahBoxes[i] = SahBoxOf(boxes[i]);
        });
    } else {
        // The centres in an array of their own: every level of a median build reads them.
        input.centres.reserve(boxes.size());
        for (const Bounds3& b : boxes) input.centres.push_back(b.Center());
    }
    const BuildItems buildItems{items_, sahBoxes.get()};
    // The top levels, leaving the subtrees below them as tasks. Synchronisation: every task
    // writes only its own outputs (its range items_[begin, end), disjoint from the others',
    // and its own vector of nodes) and reads what was written before the loop started;
    // RunBuildLoop returns after every task has (the worker pool's mutex orders both ends).
    std::vector<Node> top;
    std::vector<Subtree> deferred;
    const bool parallel = count >= kParallelBuildItems;
    top.reserve(parallel ? 4 * kBuildTasks : 2 * boxes.size());
    BuildNode(top, buildItems, 0, count, input, split, 0, count / kBuildTasks,
              parallel ? &deferred : nullptr);
    // The largest first, for balance; each task partitions only its own items.
    std::vector<int> order(deferred.size());
    for (size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
        return deferred[a].end - deferred[a].begin > deferred[b].end - deferred[b].begin;
    });
    std::vector<std::vector<Node>> parts(deferred.size());
    RunBuildLoop(static_cast<long>(order.size()), [&](long i) {
        const Subtree& task = deferred[order[i]];
        std::vector<Node>& part = parts[order[i]];
        part.reserve(2 * static_cast<size_t>(task.end - task.begin));
        BuildNode(part, buildItems, task.begin, task.end, input, split, task.depth, 0, nullptr);
    });
    std::vector<int> partAt;
    if (!deferred.empty()) {
        partAt.assign(top.size(), -1);
        for (size_t k = 0; k < deferred.size(); ++k) partAt[deferred[k].node] = static_cast<int>(k);
    }
    const BinaryParts tree{top, parts, partAt};
    BuildWideTree(tree);
    const Bounds3 root = NodeAt(tree, Resolve(tree, {-1, 0})).box;
    // A root of zero area leaves every term 0 (see ExpectedCost).
    if (const double rootArea = HalfArea(root); rootArea > 0) expectedCost_ /= rootArea;
    scale_ = std::max({std::fabs(FloatAtOrBelow(root.lo.x)), std::fabs(FloatAtOrBelow(root.lo.y)),
                       std::fabs(FloatAtOrBelow(root.lo.z)), std::fabs(FloatAtOrAbove(root.hi.x)),
                       std::fabs(FloatAtOrAbove(root.hi.y)), std::fabs(FloatAtOrAbove(root.hi.z))});
    // A median build keeps the binary tree for the walks in entry order and by point, in the
    // preorder one recursive build gives; the SAH's hierarchies only use the wide walk, and
    // the splice was 8.5 ms of tree's two-thread setup on one thread.
    if (split != Split::Median) return;
    if (parts.empty()) {
        nodes_ = std::move(top);
        return;
    }
    nodes_.reserve(2 * boxes.size());
    const auto splice = [&](const auto& self, int node) -> void {
        const int index = static_cast<int>(nodes_.size());
        if (partAt[node] >= 0) {
            for (Node n : parts[partAt[node]]) {
                if (n.count == 0) n.right += index;
                nodes_.push_back(n);
            }
            return;
        }
        nodes_.push_back(top[node]);
        if (top[node].count > 0) return;
        self(self, node + 1);
        nodes_[index].right = static_cast<int>(nodes_.size());
        self(self, top[node].right);
    };
    splice(splice, 0);
}

void BoundingVolumeHierarchy::BuildWideTree(const BinaryParts& tree) {
    WidePart top;
    std::vector<int> deferredParts;
    if (tree.parts.empty()) top.nodes.reserve(tree.top.size() / 2 + 1);  // the whole tree
    BuildWide(tree, Resolve(tree, {-1, 0}), top, &deferredParts);
    expectedCost_ = top.cost;
    std::vector<WidePart> parts(deferredParts.size());
    RunBuildLoop(static_cast<long>(parts.size()), [&](long p) {
        parts[p].nodes.reserve(tree.parts[deferredParts[p]].size() / 2 + 1);
        BuildWide(tree, {deferredParts[p], 0}, parts[p], nullptr);
    });
    for (const WidePart& part : parts) expectedCost_ += part.cost;
    // Spliced in preorder: a top node, then each lane's subtree in lane order. Where each
    // top node and part goes is worked out first; the parts are then copied there as tasks
    // (each writes only its own range), their interior lanes moved by their offset.
    std::vector<int> topAt(top.nodes.size()), partOffset(parts.size());
    int placed = 0;
    const auto place = [&](const auto& self, int t) -> void {
        topAt[t] = placed++;
        for (int k = 0; k < 4; ++k) {
            const int child = top.nodes[t].child[k];
            if (top.nodes[t].count[k] > 0 || child == 0) continue;  // a leaf or unused lane
            if (child <= kDeferredLane) {
                partOffset[kDeferredLane - child] = placed;
                placed += static_cast<int>(parts[kDeferredLane - child].nodes.size());
            } else {
                self(self, child);
            }
        }
    };
    place(place, 0);
    wide_ = std::make_unique_for_overwrite<WideNode[]>(static_cast<size_t>(placed));
    wideCount_ = placed;
    for (size_t t = 0; t < top.nodes.size(); ++t) {
        WideNode w = top.nodes[t];
        for (int k = 0; k < 4; ++k) {
            if (w.count[k] > 0 || w.child[k] == 0) continue;
            w.child[k] = w.child[k] <= kDeferredLane ? partOffset[kDeferredLane - w.child[k]]
                                                     : topAt[w.child[k]];
        }
        wide_[topAt[t]] = w;
    }
    RunBuildLoop(static_cast<long>(parts.size()), [&](long p) {
        const int offset = partOffset[p];
        WideNode* out = &wide_[offset];
        for (WideNode w : parts[p].nodes) {
            for (int k = 0; k < 4; ++k)
                if (w.count[k] == 0 && w.child[k] != 0) w.child[k] += offset;  // interior
            *out++ = w;
        }
    });
}

int BoundingVolumeHierarchy::BuildWide(const BinaryParts& tree, NodeRef node, WidePart& out,
                                       std::vector<int>* deferredParts) const {
    // A lane that stays whole: a leaf, or from the top a part's root (built as its task).
    const auto whole = [&](NodeRef lane) {
        return NodeAt(tree, lane).count > 0 || (deferredParts != nullptr && lane.part >= 0);
    };
    const auto left = [&](NodeRef n) { return Resolve(tree, {n.part, n.index + 1}); };
    const auto right = [&](NodeRef n) { return Resolve(tree, {n.part, NodeAt(tree, n).right}); };
    NodeRef lanes[4];
    int laneCount = 0;
    if (NodeAt(tree, node).count > 0) {
        lanes[laneCount++] = node;  // a leaf root
    } else {
        lanes[laneCount++] = left(node);
        lanes[laneCount++] = right(node);
    }
    while (laneCount < 4) {
        int widest = -1;
        double widestArea = -1;
        for (int k = 0; k < laneCount; ++k) {
            if (whole(lanes[k])) continue;
            const double area = HalfArea(NodeAt(tree, lanes[k]).box);
            if (area > widestArea) {
                widestArea = area;
                widest = k;
            }
        }
        if (widest < 0) break;
        const NodeRef split = lanes[widest];
        lanes[widest] = left(split);
        lanes[laneCount++] = right(split);
    }
    const int index = static_cast<int>(out.nodes.size());
    out.nodes.emplace_back();
    out.cost += HalfArea(NodeAt(tree, node).box);
    for (int k = 0; k < 4; ++k) {
        int child = 0, count = 0;
        Bounds3 box;  // empty for unused lanes
        if (k < laneCount) {
            const Node& lane = NodeAt(tree, lanes[k]);
            box = lane.box;
            if (lane.count > 0) {
                child = lane.first;
                count = lane.count;
                out.cost += HalfArea(lane.box) * count;
            } else if (whole(lanes[k])) {
                child = kDeferredLane - static_cast<int>(deferredParts->size());
                deferredParts->push_back(lanes[k].part);
            } else {
                child = BuildWide(tree, lanes[k], out, deferredParts);  // may move out.nodes
            }
        }
        WideNode& w = out.nodes[index];
        w.child[k] = child;
        w.count[k] = count;
        constexpr float kInfinity = std::numeric_limits<float>::infinity();
        for (int a = 0; a < 3; ++a) {
            w.planes[a][k] = box.IsEmpty() ? kInfinity : FloatAtOrBelow(box.lo[a]);
            w.planes[3 + a][k] = box.IsEmpty() ? -kInfinity : FloatAtOrAbove(box.hi[a]);
        }
    }
    return index;
}

bool BoundingVolumeHierarchy::FloatRay::Set(const Ray& ray, double scale) {
    constexpr double kMax = std::numeric_limits<float>::max() / 4;
    constexpr double kMinInverse = std::numeric_limits<float>::min();
    for (int a = 0; a < 3; ++a) {
        const double o = ray.origin[a], d = ray.dir[a];
        const double delta = 0x1p-21 * (std::fabs(o) + scale);
        if (!(std::fabs(o) + delta < kMax)) return false;
        const double inv = 1 / d;
        // d = 0 gives inv = ±inf, and parameters ±inf or NaN (an origin on the plane), which
        // Clip handles; otherwise 1/d must stay in float's normal range (and away from its
        // top, so products keep the relative error bound).
        if (d != 0 && !(std::fabs(inv) >= kMinInverse && std::fabs(inv) <= kMax)) return false;
        const bool negative = std::signbit(inv);
        nearPlane[a] = negative ? 3 + a : a;
        farPlane[a] = negative ? a : 3 + a;
        invDir[a] = Splat(static_cast<float>(inv));
        nearOrigin[a] = Splat(static_cast<float>(negative ? o - delta : o + delta));
        farOrigin[a] = Splat(static_cast<float>(negative ? o + delta : o - delta));
    }
    return true;
}

BoundingVolumeHierarchy::SahBox BoundingVolumeHierarchy::SahBoxOf(const Bounds3& box) {
    return {Float4{FloatAtOrBelow(box.lo.x), FloatAtOrBelow(box.lo.y), FloatAtOrBelow(box.lo.z), 0},
            Float4{FloatAtOrAbove(box.hi.x), FloatAtOrAbove(box.hi.y), FloatAtOrAbove(box.hi.z), 0}};
}

int BoundingVolumeHierarchy::SahPartition(BuildItems order, int begin, int end,
                                          const Bounds3& box, const Bounds3& centroids,
                                          int& axis) {
    constexpr int kBins = 16;
    typedef int Int4 __attribute__((vector_size(16)));
    const int count = end - begin;
    // Costs in units of one item test, a box test of a child counted as one as well:
    // splitting costs 1 + (A_left·N_left + A_right·N_right) / A; a leaf costs N.
    double bestCost = count;
    int bestAxis = -1, bestBin = 0;
    const double area = HalfArea(box);
    const Vec3 cExtent = centroids.Extent();
    // The three axes' bins of a centre at once, in single precision (an axis whose centres
    // all coincide is binned into bin 0 and not split).
    const Float4 cLo{static_cast<float>(centroids.lo.x), static_cast<float>(centroids.lo.y),
                     static_cast<float>(centroids.lo.z), 0};
    Float4 binsPerUnit{};
    for (int a = 0; a < 3; ++a)
        if (cExtent[a] > 0) binsPerUnit[a] = static_cast<float>(kBins / cExtent[a]);
    const SahBox* boxes = order.sahBoxes;
    // The three axes' bins of the item at position i.
    const auto binsOf = [&](int i) {
        const Float4 rel = (boxes[i].Centre() - cLo) * binsPerUnit;
        const Int4 b = __builtin_convertvector(rel > 0 ? rel : Float4{}, Int4);
        return b < kBins - 1 ? b : Int4{} + (kBins - 1);
    };
    // Half the area of a bin union, 0 when empty.
    const auto halfArea = [](const Float4& lo, const Float4& hi) {
        const Float4 e = hi - lo;
        return e[0] >= 0 ? static_cast<double>(e[0] * e[1] + e[1] * e[2] + e[2] * e[0]) : 0.0;
    };
    // Two items (about half the calls: most nodes just above the leaves): the choice the
    // bins' sweeps below would make, without filling them. An axis whose two centres fall in
    // different bins offers one split, the lower bin's item against the other, of cost
    // 1 + (A_lower + A_upper) / A (the sweeps' A·N terms with N = 1, exactly), the same on
    // every such axis; the sweeps keep the first axis of least cost, and the partition
    // puts the lower item first.
    static_assert(kMaxSahLeaf >= 2, "two items that are not split make a leaf");
    if (count == 2) {
        const Int4 b0 = binsOf(begin), b1 = binsOf(begin + 1);
        for (int a = 0; a < 3; ++a) {
            if (!(cExtent[a] > 0) || b0[a] == b1[a]) continue;
            const double cost = 1 + (halfArea(boxes[begin].lo, boxes[begin].hi) +
                                     halfArea(boxes[begin + 1].lo, boxes[begin + 1].hi)) /
                                        area;
            if (!(cost < bestCost)) break;
            axis = a;
            if (b1[a] < b0[a]) order.Swap(begin, begin + 1);
            return begin + 1;
        }
        return kSahLeaf;
    }
    // One pass over the items fills the bins of all three axes (each box read once).
    constexpr float kInf = std::numeric_limits<float>::infinity();
    struct Bins {
        Float4 lo[3][kBins], hi[3][kBins];
        int counts[3][kBins] = {};
        Bins() {
            for (int a = 0; a < 3; ++a) {
                for (int k = 0; k < kBins; ++k) {
                    lo[a][k] = Float4{} + kInf;
                    hi[a][k] = Float4{} - kInf;
                }
            }
        }
        void Add(int a, int k, const Float4& boxLo, const Float4& boxHi, int n) {
            counts[a][k] += n;
            lo[a][k] = LaneMin(boxLo, lo[a][k]);
            hi[a][k] = LaneMax(boxHi, hi[a][k]);
        }
    };
    Bins bins;
    ChunkedPass(
        begin, end, bins,
        [&](Bins& part, int from, int to) {
            for (int i = from; i < to; ++i) {
                const Int4 b = binsOf(i);
                for (int a = 0; a < 3; ++a) part.Add(a, b[a], boxes[i].lo, boxes[i].hi, 1);
            }
        },
        [](Bins& into, const Bins& part) {
            for (int a = 0; a < 3; ++a)
                for (int k = 0; k < kBins; ++k)
                    into.Add(a, k, part.lo[a][k], part.hi[a][k], part.counts[a][k]);
        });
    const auto& binLo = bins.lo;
    const auto& binHi = bins.hi;
    const auto& counts = bins.counts;
    // An empty bin leaves both sweeps' unions and counts as they were, so every split between
    // two consecutive non-empty bins costs the same, and the first of them is the one just
    // after the lower bin: the sweeps run over the non-empty bins only (small nodes fill
    // few), which keeps the first split of the least cost.
    for (int a = 0; a < 3; ++a) {
        if (!(cExtent[a] > 0)) continue;
        // The non-empty bins in order, listed without a branch per bin (each written, and
        // kept when its count is positive).
        int filled[kBins];
        int m = 0;
        for (int k = 0; k < kBins; ++k) {
            filled[m] = k;
            m += counts[a][k] > 0;
        }
        // rightCost[j]: A·N of the non-empty bins j.. (the right part of the split before
        // bin filled[j]).
        double rightCost[kBins];
        Float4 accLo = Float4{} + kInf, accHi = Float4{} - kInf;
        int n = 0;
        for (int j = m - 1; j > 0; --j) {
            const int k = filled[j];
            accLo = LaneMin(binLo[a][k], accLo);
            accHi = LaneMax(binHi[a][k], accHi);
            n += counts[a][k];
            rightCost[j] = halfArea(accLo, accHi) * n;
        }
        accLo = Float4{} + kInf;
        accHi = Float4{} - kInf;
        n = 0;
        for (int j = 0; j + 1 < m; ++j) {
            const int k = filled[j];
            accLo = LaneMin(binLo[a][k], accLo);
            accHi = LaneMax(binHi[a][k], accHi);
            n += counts[a][k];
            const double cost = 1 + (halfArea(accLo, accHi) * n + rightCost[j + 1]) / area;
            if (cost < bestCost) {
                bestCost = cost;
                bestAxis = a;
                bestBin = k + 1;
            }
        }
    }
    if (bestAxis < 0) return count <= kMaxSahLeaf ? kSahLeaf : kSahMedian;
    axis = bestAxis;
    // The left part to the front, items and boxes together.
    int i = begin, j = end - 1;
    for (;;) {
        while (i <= j && binsOf(i)[bestAxis] < bestBin) ++i;
        while (i <= j && !(binsOf(j)[bestAxis] < bestBin)) --j;
        if (i >= j) return i;
        order.Swap(i++, j--);
    }
}

int BoundingVolumeHierarchy::BuildNode(std::vector<Node>& nodes, BuildItems order, int begin,
                                       int end, const BuildInput& input, Split split,
                                       int depth, int deferBelow, std::vector<Subtree>* deferred) {
    const int index = static_cast<int>(nodes.size());
    nodes.emplace_back();
    if (deferred != nullptr && end - begin <= deferBelow) {
        deferred->push_back({begin, end, depth, index});
        return index;
    }
    struct NodeBounds {
        Bounds3 box, centroids;
    } bounds;
    const std::vector<int>& items = order.items;
    if (order.sahBoxes == nullptr) {
        ChunkedPass(
            begin, end, bounds,
            [&](NodeBounds& part, int from, int to) {
                // In locals, which the compiler keeps in registers (`part` might alias the input).
                Bounds3 partBox, partCentroids;
                for (int i = from; i < to; ++i) {
                    partBox.Extend(input.boxes[items[i]]);
                    partCentroids.Extend(input.centres[items[i]]);
                }
                part = {partBox, partCentroids};
            },
            [](NodeBounds& into, const NodeBounds& part) {
                into.box.Extend(part.box);
                into.centroids.Extend(part.centroids);
            });
    } else {
        // The SAH's node box: the union of its items' outward-rounded float boxes, and its
        // centroid bounds over the centres its bins use (SahPartition's binsOf).
        constexpr float kInf = std::numeric_limits<float>::infinity();
        struct FloatBounds {
            Float4 lo = Splat(kInf), hi = Splat(-kInf), centreLo = Splat(kInf), centreHi = Splat(-kInf);
        } floatBounds;
        const SahBox* boxes = order.sahBoxes;
        ChunkedPass(
            begin, end, floatBounds,
            [&](FloatBounds& part, int from, int to) {
                Float4 lo = part.lo, hi = part.hi, centreLo = part.centreLo, centreHi = part.centreHi;
                for (int i = from; i < to; ++i) {
                    const Float4 centre = boxes[i].Centre();
                    lo = LaneMin(boxes[i].lo, lo);
                    hi = LaneMax(boxes[i].hi, hi);
                    centreLo = LaneMin(centre, centreLo);
                    centreHi = LaneMax(centre, centreHi);
                }
                part = {lo, hi, centreLo, centreHi};
            },
            [](FloatBounds& into, const FloatBounds& part) {
                into.lo = LaneMin(part.lo, into.lo);
                into.hi = LaneMax(part.hi, into.hi);
                into.centreLo = LaneMin(part.centreLo, into.centreLo);
                into.centreHi = LaneMax(part.centreHi, into.centreHi);
            });
        const auto toVec3 = [](const Float4& v) { return Vec3{v[0], v[1], v[2]}; };
        bounds.box.lo = toVec3(floatBounds.lo);
        bounds.box.hi = toVec3(floatBounds.hi);
        bounds.centroids.lo = toVec3(floatBounds.centreLo);
        bounds.centroids.hi = toVec3(floatBounds.centreHi);
    }
    const Bounds3& box = bounds.box;
    const Bounds3& centroids = bounds.centroids;
    nodes[index].box = box;
    const auto leaf = [&] {
        nodes[index].first = begin;
        nodes[index].count = end - begin;
        return index;
    };
    Vec3 extent = centroids.Extent();
    int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    int mid = kSahMedian;
    if (split == Split::SurfaceArea && depth < kMaxSahDepth) {
        if (end - begin <= 1) return leaf();
        mid = SahPartition(order, begin, end, box, centroids, axis);
        if (mid == kSahLeaf) return leaf();
    } else if (end - begin <= kLeafSize) {
        return leaf();
    }
    if (mid == kSahMedian) {
        mid = begin + (end - begin) / 2;
        std::nth_element(order.items.begin() + begin, order.items.begin() + mid,
                         order.items.begin() + end, [&](int a, int b) {
                             // Ties broken by item, so which items go to each half
                             // does not depend on the standard library.
                             const double ca = CentreOf(input, a, axis), cb = CentreOf(input, b, axis);
                             return ca < cb || (ca == cb && a < b);
                         });
        // The SAH's boxes follow their items (a median split under the SAH is rare: past
        // kMaxSahDepth, or where no split pays but the node is too large for a leaf).
        if (order.sahBoxes != nullptr)
            for (int i = begin; i < end; ++i) order.sahBoxes[i] = SahBoxOf(input.boxes[items[i]]);
    }
    BuildNode(nodes, order, begin, mid, input, split, depth + 1, deferBelow, deferred);
    const int right = BuildNode(nodes, order, mid, end, input, split, depth + 1, deferBelow, deferred);
    nodes[index].right = right;
    nodes[index].axis = axis;
    return index;
}

}  // namespace rs
