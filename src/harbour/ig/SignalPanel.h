#pragma once

#include <osg/Geometry>
#include <osg/MatrixTransform>
#include <osg/ref_ptr>
#include <osgText/Text>

#include "harbour/scene/Snapshot.h"

namespace harbour::ig {

/// The signaller's latest hand signal in a corner of the cab's picture: the signaller drawn giving it, with
/// its words, for kShown_s after it was given.
class SignalPanel {
 public:
  static constexpr double kShown_s = 8.0;

  /// For a picture `width` x `height` pixels, its text `text_px` high.
  SignalPanel(int width, int height, float text_px);
  osg::Node* node() const { return panel_.get(); }
  void update(const scene::Snapshot& s);
  /// The signal drawn now (-1: none).
  int shown() const { return shown_; }

 private:
  osg::ref_ptr<osg::MatrixTransform> panel_;
  osg::ref_ptr<osg::Geometry> figure_;
  osg::ref_ptr<osgText::Text> words_;
  float scale_px_per_m_ = 1.0f;
  int shown_ = -1;
};

}  // namespace harbour::ig
