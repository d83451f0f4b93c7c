// Evaluation of Embree 3 on the SPD scenes (issue 15): how fast Intel's kernels build and
// trace the same geometry our renderer traces, and how precise their single-precision hits
// are. Not part of the renderer: built only with -DRAYSHADE_EMBREE_EVAL=ON (needs
// libembree-dev) and driven by bench/embree.sh, which compares the hits with ours.
//
// It reads the generated SPD files only (their own small subset of the language: `eyep`,
// `lookp`, `up`, `fov`, `screen`, `light ... point X Y Z`, and objects `triangle SURF` with 9
// or 18 numbers, `polygon SURF` with its vertices, `sphere SURF R X Y Z`; everything else is
// skipped). Polygons are split into a fan of triangles, which is exact for the convex
// polygons of balls, mount, teapot and tetra (not for gears' outlines: the tool refuses
// scenes with polygons of more than 4 vertices rather than misrepresent them). Cones are
// refused too (tree): Embree has no capped cone.
//
// It traces, single-threaded, one eye ray per pixel through a pinhole camera (rtcIntersect1,
// then again in packets of 8 rays with rtcIntersect8) and, from every eye hit, one shadow ray
// per point light (rtcOccluded1), and prints the CPU seconds of the build and of each
// trace. With --rays FILE it writes every 64th eye ray with Embree's answer (origin,
// direction, then `hit T` or `miss`) for the comparison with rayquery.
#include <embree3/rtcore.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Vec {
    double x = 0, y = 0, z = 0;
};
Vec operator-(Vec a, Vec b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec operator+(Vec a, Vec b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec operator*(Vec a, double s) { return {a.x * s, a.y * s, a.z * s}; }
Vec Cross(Vec a, Vec b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
Vec Normalized(Vec a) { return a * (1 / std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z)); }

struct SpdScene {
    Vec eye, look{0, 0, -1}, up{0, 0, 1};
    double fov = 45;
    int width = 512, height = 512;
    std::vector<Vec> lights;
    std::vector<float> vertices;     // x y z per vertex
    std::vector<unsigned> triangles;  // three vertex indices per triangle
    std::vector<float> spheres;      // x y z r per sphere
};

double CpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

[[noreturn]] void Fail(const std::string& message) {
    std::fprintf(stderr, "embree_eval: %s\n", message.c_str());
    std::exit(1);
}

bool IsNumber(const std::string& word) {
    char* end = nullptr;
    std::strtod(word.c_str(), &end);
    return !word.empty() && *end == '\0';
}

// Reads the SPD subset described at the top. Words are read one at a time; an object's
// numbers run until the next word that is not a number.
SpdScene ReadScene(const char* path) {
    std::ifstream in(path);
    if (!in) Fail(std::string("cannot read ") + path);
    SpdScene scene;
    std::vector<std::string> words;
    for (std::string w; in >> w;) words.push_back(w);
    size_t i = 0;
    auto numbersAfter = [&](size_t from, std::vector<double>& out) {
        out.clear();
        size_t k = from;
        while (k < words.size() && IsNumber(words[k])) out.push_back(std::atof(words[k++].c_str()));
        return k;
    };
    std::vector<double> n;
    auto vec = [&](size_t k) { return Vec{n[k], n[k + 1], n[k + 2]}; };
    auto addVertex = [&](Vec p) {
        scene.vertices.insert(scene.vertices.end(), {static_cast<float>(p.x),
                                                     static_cast<float>(p.y),
                                                     static_cast<float>(p.z)});
        return static_cast<unsigned>(scene.vertices.size() / 3 - 1);
    };
    while (i < words.size()) {
        const std::string& w = words[i];
        // The surface name after an object keyword, when there is one.
        size_t args = i + 1;
        if ((w == "triangle" || w == "polygon" || w == "sphere" || w == "cone") &&
            args < words.size() && !IsNumber(words[args])) {
            ++args;
        }
        if (w == "eyep" || w == "lookp" || w == "up") {
            i = numbersAfter(i + 1, n);
            if (n.size() < 3) Fail(w + " needs 3 numbers");
            (w == "eyep" ? scene.eye : w == "lookp" ? scene.look : scene.up) = vec(0);
        } else if (w == "fov") {
            i = numbersAfter(i + 1, n);
            if (n.empty()) Fail("fov needs a number");
            scene.fov = n[0];
        } else if (w == "screen") {
            i = numbersAfter(i + 1, n);
            if (n.size() < 2) Fail("screen needs 2 numbers");
            scene.width = static_cast<int>(n[0]);
            scene.height = static_cast<int>(n[1]);
        } else if (w == "point" && i > 0) {
            // `light I point X Y Z` (the intensity before `point` is not needed)
            i = numbersAfter(i + 1, n);
            if (n.size() >= 3) scene.lights.push_back(vec(0));
        } else if (w == "triangle") {
            i = numbersAfter(args, n);
            if (n.size() != 9 && n.size() != 18) Fail("triangle with neither 9 nor 18 numbers");
            const int stride = n.size() == 18 ? 6 : 3;  // with normals: p n p n p n
            for (int v = 0; v < 3; ++v) scene.triangles.push_back(addVertex(vec(v * stride)));
        } else if (w == "polygon") {
            i = numbersAfter(args, n);
            if (n.size() % 3 != 0 || n.size() < 9) Fail("polygon with a bad vertex list");
            if (n.size() > 12) Fail("polygon of more than 4 vertices (not evaluated: gears)");
            const unsigned first = addVertex(vec(0));
            unsigned previous = addVertex(vec(3));
            for (size_t v = 6; v < n.size(); v += 3) {
                const unsigned next = addVertex(vec(v));
                scene.triangles.insert(scene.triangles.end(), {first, previous, next});
                previous = next;
            }
        } else if (w == "sphere") {
            i = numbersAfter(args, n);
            if (n.size() != 4) Fail("sphere needs 4 numbers");
            scene.spheres.insert(scene.spheres.end(),
                                 {static_cast<float>(n[1]), static_cast<float>(n[2]),
                                  static_cast<float>(n[3]), static_cast<float>(n[0])});
        } else if (w == "cone" || w == "cylinder" || w == "box" || w == "torus" ||
                   w == "disc" || w == "heightfield") {
            Fail(w + " is not evaluated (no matching Embree primitive)");
        } else {
            ++i;
        }
    }
    return scene;
}

template <class T>
void Fill(RTCGeometry geometry, RTCBufferType type, RTCFormat format, const std::vector<T>& data,
          size_t itemSize) {
    void* buffer = rtcSetNewGeometryBuffer(geometry, type, 0, format, itemSize,
                                           data.size() * sizeof(T) / itemSize);
    std::memcpy(buffer, data.data(), data.size() * sizeof(T));
}

RTCScene Build(RTCDevice device, const SpdScene& s, bool robust) {
    RTCScene scene = rtcNewScene(device);
    if (robust) rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    if (!s.triangles.empty()) {
        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        Fill(g, RTC_BUFFER_TYPE_VERTEX, RTC_FORMAT_FLOAT3, s.vertices, 3 * sizeof(float));
        Fill(g, RTC_BUFFER_TYPE_INDEX, RTC_FORMAT_UINT3, s.triangles, 3 * sizeof(unsigned));
        rtcCommitGeometry(g);
        rtcAttachGeometry(scene, g);
        rtcReleaseGeometry(g);
    }
    if (!s.spheres.empty()) {
        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
        Fill(g, RTC_BUFFER_TYPE_VERTEX, RTC_FORMAT_FLOAT4, s.spheres, 4 * sizeof(float));
        rtcCommitGeometry(g);
        rtcAttachGeometry(scene, g);
        rtcReleaseGeometry(g);
    }
    rtcCommitScene(scene);
    return scene;
}

// The eye ray of pixel (x, y): a pinhole at eyep looking at lookp, horizontal field of
// view `fov` degrees, pixel centres.
struct Camera {
    Vec eye, forward, right, upward;
    Camera(const SpdScene& s) : eye(s.eye) {
        forward = Normalized(s.look - s.eye);
        right = Normalized(Cross(forward, s.up));
        upward = Cross(right, forward);
        const double half = std::tan(s.fov * M_PI / 360);
        right = right * half;
        upward = upward * (half * s.height / s.width);
    }
    Vec Direction(const SpdScene& s, int x, int y) const {
        const double u = 2 * (x + 0.5) / s.width - 1, v = 1 - 2 * (y + 0.5) / s.height;
        return Normalized(forward + right * u + upward * v);
    }
};

void SetRay(RTCRay& ray, Vec o, Vec d, float tfar) {
    ray.org_x = static_cast<float>(o.x);
    ray.org_y = static_cast<float>(o.y);
    ray.org_z = static_cast<float>(o.z);
    ray.dir_x = static_cast<float>(d.x);
    ray.dir_y = static_cast<float>(d.y);
    ray.dir_z = static_cast<float>(d.z);
    ray.tnear = 0;
    ray.tfar = tfar;
    ray.time = 0;
    ray.mask = ~0u;
    ray.id = 0;
    ray.flags = 0;
}

}  // namespace

int main(int argc, char** argv) {
    const char* path = nullptr;
    const char* raysOut = nullptr;
    bool robust = false;
    for (int k = 1; k < argc; ++k) {
        if (!std::strcmp(argv[k], "--rays") && k + 1 < argc) {
            raysOut = argv[++k];
        } else if (!std::strcmp(argv[k], "--robust")) {
            robust = true;
        } else if (argv[k][0] != '-' && !path) {
            path = argv[k];
        } else {
            Fail("usage: embree_eval [--robust] [--rays FILE] SCENE.ray");
        }
    }
    if (!path) Fail("usage: embree_eval [--robust] [--rays FILE] SCENE.ray");
    double start = CpuSeconds();
    const SpdScene s = ReadScene(path);
    const double readSeconds = CpuSeconds() - start;

    RTCDevice device = rtcNewDevice("threads=1");
    if (!device) Fail("rtcNewDevice failed");
    start = CpuSeconds();
    RTCScene scene = Build(device, s, robust);
    const double buildSeconds = CpuSeconds() - start;

    const Camera camera(s);
    RTCIntersectContext context;
    std::vector<float> hitT(static_cast<size_t>(s.width) * s.height, -1);
    start = CpuSeconds();
    for (int y = 0; y < s.height; ++y) {
        for (int x = 0; x < s.width; ++x) {
            RTCRayHit rh;
            SetRay(rh.ray, camera.eye, camera.Direction(s, x, y), INFINITY);
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rtcInitIntersectContext(&context);
            rtcIntersect1(scene, &context, &rh);
            if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) hitT[y * s.width + x] = rh.ray.tfar;
        }
    }
    const double eyeSeconds = CpuSeconds() - start;

    // The same eye rays in packets of 8 along each row.
    start = CpuSeconds();
    size_t packetHits = 0;
    for (int y = 0; y < s.height; ++y) {
        for (int x0 = 0; x0 < s.width; x0 += 8) {
            alignas(32) RTCRayHit8 rh;
            alignas(32) int valid[8];
            for (int l = 0; l < 8; ++l) {
                const int x = x0 + l;
                valid[l] = x < s.width ? -1 : 0;
                const Vec d = camera.Direction(s, x < s.width ? x : s.width - 1, y);
                rh.ray.org_x[l] = static_cast<float>(camera.eye.x);
                rh.ray.org_y[l] = static_cast<float>(camera.eye.y);
                rh.ray.org_z[l] = static_cast<float>(camera.eye.z);
                rh.ray.dir_x[l] = static_cast<float>(d.x);
                rh.ray.dir_y[l] = static_cast<float>(d.y);
                rh.ray.dir_z[l] = static_cast<float>(d.z);
                rh.ray.tnear[l] = 0;
                rh.ray.tfar[l] = INFINITY;
                rh.ray.time[l] = 0;
                rh.ray.mask[l] = ~0u;
                rh.ray.id[l] = l;
                rh.ray.flags[l] = 0;
                rh.hit.geomID[l] = RTC_INVALID_GEOMETRY_ID;
            }
            rtcInitIntersectContext(&context);
            rtcIntersect8(valid, scene, &context, &rh);
            for (int l = 0; l < 8; ++l) {
                packetHits += valid[l] && rh.hit.geomID[l] != RTC_INVALID_GEOMETRY_ID;
            }
        }
    }
    const double packetSeconds = CpuSeconds() - start;

    // One shadow ray per eye hit and point light, from the hit point towards the light.
    start = CpuSeconds();
    size_t shadowRays = 0, blocked = 0, eyeHits = 0;
    for (int y = 0; y < s.height; ++y) {
        for (int x = 0; x < s.width; ++x) {
            const float t = hitT[y * s.width + x];
            if (t < 0) continue;
            ++eyeHits;
            const Vec p = camera.eye + camera.Direction(s, x, y) * t;
            for (const Vec& light : s.lights) {
                const Vec toLight = light - p;
                const double distance =
                    std::sqrt(toLight.x * toLight.x + toLight.y * toLight.y + toLight.z * toLight.z);
                RTCRay ray;
                SetRay(ray, p, toLight * (1 / distance), static_cast<float>(distance));
                ray.tnear = 1e-4f;
                rtcInitIntersectContext(&context);
                rtcOccluded1(scene, &context, &ray);
                ++shadowRays;
                blocked += ray.tfar < 0;  // rtcOccluded1 sets tfar to -inf when blocked
            }
        }
    }
    const double shadowSeconds = CpuSeconds() - start;

    std::printf("triangles %zu spheres %zu lights %zu%s\n", s.triangles.size() / 3,
                s.spheres.size() / 4, s.lights.size(), robust ? " (robust build)" : "");
    std::printf("read %.3f s  build %.3f s\n", readSeconds, buildSeconds);
    std::printf("eye rays %d x %d: %zu hits, rtcIntersect1 %.3f s, rtcIntersect8 %.3f s "
                "(%zu hits)\n",
                s.width, s.height, eyeHits, eyeSeconds, packetSeconds, packetHits);
    std::printf("shadow rays %zu (%zu blocked): rtcOccluded1 %.3f s\n", shadowRays, blocked,
                shadowSeconds);
    std::printf("figures build %.4f eye %.4f packet %.4f shadow %.4f rays %zu\n", buildSeconds,
                eyeSeconds, packetSeconds, shadowSeconds,
                static_cast<size_t>(s.width) * s.height + shadowRays);

    if (raysOut) {
        std::ofstream out(raysOut);
        for (int k = 0; k < s.width * s.height; k += 64) {
            const int x = k % s.width, y = k / s.width;
            const Vec d = camera.Direction(s, x, y);
            out.precision(17);
            out << camera.eye.x << ' ' << camera.eye.y << ' ' << camera.eye.z << ' ' << d.x << ' '
                << d.y << ' ' << d.z << ' ';
            if (hitT[k] < 0) {
                out << "miss\n";
            } else {
                out << "hit " << hitT[k] << '\n';
            }
        }
        if (!out) Fail(std::string("cannot write ") + raysOut);
    }
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
    return 0;
}
