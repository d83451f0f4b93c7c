// Occlusion queries (Object::Occluded, the shadow rays' question) must give the same answer
// as the nearest-hit search for every primitive and aggregate: they only may stop earlier.
// The blocker they name must block the same ray.
#include <gtest/gtest.h>

#include "libcommon/constants.h"
#include "libcommon/random.h"
#include "libobj/blob.h"
#include "libobj/box.h"
#include "libobj/cone.h"
#include "libobj/csg.h"
#include "libobj/cylinder.h"
#include "libobj/disc.h"
#include "libobj/grid.h"
#include "libobj/heightfield.h"
#include "libobj/list.h"
#include "libobj/object.h"
#include "libobj/plane.h"
#include "libobj/polygon.h"
#include "libobj/sphere.h"
#include "libobj/torus.h"
#include "libobj/triangle.h"

namespace rs {
namespace {

double Uniform(Rng& rng, double lo, double hi) { return lo + (hi - lo) * rng.Uniform(); }
Vec3 RandomPoint(Rng& rng, double lo, double hi) {
    return {Uniform(rng, lo, hi), Uniform(rng, lo, hi), Uniform(rng, lo, hi)};
}
Vec3 RandomDirection(Rng& rng) {
    for (;;) {
        const Vec3 d = RandomPoint(rng, -1, 1);
        if (LengthSquared(d) > 1e-4 && LengthSquared(d) <= 1) return Normalize(d);
    }
}

std::shared_ptr<Object> Prim(std::shared_ptr<Primitive> p) { return Object::MakePrimitive(std::move(p)); }

std::shared_ptr<Object> Agg(std::shared_ptr<Aggregate> a, const std::vector<std::shared_ptr<Object>>& children) {
    for (const auto& c : children) a->AddChild(c);
    auto node = Object::MakeAggregate(std::move(a));
    node->PrepareFrame(0, 0);
    return node;
}

std::shared_ptr<Object> Instance(Rng& rng, std::shared_ptr<Object> of) {
    auto node = Object::MakeInstance(std::move(of));
    node->parentFromObject.Append(*Transform::Scale(RandomPoint(rng, 0.5, 1.5)));
    node->parentFromObject.Append(Transform::Translate(RandomPoint(rng, -1, 1)));
    node->PrepareFrame(0, 0);
    return node;
}

// One of each primitive type near `c`.
std::vector<std::shared_ptr<Object>> Primitives(Rng& rng, const Vec3& c) {
    const auto near = [&](double spread) { return c + RandomPoint(rng, -spread, spread); };
    std::vector<float> heights(16 * 16);
    for (float& h : heights) h = static_cast<float>(Uniform(rng, 0, 0.3));
    auto heightField = Object::MakeInstance(Prim(std::make_shared<HeightField>(16, heights)));
    heightField->parentFromObject.Append(Transform::Translate(near(1)));
    std::vector<std::shared_ptr<Object>> out = {
        Prim(std::make_shared<Sphere>(Uniform(rng, 0.2, 1), near(1))),
        Prim(std::make_shared<Box>(near(1), near(1))),
        Prim(std::make_shared<Cone>(Uniform(rng, 0.1, 0.5), near(1), Uniform(rng, 0.5, 1), near(1))),
        Prim(std::make_shared<Cylinder>(Uniform(rng, 0.1, 0.6), near(1), near(1))),
        Prim(std::make_shared<Disc>(Uniform(rng, 0.2, 1), near(1), RandomDirection(rng))),
        Prim(std::make_shared<Polygon>(std::vector<Vec3>{c, c + Vec3{1, 0, 0.2}, c + Vec3{1, 1, 0.4},
                                                         c + Vec3{0, 1, 0.2}},
                                       false)),
        Prim(std::make_shared<Triangle>(Triangle::Points{near(1), near(1), near(1)}, false)),
        Prim(std::make_shared<Torus>(Uniform(rng, 0.5, 1), Uniform(rng, 0.1, 0.3), near(1),
                                     RandomDirection(rng))),
        Prim(std::make_shared<Blob>(0.5, std::vector<Metaball>{{near(0.5), 0.6, 1}, {near(0.5), 0.5, 1}})),
        heightField,
    };
    for (auto& o : out) o->PrepareFrame(0, 0);
    return out;
}

// Nodes to query: each primitive, CSG of closed shapes, instances, a list, a grid, and a
// top-level list holding a plane, the grid, instances of the list and the CSG nodes (the
// grids: one walking its voxels, one its hierarchy, the top-level one choosing).
std::vector<std::shared_ptr<Object>> Nodes(Rng& rng) {
    std::vector<std::shared_ptr<Object>> nodes, all;
    for (int k = 0; k < 6; ++k) {
        auto prims = Primitives(rng, RandomPoint(rng, -3, 3));
        nodes.insert(nodes.end(), prims.begin(), prims.end());
        all.insert(all.end(), prims.begin(), prims.end());
    }
    std::vector<std::shared_ptr<Object>> csgs;
    for (auto op : {CsgAggregate::Op::Union, CsgAggregate::Op::Intersect, CsgAggregate::Op::Difference}) {
        const Vec3 c = RandomPoint(rng, -3, 3);
        csgs.push_back(Agg(std::make_shared<CsgAggregate>(op),
                           {Prim(std::make_shared<Sphere>(1, c)),
                            Prim(std::make_shared<Box>(c, c + RandomPoint(rng, -1.5, 1.5)))}));
    }
    auto list = Agg(std::make_shared<ListAggregate>(), all);
    auto grid = Agg(std::make_shared<GridAggregate>(5, 6, 7, GridAggregate::Search::Voxels), all);
    std::vector<std::shared_ptr<Object>> top = {Prim(std::make_shared<Plane>(Vec3{0, 0, -4}, Vec3{0, 0.3, 1})),
                                                grid, Instance(rng, list), Instance(rng, grid)};
    top.insert(top.end(), csgs.begin(), csgs.end());
    nodes.insert(nodes.end(), csgs.begin(), csgs.end());
    nodes.push_back(Instance(rng, csgs[2]));
    nodes.push_back(list);
    nodes.push_back(grid);
    nodes.push_back(Agg(std::make_shared<GridAggregate>(3, 3, 3), top));
    nodes.push_back(Agg(std::make_shared<GridAggregate>(5, 6, 7, GridAggregate::Search::Hierarchy), all));
    nodes.push_back(Agg(std::make_shared<ListAggregate>(), top));
    return nodes;
}

// Whether `target` is `node` or lies below it through nodes without transforms that are
// lists, grids or instances: where Object::Occluded may find the blocker it names.
bool ReachableThroughPlainNodes(const Object& node, const Object* target) {
    if (&node == target) return true;
    if (!node.parentFromObject.IsIdentity()) return false;
    if (const Object* of = node.instanceOf()) return ReachableThroughPlainNodes(*of, target);
    const Aggregate* aggregate = node.aggregate();
    if (aggregate == nullptr || dynamic_cast<const CsgAggregate*>(aggregate) != nullptr) return false;
    for (const auto& child : aggregate->Children())
        if (ReachableThroughPlainNodes(*child, target)) return true;
    return false;
}

TEST(Occlusion, AgreesWithTheNearestHitSearchOnRandomRays) {
    for (uint64_t seed = 1; seed <= 4; ++seed) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        Rng rng(seed);
        const auto nodes = Nodes(rng);
        int occluded = 0, clear = 0, namedBelow = 0, unnamed = 0, hitsNamed = 0;
        for (size_t n = 0; n < nodes.size(); ++n) {
            const Object& node = *nodes[n];
            for (int i = 0; i < 400; ++i) {
                const Vec3 origin = RandomPoint(rng, -7, 7);
                Vec3 dir = RandomDirection(rng);
                if (i % 2 == 0 && node.IsBounded())  // aimed near the node: many hits
                    dir = Normalize(node.BoundsInParent().Center() + RandomPoint(rng, -0.5, 0.5) - origin);
                const Ray ray{origin, dir * Uniform(rng, 0.5, 2), 0};
                const double tMin = rng.Uniform() < 0.3 ? Uniform(rng, 0, 4) : kShadowEpsilon;
                const double tMax = rng.Uniform() < 0.5 ? tMin + Uniform(rng, 0.1, 8) : kFar;
                HitRecord hit;
                double t = tMax;
                const bool nearest = node.Intersect(ray, tMin, t, hit);
                ASSERT_EQ(node.Occluded(ray, tMin, tMax), nearest)
                    << "node " << n << " (" << node.TypeName() << "), ray " << i;
                ++(nearest ? occluded : clear);
                // The primitive a nearest hit names, when it names one, blocks the same ray.
                if (const Object* primitive = nearest ? Object::PlainPathPrimitive(hit) : nullptr) {
                    ASSERT_TRUE(ReachableThroughPlainNodes(node, primitive));
                    ASSERT_TRUE(primitive->Occluded(ray, tMin, tMax));
                    ++hitsNamed;
                }
                // The blocker named is one the same ray is blocked by, in the node's parent
                // space (the shadow cache tests it on the world's ray).
                const Object* blocker = nullptr;
                ASSERT_EQ(node.Occluded(ray, tMin, tMax, &blocker), nearest);
                if (!nearest) continue;
                if (blocker == nullptr) {
                    ++unnamed;
                    continue;
                }
                ASSERT_NE(blocker->primitive(), nullptr);
                ASSERT_TRUE(ReachableThroughPlainNodes(node, blocker))
                    << "node " << n << " (" << node.TypeName() << "), ray " << i;
                ASSERT_TRUE(blocker->Occluded(ray, tMin, tMax))
                    << "node " << n << " (" << node.TypeName() << "), ray " << i << ", blocker "
                    << blocker->TypeName();
                if (blocker != &node) ++namedBelow;
            }
        }
        EXPECT_GT(occluded, 2000);
        EXPECT_GT(clear, 2000);
        // Aggregates name primitives below them; CSG and transformed aggregates name none.
        EXPECT_GT(namedBelow, 300);
        EXPECT_GT(unnamed, 100);
        EXPECT_GT(hitsNamed, 1000);
    }
}

}  // namespace
}  // namespace rs
