#include "rayshade/camera.h"

#include <algorithm>
#include <cmath>

#include "libcommon/constants.h"
#include "libcommon/error.h"

namespace rs {

CameraSetup::CameraSetup(const Camera& camera, const RenderOptions& options) {
    eye_ = camera.eye;
    Vec3 lookAt = camera.lookAt;
    auto frame = [&](Vec3& gaze, double& dist) {
        Vec3 d = lookAt - eye_;
        dist = Length(d);
        gaze = dist > 0 ? d / dist : Vec3{};
        Vec3 r = Cross(gaze, camera.up);
        if (!(dist > 0))
            Report(Severity::Abort, camera.viewStatement,
                   "view and up directions are identical: eyep and lookp are the same point");
        if (!(Length(r) > 0))
            Report(Severity::Abort, camera.viewStatement,
                   "view and up directions are identical: up is parallel to lookp - eyep");
        right_ = Normalize(r);
        up_ = Normalize(Cross(right_, gaze));
    };
    Vec3 gaze;
    double dist = 0;
    frame(gaze, dist);
    if (options.eyeSepSide != 0) {
        if (camera.eyeSep < 0)
            Report(Severity::Abort, {}, "stereo rendering (-l/-r) needs an eye separation (eyesep or -E)");
        // Toe-in stereo: move the eye sideways, keep aiming at the same point.
        eye_ = eye_ + right_ * (options.eyeSepSide * camera.eyeSep * 0.5);
        frame(gaze, dist);
    }

    double hfov = camera.hfov;
    // The original derives vfov linearly (spec §3.2, kept for compatibility).
    double vfov = camera.vfov > 0 ? camera.vfov : hfov * options.yres / options.xres;
    Vec3 d = gaze * dist;
    screenDist_ = dist;
    dx_ = right_ * (2 * dist * std::tan(hfov * kPi / 360) / options.xres);
    dy_ = -up_ * (2 * dist * std::tan(vfov * kPi / 360) / options.yres);
    corner_ = d - dx_ * (options.xres / 2.0) - dy_ * (options.yres / 2.0);
    pixelSpan_ = std::min(Length(dx_), Length(dy_)) * screenDist_;

    aperture_ = camera.aperture;
    focalDist_ = camera.focalDist > 0 ? camera.focalDist : dist;
}

Ray CameraSetup::EyeRay(double sx, double sy, double lensX, double lensY, double time) const {
    const Vec3 toScreen = corner_ + dx_ * sx + dy_ * sy;
    // ℓ = |toScreen| serves both the direction and the footprint (one square root per ray).
    const double ell = Length(toScreen);
    Vec3 dir = ell > 0 ? toScreen / ell : Vec3{};
    Ray ray{eye_, dir, time};
    if (aperture_ > 0) {
        // Thin lens: aim from a point of the (square) lens at the pinhole ray's point on the
        // focal plane.
        Vec3 offset = (right_ * lensX + up_ * lensY) * aperture_;
        ray = {eye_ + offset, Normalize(dir * focalDist_ - offset), time};
    }
    // Footprint (ray.h): the pixel seen from the eye. At the screen point, at distance
    // ℓ from the eye, a pixel spans |dx| by |dy|, foreshortened across the ray by
    // cos θ = screenDist/ℓ at most; so the beam widens by at least min(|dx|, |dy|)·cos θ/ℓ
    // = pixelSpan/ℓ² per unit of distance, from 0 at a pinhole. (With a lens the beam of
    // one lens sample is the same pixel cone, through the focal point.)
    if (ell > 0) ray.footprintSpread = pixelSpan_ / (ell * ell);
    return ray;
}

}  // namespace rs
