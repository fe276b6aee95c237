// The camera (CameraView, sceneCamera, cutCamera) is part of the scene layer: scene/camera.h. This header only
// forwards to it, for render code that still includes it here (render/renderer.h).
#pragma once

#include "scene/camera.h"
