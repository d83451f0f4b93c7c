// Layer 8 of the implicit module: the settings of one implicit object, as its block and
// the command line give them: every method's root search settings (root_finding.h), the
// octree methods' heuristics (lg_octree.h) and the object's own. The registry's factories
// make a method from them.
#pragma once

#include <utility>
#include <vector>

#include "libobj/implicit/contact.h"
#include "libobj/implicit/lg_octree.h"
#include "libobj/implicit/patch.h"

namespace rs {

enum class ImplicitMethod { Patches, Kb89, March, Sphere, Segment, Polynomial, Exact, Auto };

// The member initializers (and those of RootSearchSettings and OctreeHeuristics) are the
// scene's defaults, the one table of them: the block reader starts from them
// (BlockSettings) and docs/implicit-reference.md documents them.
struct ImplicitOptions {
    double threshold = 1;
    // Every method's root accuracy.
    RootSearchSettings search;
    // The octree methods' heuristics (kb89's or the patches', MethodOctreeHeuristics).
    OctreeHeuristics octree;
    // Gascuel's Dratio as declared, restored when the method becomes Patches again.
    double patchesDRatio = OctreeHeuristics().dRatio;
    // `octree auto`: each patch's octree depth from its own skeleton's thickness
    // (PatchesMethod); otherwise octree.minDepth and maxDepth.
    bool autoDepth = true;
    // Auto until ChooseMethod resolves it (a primitive is made with a resolved method).
    ImplicitMethod method = ImplicitMethod::Auto;
    // The march step (object-space distance); <= 0: DefaultMarchStep.
    double marchStep = 0;
    // The declared blend graph; used only in patches mode.
    BlendMode blendMode = BlendMode::Automatic;
    std::vector<std::pair<int, int>> blendPairs;  // term indices, Explicit mode only
    // Colliding patches and their attenuation zones (contact.h); patches mode only.
    std::vector<ContactPair> contacts;
    std::vector<Propagation> propagations;
    // `contact auto`: at each build (each frame) every pair of positive skeletons that do
    // not blend and whose undeformed patch volumes interpenetrate (VolumesInterpenetrate)
    // is put in contact too, besides the declared pairs.
    bool autoContacts = false;
};

}  // namespace rs
