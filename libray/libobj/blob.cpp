#include "libobj/blob.h"

#include <utility>

#include "libcommon/constants.h"

namespace rs {

Blob::Blob(double threshold, std::vector<Metaball> balls) : sum_(threshold, std::move(balls)) {}

std::shared_ptr<Primitive> Blob::Create(ArgReader& args) {
    double threshold = args.ReadNumber();
    std::vector<Metaball> balls;
    bool degenerate = false;
    while (args.PeekNumber()) {
        Metaball b;
        b.strength = args.ReadNumber();
        b.radius = args.ReadNumber();
        b.centre = args.ReadVector();
        degenerate = degenerate || b.strength < kEpsilon || b.radius < kEpsilon;
        balls.push_back(b);
    }
    if (balls.empty() || degenerate) {
        args.Warn(balls.empty() ? "blob without metaballs, discarded"
                                : "blob with a strength or radius below 1e-5, discarded");
        return nullptr;
    }
    return std::make_shared<Blob>(threshold, std::move(balls));
}

const IntersectionCounters& Blob::Counters() const {
    static const IntersectionCounters counters("Blob");
    return counters;
}

bool Blob::Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const {
    std::optional<double> t = sum_.FirstRoot(ray, tMin, tMax);
    if (!t) return false;
    hit.t = *t;
    return true;
}

SurfaceNormals Blob::Normal(const Vec3& p, const PrimitiveHit&) const {
    Vec3 n = Normalize(-sum_.Gradient(p));
    if (LengthSquared(n) == 0) n = {0, 0, 1};  // a zero gradient (pinch point): any direction
    return {n, n, false};
}

}  // namespace rs
