#include "libobj/implicit/field_motion.h"

#include <atomic>
#include <cmath>
#include <limits>
#include <utility>

#include "libobj/implicit/field.h"

namespace rs {

namespace {

thread_local double tRayTime = std::numeric_limits<double>::quiet_NaN();

// One thread's terms of one FieldMotion at one time: row r is current when stamp[r] ==
// epoch; a new time bumps the epoch (O(1)), so stale rows are remade on their next use.
struct TermCache {
    uint64_t id = 0;
    double time = std::numeric_limits<double>::quiet_NaN();
    uint64_t epoch = 1;
    uint64_t lastUse = 0;
    std::vector<uint64_t> stamp;  // 0: the row's slot holds no term yet
    std::vector<FieldTerm> terms;
};

// A few caches per thread (one per moving object a ray meets), least recently used first
// to go: bounded memory, however many frames and objects come and go.
constexpr size_t kCachesPerThread = 8;

TermCache& CacheFor(uint64_t id, size_t rows) {
    thread_local std::vector<TermCache> caches;
    thread_local uint64_t clock = 0;
    thread_local size_t last = 0;  // the cache found last time: every term of a sum asks
    if (last < caches.size() && caches[last].id == id) return caches[last];
    ++clock;
    TermCache* oldest = nullptr;
    for (TermCache& c : caches) {
        if (c.id == id) {
            c.lastUse = clock;
            last = static_cast<size_t>(&c - caches.data());
            return c;
        }
        if (!oldest || c.lastUse < oldest->lastUse) oldest = &c;
    }
    TermCache& c = caches.size() < kCachesPerThread ? caches.emplace_back() : *oldest;
    last = static_cast<size_t>(&c - caches.data());
    c.id = id;
    c.time = std::numeric_limits<double>::quiet_NaN();
    c.lastUse = clock;
    c.stamp.assign(rows, 0);
    c.terms.assign(rows, FieldTerm{});
    return c;
}

std::atomic<uint64_t> gNextMotionId{1};

}  // namespace

FieldMotion::FieldMotion(std::vector<TermMotion> terms, TermAt termAt)
    : terms_(std::move(terms)), termAt_(std::move(termAt)), id_(gNextMotionId++) {}

const FieldTerm& FieldMotion::Resolve(int row, const FieldTerm& reference) const {
    const double time = tRayTime;
    if (!terms_[row].moving || std::isnan(time)) return reference;
    TermCache& cache = CacheFor(id_, terms_.size());
    if (!(cache.time == time)) {
        cache.time = time;
        ++cache.epoch;
    }
    FieldTerm& term = cache.terms[row];
    if (cache.stamp[row] != cache.epoch) {
        if (cache.stamp[row] == 0) term = reference;  // name and kernel, once
        termAt_(row, time, term);
        cache.stamp[row] = cache.epoch;
    }
    return term;
}

RayTimeScope::RayTimeScope(double time) : previous_(tRayTime) { tRayTime = time; }
RayTimeScope::~RayTimeScope() { tRayTime = previous_; }

}  // namespace rs
