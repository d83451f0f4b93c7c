#include "libobj/implicit/patch.h"

#include <algorithm>

namespace rs {

namespace {

std::vector<FieldTerm> SelectTerms(const std::vector<FieldTerm>& all,
                                   const std::vector<int>& members) {
    std::vector<FieldTerm> out;
    out.reserve(members.size());
    for (int i : members) out.push_back(all[i]);
    return out;
}

bool BoxesOverlap(const Bounds3& a, const Bounds3& b) {
    return !Intersection(a, b).IsEmpty();
}

}  // namespace

Patch::Patch(const std::vector<FieldTerm>& allTerms, std::vector<int> members)
    : members_(std::move(members)),
      field_(SelectTerms(allTerms, members_)),
      box_(TermSupportBounds(allTerms[members_.front()])) {}

bool Patch::Predominates(const Vec3& p) const {
    double own = field_.TermValue(0, p);
    int ownIndex = members_.front();
    for (int j = 1; j < field_.Size(); ++j) {
        double other = field_.TermValue(j, p);
        if (other > own || (other == own && members_[j] < ownIndex)) return false;
    }
    return true;
}

std::vector<Patch> BuildPatches(const std::vector<FieldTerm>& terms, BlendMode mode,
                                const std::vector<std::pair<int, int>>& blendPairs,
                                const std::vector<std::pair<int, int>>& separatePairs) {
    int n = static_cast<int>(terms.size());
    std::vector<Bounds3> support(n);
    for (int i = 0; i < n; ++i) support[i] = TermSupportBounds(terms[i]);
    std::vector<std::vector<bool>> blends;
    if (mode == BlendMode::Explicit) {
        blends.assign(n, std::vector<bool>(n, false));
        for (auto [a, b] : blendPairs) {
            if (a < 0 || b < 0 || a >= n || b >= n || a == b) continue;
            blends[a][b] = blends[b][a] = true;
        }
    }
    auto separate = [&separatePairs](int i, int j) {
        for (auto [a, b] : separatePairs) {
            if ((a == i && b == j) || (a == j && b == i)) return true;
        }
        return false;
    };
    std::vector<Patch> patches;
    for (int i = 0; i < n; ++i) {
        if (!(terms[i].weight > 0)) continue;
        std::vector<int> members{i};
        for (int j = 0; j < n; ++j) {
            if (j == i || !BoxesOverlap(support[i], support[j])) continue;
            if (mode == BlendMode::Explicit && !blends[i][j]) continue;
            if (separate(i, j)) continue;
            members.push_back(j);
        }
        patches.emplace_back(terms, std::move(members));
    }
    return patches;
}

}  // namespace rs
