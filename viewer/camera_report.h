// The facts a pixel test needs to check a screenshot without trusting the renderer: the camera
// (eye, target, vertical field of view, image size), the clear colour, and for every drawn body its
// centre of mass, bounding box, rotation and the colour it is drawn with. viewer/tests/check_png.py
// projects the centres itself and checks the pixels there.
#pragma once

#include "orbit_camera.h"
#include "viewer_scene.h"

#include <string>

namespace collide::viewer {

// Writes the report as JSON; throws Error when the file cannot be written.
void writeCameraReport(const std::string& path, const OrbitCamera& camera, int width, int height,
                       const Vec3& background, const ViewerScene& scene);

}  // namespace collide::viewer
