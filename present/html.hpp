// A self-contained HTML page that plays a sequence of scenes (w:export_html): the frames'
// data as JSON in the page, drawn on a canvas by a small script in the same page, with a
// time slider, play/pause and the camera orbited by dragging. Nothing outside the page is
// referenced: no network, no other file.
#pragma once

#include <string>
#include <vector>

#include "present/camera.hpp"
#include "present/scene.hpp"

namespace rigidlab::present {

struct HtmlFrame {
  double time = 0.0;   // s
  Scene scene;
  std::string status;  // shown under the picture: "t = 1.5 s   E = 3.2 J"
};

// The page. `camera` is where the view starts; `title` heads the page (made well-formed).
std::string html_player(const std::vector<HtmlFrame>& frames, const Camera& camera,
                        const std::string& title);

// A camera that frames every frame of the sequence at once (fit_camera over all of them).
Camera fit_camera_to_frames(const std::vector<HtmlFrame>& frames, double fov, double aspect);

}  // namespace rigidlab::present
