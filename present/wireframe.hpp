// A 3-D frame as text: the scene's bodies as wireframes (boxes by their 12 edges, spheres by
// their outline and three great circles of the body frame, so spin shows), planes as grids,
// and the overlays (body axes, ω, L, contact points and impulses, inertia ellipsoids, trails)
// drawn in perspective onto a braille or ASCII canvas, with a legend. Pure: no terminal I/O.
#pragma once

#include <string>
#include <vector>

#include "present/camera.hpp"
#include "present/canvas.hpp"
#include "present/scene.hpp"
#include "present/style.hpp"

namespace rigidlab::present {

struct RenderOptions {
  int width = 80, height = 24;  // the picture in character cells; the legend adds lines below
  TextStyle style;
  Camera camera;                // fit_camera(scene, ...) frames the whole scene
  bool legend = true;
};

// Inks: bodies cycle through 6 (a colour each, or without colour a dash pattern each: 4),
// then one ink per plane grid and per overlay, drawn above the bodies.
Ink body_ink(std::size_t body);
Ink plane_ink();
Ink overlay_ink(Overlay kind);

// The scene on a canvas of `width` x `height` cells (braille when style.unicode): for callers
// that compose frames, and for tests that look at which cells are lit.
Canvas draw_scene(const Scene& scene, const Camera& camera, int width, int height,
                  const TextStyle& style);

// The picture's rows, then the legend's (lines joined by "\n", no final newline).
std::string render_scene(const Scene& scene, const RenderOptions& options);

// The label of an overlay at the tip of its arrows and in the legend: "ω" or "w", "L", ...
std::string overlay_label(Overlay kind, bool unicode);

}  // namespace rigidlab::present
