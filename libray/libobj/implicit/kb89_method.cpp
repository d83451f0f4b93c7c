#include "libobj/implicit/kb89_method.h"

namespace rs {

Kb89Method::Kb89Method(const Field& whole, double threshold, const OctreeSettings& settings,
                       const ImplicitObjectStats& stats)
    : whole_(whole), threshold_(threshold), settings_(settings), stats_(stats) {
    box_ = PositiveSupportBounds(whole);
}

std::optional<double> Kb89Method::FirstRoot(const Ray& ray, double tMin, double tMax) const {
    const LGOctree& tree = tree_.Get([this] {
        return stats_.BuildTree([this] { return LGOctree(whole_, threshold_, box_, settings_); });
    });
    return tree.FirstRoot(ray, tMin, tMax);
}

}  // namespace rs
