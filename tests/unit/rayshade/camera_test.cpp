#include "rayshade/camera.h"

#include <gtest/gtest.h>

#include <cmath>

#include "libcommon/constants.h"
#include "libcommon/error.h"
#include "rayshade/renderer.h"

namespace rs {
namespace {

TEST(Camera, ScreenCentreLooksAtLookPoint) {
    Camera cam;  // eye (0,-10,0) looking at the origin, z up
    RenderOptions o;
    o.xres = o.yres = 100;
    CameraSetup setup(cam, o);
    Ray r = setup.EyeRay(50, 50, 0, 0, 0);
    EXPECT_NEAR(r.dir.x, 0, 1e-12);
    EXPECT_NEAR(r.dir.y, 1, 1e-12);
    EXPECT_NEAR(r.dir.z, 0, 1e-12);
}

TEST(Camera, ScreenEdgesSpanTheHorizontalFieldOfView) {
    Camera cam;
    cam.hfov = 60;
    RenderOptions o;
    o.xres = 200;
    o.yres = 100;
    CameraSetup setup(cam, o);
    Ray left = setup.EyeRay(0, 50, 0, 0, 0), right = setup.EyeRay(200, 50, 0, 0, 0);
    double angle = std::acos(Dot(left.dir, right.dir)) * 180 / kPi;
    EXPECT_NEAR(angle, 60, 1e-9);
    // Left edge is at −x (right-handed, z up, looking along +y: +x is to the right).
    EXPECT_LT(left.dir.x, 0);
    EXPECT_GT(right.dir.x, 0);
}

TEST(Camera, RowZeroIsTheTopOfThePicture) {
    Camera cam;
    RenderOptions o;
    o.xres = o.yres = 64;
    CameraSetup setup(cam, o);
    EXPECT_GT(setup.EyeRay(32, 0, 0, 0, 0).dir.z, 0);
    EXPECT_LT(setup.EyeRay(32, 64, 0, 0, 0).dir.z, 0);
}

TEST(Camera, VerticalFovDerivesLinearlyFromHorizontal) {
    // vfov = hfov·yres/xres in degrees (spec §3.2), so a 2:1 image at 60° gets 30°.
    Camera cam;
    cam.hfov = 60;
    RenderOptions o;
    o.xres = 200;
    o.yres = 100;
    CameraSetup setup(cam, o);
    Ray top = setup.EyeRay(100, 0, 0, 0, 0), bottom = setup.EyeRay(100, 100, 0, 0, 0);
    EXPECT_NEAR(std::acos(Dot(top.dir, bottom.dir)) * 180 / kPi, 30, 1e-9);
}

TEST(Camera, ParallelUpIsAnError) {
    Camera cam;
    cam.up = {0, 1, 0};  // along the view direction
    RenderOptions o;
    EXPECT_THROW(CameraSetup(cam, o).HasAperture(), FatalError);
}

TEST(Camera, LensRaysConvergeOnTheFocalPlane) {
    Camera cam;
    cam.aperture = 0.5;
    cam.focalDist = 10;
    RenderOptions o;
    o.xres = o.yres = 10;
    CameraSetup setup(cam, o);
    Ray a = setup.EyeRay(3, 7, -1, 1, 0), b = setup.EyeRay(3, 7, 0.5, -0.25, 0);
    Ray pin = setup.EyeRay(3, 7, 0, 0, 0);
    // Every lens ray passes through the pinhole ray's point at distance 10 along it.
    Vec3 focus = pin.At(10);
    for (const Ray& r : {a, b}) {
        Vec3 toFocus = focus - r.origin;
        EXPECT_NEAR(Length(Cross(toFocus, r.dir)), 0, 1e-9);
    }
}

TEST(Camera, EyeRaysCarryThePixelFootprint) {
    Camera cam;  // eye 10 from the look point; hfov 90: the screen at distance d is 2d wide
    cam.hfov = 90;
    RenderOptions o;
    o.xres = o.yres = 100;
    CameraSetup setup(cam, o);
    Ray centre = setup.EyeRay(50, 50, 0, 0, 0);
    EXPECT_EQ(centre.footprintWidth, 0);
    EXPECT_NEAR(centre.footprintSpread, 2.0 / 100, 1e-12);  // pixel 2d/100 seen from d
    // At the left edge (45° off axis) the pixel is √2 farther and foreshortened by
    // cos 45°: spread (2d/100)·cos45°/(d√2) = 0.01.
    Ray edge = setup.EyeRay(0, 50, 0, 0, 0);
    EXPECT_NEAR(edge.footprintSpread, 0.01, 1e-12);
}

TEST(Window, CropSelectsFractionOfScreen) {
    RenderOptions o;
    o.xres = 101;
    o.yres = 51;
    o.crop[0] = 0.5;  // left half cut off
    RenderWindow w = ComputeWindow(o);
    EXPECT_EQ(w.minX, 50);
    EXPECT_EQ(w.maxX, 100);
    EXPECT_EQ(w.Height(), 51);
}

TEST(Window, OutsideScreenIsAnError) {
    RenderOptions o;
    o.xres = o.yres = 10;
    o.window[0] = 0;
    o.window[1] = 10;  // one past the last column
    o.window[2] = 0;
    o.window[3] = 9;
    EXPECT_THROW(ComputeWindow(o), FatalError);
}

// ---- Stereo (spec §3.2): the eye moves by ∓eyesep/2 along r̂ and aims at the same point ----

TEST(Stereo, EyesMoveHalfTheSeparationAlongTheRightVector) {
    // Default view: eye (0,−10,0) looking at the origin with z up, so r̂ = +x.
    Camera cam;
    cam.eyeSep = 2;
    RenderOptions o;
    o.xres = o.yres = 64;
    for (int side : {-1, 1}) {
        o.eyeSepSide = side;
        CameraSetup setup(cam, o);
        Ray centre = setup.EyeRay(32, 32, 0, 0, 0);
        EXPECT_NEAR(centre.origin.x, side * 1.0, 1e-12);  // left −1, right +1
        EXPECT_NEAR(centre.origin.y, -10, 1e-12);
        EXPECT_NEAR(centre.origin.z, 0, 1e-12);
        // Toe-in: the screen centre still looks at the look point.
        Vec3 toLook = Normalize(Vec3{0, 0, 0} - centre.origin);
        EXPECT_NEAR(Dot(centre.dir, toLook), 1, 1e-12);
    }
}

TEST(Stereo, SeparationIsMeasuredAcrossAnObliqueView) {
    // Looking from (4,4,1) at the origin: r̂ = normalize(ĝ × up) is horizontal and
    // perpendicular to the view.
    Camera cam;
    cam.eye = {4, 4, 1};
    cam.lookAt = {0, 0, 0};
    cam.eyeSep = 0.5;
    RenderOptions o;
    o.xres = o.yres = 10;
    o.eyeSepSide = -1;
    Ray left = CameraSetup(cam, o).EyeRay(5, 5, 0, 0, 0);
    o.eyeSepSide = 1;
    Ray right = CameraSetup(cam, o).EyeRay(5, 5, 0, 0, 0);
    Vec3 between = right.origin - left.origin;
    EXPECT_NEAR(Length(between), 0.5, 1e-12);
    EXPECT_NEAR(between.z, 0, 1e-12);                        // horizontal (up is z)
    EXPECT_NEAR(Dot(between, Vec3{-4, -4, -1}), 0, 1e-12);   // across the view
    // ĝ × up for ĝ ∝ (−4,−4,−1), up = z: ∝ (−4, 4, 0); the right eye is on that side.
    EXPECT_GT(Dot(between, Vec3{-1, 1, 0}), 0);
    Vec3 mid = (left.origin + right.origin) * 0.5;  // the mono eye is halfway
    EXPECT_NEAR(Length(mid - cam.eye), 0, 1e-12);
}

TEST(Stereo, NeedsAnEyeSeparation) {
    Camera cam;  // eyeSep unset
    RenderOptions o;
    o.eyeSepSide = 1;
    EXPECT_THROW(CameraSetup(cam, o).HasAperture(), FatalError);
}

}  // namespace
}  // namespace rs
