// Where the editor and gi-render start in a glTF file that has no camera of its own.
//
// frameBounds (gi/scene/scene.h) looks at the bounding box from outside along a fixed diagonal:
// right for an object, wrong for a room or a box open on one side, where it shows the outside of
// a wall. frameScene decides with rays through the reference's BVH:
//   1. From the centre of the bounds, 256 directions spread evenly over the sphere. Where at
//      least 60 % of them meet a surface from its front (the authored normal faces the centre)
//      and at most 20 % one from behind, the centre lies inside an enclosure. Otherwise (an
//      object, whose centre is inside it, or an open scene) frameBounds' view is kept.
//   2. Inside an enclosure: one view along each horizontal axis (+-x, +-z; glTF's up is +y)
//      through the centre, the eye at the centre's height. The eye backs away from the centre
//      until the enclosure's cross-section across that axis fills a square frame, but stops at
//      90 % of the way to the first surface behind it; where nothing is behind it (an open side,
//      like the front of the Cornell box) it stands outside at that framing distance. The frame
//      keeps 5 % of margin.
//   3. Open sides are tried first, then the views with the most room behind the eye. The first
//      whose 24 x 24 primary rays meet front faces on at least 20 % of the frame and back faces
//      on at most 5 % of the rays that hit is taken (an eye inside a pillar or behind a wall
//      sees back faces); when none passes, the one with the most front and fewest back faces.
// The near plane is fitted to the scene's size, as in frameBounds.
#pragma once

#include "gi/reference/path_tracer.h"
#include "gi/scene/scene.h"

#include <string>

namespace gi {

struct Framing {
    CameraSettings camera;
    bool inside = false;  // the view chosen from inside an enclosure (step 2), not frameBounds'
    std::string how;      // one line: why this view
};

Framing frameScene(const Scene& scene, const PathTracer& tracer);

// When loadScene made the scene's camera (the file has none), replaces it with frameScene's
// view; builds a tracer for it. Returns frameScene's line, or "" for a scene with cameras of its
// own (left as it is).
std::string frameCameraless(Scene& scene);

}  // namespace gi
