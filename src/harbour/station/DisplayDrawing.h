#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "harbour/ig/RenderThread.h"
#include "harbour/station/DisplayLayout.h"
#include "harbour/station/Profile.h"

namespace harbour::station {

/// Where a drawn picture goes: window `window`'s tile from column `x0`, the colours `colours` names; `last`:
/// the frame's last picture there (the window shows the frame once it is in).
using ShowPicture =
    std::function<void(int window, const osg::Image& picture, int x0, std::uint8_t colours, bool last)>;

/// The image generator's views of a profile's displays as the layout draws them (each eye's in stereo).
std::vector<ig::View> display_views(const Profile& profile, const DisplayLayout& layout);

/// One image generator on its own thread drawing every picture of the layout from the newest snapshot and
/// handing each to `show`; `before_last`, where given, is called with each frame's snapshot before its
/// last picture is handed over (a remote channel waits there for its frame's turn to be shown).
std::unique_ptr<ig::RenderThread> draw_displays(
    const Profile& profile, const DisplayLayout& layout, const scene::SceneDescription& scene,
    const ig::Looks& looks, ig::RenderThread::Source source, ig::RenderThread::BulkSource bulk,
    ShowPicture show, std::function<void(const scene::Snapshot&)> before_last = {}, double max_fps = 60.0,
    ig::RenderThread::Priority priority = ig::RenderThread::Priority::kBelowSimulation);

}  // namespace harbour::station
