// The viewing setup of spec §3.2: screen vectors, the half-pixel footprint convention, and
// depth of field. Screen coordinates (sx, sy) span [0, xres] × [0, yres] with sy growing
// DOWNWARD (row 0 is the top row, as in the original's mtv output, which our PNG follows).
#pragma once

#include "libcommon/ray.h"
#include "libshade/scene.h"

namespace rs {

class CameraSetup {
  public:
    // Validates the camera (view and up directions must not be parallel, stereo needs an
    // eye separation) and reports Abort through the error sink when they are not.
    CameraSetup(const Camera& camera, const RenderOptions& options);

    // The eye ray through screen point (sx, sy); (lensX, lensY) ∈ [−1,1]² is the square-lens
    // sample, ignored for a pinhole camera. The direction is unit length; the footprint
    // (ray.h) is the pixel's: width 0 at the eye, spread the pixel's angular size.
    Ray EyeRay(double sx, double sy, double lensX, double lensY, double time) const;

    bool HasAperture() const { return aperture_ > 0; }

  private:
    Vec3 eye_;
    Vec3 right_, up_;     // r̂, û
    Vec3 corner_;         // F0: direction from the eye to the screen's top-left corner
    Vec3 dx_, dy_;        // one pixel along x and (downward) along y
    double screenDist_ = 1;  // distance from the eye to the screen centre (|gaze·dist|)
    double pixelSpan_ = 0;   // min(|dx|, |dy|)·screenDist: the footprint spread is this / ℓ²
    double aperture_ = 0;
    double focalDist_ = 1;
};

}  // namespace rs
