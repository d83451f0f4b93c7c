#include "libobj/implicit/field_motion.h"

#include <atomic>
#include <cmath>
#include <limits>
#include <utility>

#include "libobj/implicit/field.h"

namespace rs {

namespace {

using field_motion_detail::tRayTime;

// A few caches per thread (one per moving object a ray meets), least recently used first
// to go: bounded memory, however many frames and objects come and go.
constexpr size_t kCachesPerThread = 8;

std::atomic<uint64_t> gNextMotionId{1};

}  // namespace

FieldMotion::FieldMotion(std::vector<TermMotion> terms, TermAt termAt)
    : terms_(std::move(terms)), termAt_(std::move(termAt)), id_(gNextMotionId++) {}

TermsAtTime* FieldMotion::FindNow() const {
    field_motion_detail::ThreadRayTime& now = tRayTime;
    const double time = now.time;
    now.lastId = id_;
    now.lastChanges = now.changes;
    now.last = nullptr;
    if (std::isnan(time)) return nullptr;
    thread_local std::vector<TermsAtTime> caches;
    // Never reallocated (at most kCachesPerThread), so `now.last` stays valid.
    if (caches.capacity() < kCachesPerThread) caches.reserve(kCachesPerThread);
    thread_local uint64_t clock = 0;
    thread_local size_t last = 0;  // the cache found last time: most lookups ask it again
    TermsAtTime* found = last < caches.size() && caches[last].id_ == id_ ? &caches[last] : nullptr;
    if (!found) {
        ++clock;
        TermsAtTime* oldest = nullptr;
        for (TermsAtTime& c : caches) {
            if (c.id_ == id_) {
                found = &c;
                break;
            }
            if (!oldest || c.lastUse_ < oldest->lastUse_) oldest = &c;
        }
        if (!found) {
            found = caches.size() < kCachesPerThread ? &caches.emplace_back() : oldest;
            found->id_ = id_;
            found->time_ = std::numeric_limits<double>::quiet_NaN();
            found->stamp_.assign(terms_.size(), 0);
            found->terms_.assign(terms_.size(), FieldTerm{});
        }
        found->motion_ = this;
        found->lastUse_ = clock;
        last = static_cast<size_t>(found - caches.data());
    }
    if (!(found->time_ == time)) {
        found->time_ = time;
        ++found->epoch_;
    }
    now.last = found;
    return found;
}

const FieldTerm& TermsAtTime::Make(int row, const FieldTerm& reference) {
    if (!motion_->terms_[row].moving) return reference;
    FieldTerm& term = terms_[row];
    if (stamp_[row] == 0) term = reference;  // the name (and any static part), once
    motion_->termAt_(row, time_, term);
    stamp_[row] = epoch_;
    return term;
}

const FieldTerm& FieldMotion::Resolve(int row, const FieldTerm& reference) const {
    if (!terms_[row].moving) return reference;
    TermsAtTime* now = Now();
    return now ? now->Of(row, reference) : reference;
}

RayTimeScope::RayTimeScope(double time) : previous_(tRayTime.time) {
    tRayTime.time = time;
    ++tRayTime.changes;
}
RayTimeScope::~RayTimeScope() {
    tRayTime.time = previous_;
    ++tRayTime.changes;
}

}  // namespace rs
