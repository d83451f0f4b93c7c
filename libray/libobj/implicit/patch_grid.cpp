#include "libobj/implicit/patch_grid.h"

namespace rs {

// The cell edge is kCellEdgePerItemEdge of the items' mean box edge, made larger where
// that would exceed kMaxCellsPerItem cells per item or 2^32 − 1 list entries (uint32
// offsets): the edge doubles until both hold. Items are binned by a counting sort (two
// passes over their blocks of cells), so each cell's list is in increasing item order.
PatchGrid::PatchGrid(const std::vector<Bounds3>& boxes) {
    if (boxes.empty()) return;
    double meanEdge = 0;
    for (const Bounds3& box : boxes) {
        bounds_.Extend(box);
        const Vec3 e = box.Extent();
        meanEdge += (e.x + e.y + e.z) / 3;
    }
    meanEdge /= static_cast<double>(boxes.size());
    const Vec3 extent = bounds_.Extent();
    const double maxCells = kMaxCellsPerItem * static_cast<double>(boxes.size());
    double cellEdge = std::max(kCellEdgePerItemEdge * meanEdge,
                               std::cbrt(extent.x * extent.y * extent.z / maxCells));
    if (!(cellEdge > 0)) cellEdge = std::max({extent.x, extent.y, extent.z, 1.0});
    struct Block {
        int lo[3], hi[3];
    };
    std::vector<Block> blocks(boxes.size());
    std::size_t total = 0;
    while (true) {
        for (int a = 0; a < 3; ++a) {
            dims_[a] = std::max(1, static_cast<int>(std::ceil(extent[a] / cellEdge)));
            edge_[a] = extent[a] > 0 ? extent[a] / dims_[a] : 1;
            invEdge_[a] = 1 / edge_[a];
        }
        total = 0;
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            std::size_t count = 1;
            for (int a = 0; a < 3; ++a) {
                const double margin = kBinMargin * edge_[a];
                blocks[i].lo[a] = CellOf(a, boxes[i].lo[a] - margin);
                blocks[i].hi[a] = CellOf(a, boxes[i].hi[a] + margin);
                count *= static_cast<std::size_t>(blocks[i].hi[a] - blocks[i].lo[a] + 1);
            }
            total += count;
        }
        if (total < std::numeric_limits<std::uint32_t>::max()) break;
        cellEdge *= 2;
    }
    const std::size_t cells = static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2];
    cellStart_.assign(cells + 1, 0);
    auto forEachCell = [&](const Block& b, auto&& body) {
        for (int z = b.lo[2]; z <= b.hi[2]; ++z) {
            for (int y = b.lo[1]; y <= b.hi[1]; ++y) {
                for (int x = b.lo[0]; x <= b.hi[0]; ++x) body(Index(x, y, z));
            }
        }
    };
    for (const Block& b : blocks) forEachCell(b, [&](std::size_t c) { ++cellStart_[c + 1]; });
    for (std::size_t c = 0; c < cells; ++c) cellStart_[c + 1] += cellStart_[c];
    entries_.resize(total);
    std::vector<std::uint32_t> fill(cellStart_.begin(), cellStart_.end() - 1);
    for (std::size_t i = 0; i < blocks.size(); ++i) {
        const auto item = static_cast<std::uint32_t>(i);
        forEachCell(blocks[i], [&](std::size_t c) { entries_[fill[c]++] = item; });
    }
}

}  // namespace rs
