#include "harbour/station/DisplayDrawing.h"

#include <osg/Image>

namespace harbour::station {

std::vector<ig::View> display_views(const Profile& profile, const DisplayLayout& layout) {
  std::vector<ig::View> views;
  for (const DisplayLayout::Picture& picture : layout.pictures) {
    const DisplayChannel& c = profile.displays[static_cast<std::size_t>(picture.channel)];
    ig::View view;
    view.yaw_rad = c.yaw_rad;
    view.pitch_rad = c.pitch_rad;
    view.from_sight = c.from_sight;
    view.fov_from_sight = c.fov_from_sight;
    view.roll_rad = c.roll_rad;
    view.fov_vertical_rad = c.fov_vertical_rad;
    view.frustum_rad = c.frustum_rad;
    view.hud = c.hud;
    view.eye_offset_m = picture.eye_offset_m;
    view.pixel_aspect = picture.pixel_aspect;
    if (profile.stereo) view.convergence_m = profile.stereo->convergence_m;
    // a tracked head looks through the desktop's monitor as through a window
    view.off_axis = profile.opentrack_port.has_value();
    views.push_back(view);
  }
  return views;
}

std::unique_ptr<ig::RenderThread> draw_displays(const Profile& profile, const DisplayLayout& layout,
                                                const scene::SceneDescription& scene, const ig::Looks& looks,
                                                ig::RenderThread::Source source,
                                                ig::RenderThread::BulkSource bulk, ShowPicture show,
                                                std::function<void(const scene::Snapshot&)> before_last,
                                                double max_fps, ig::RenderThread::Priority priority) {
  std::vector<bool> last_of_window(layout.pictures.size(), false);  // the frame's last picture there
  for (std::size_t k = 0; k < layout.pictures.size(); ++k) {
    for (std::size_t j = 0; j < k; ++j)
      if (layout.pictures[j].window == layout.pictures[k].window) last_of_window[j] = false;
    last_of_window[k] = true;
  }
  const std::size_t count = layout.pictures.size();
  return std::make_unique<ig::RenderThread>(
      scene, looks, layout.render_width, layout.render_height, display_views(profile, layout),
      std::move(source),
      [show = std::move(show), before_last = std::move(before_last), pictures = layout.pictures,
       last_of_window, count](ig::ImageGenerator& generator, const scene::Snapshot& s, int k) {
        const DisplayLayout::Picture& picture = pictures[static_cast<std::size_t>(k)];
        if (before_last && static_cast<std::size_t>(k) + 1 == count) before_last(s);
        show(picture.window, generator.render_result(), picture.x0, picture.colours,
             last_of_window[static_cast<std::size_t>(k)]);
      },
      max_fps, std::move(bulk), priority);
}

}  // namespace harbour::station
