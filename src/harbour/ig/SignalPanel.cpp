#include "harbour/ig/SignalPanel.h"

#include <osg/Geode>
#include <osg/LineWidth>

#include <algorithm>
#include <cctype>
#include <string>

#include "harbour/scene/HandSignals.h"

namespace harbour::ig {
namespace {
// the panel in the figure's own metres: the signaller 1.8 m tall, a margin round it, the words under it
constexpr float kLeft_m = -1.2f, kRight_m = 1.2f, kBottom_m = -0.4f, kTop_m = 1.95f;
}  // namespace

SignalPanel::SignalPanel(int width, int height, float text_px) {
  // a third of the picture's height for the panel, at the right, below the HUD's lines
  scale_px_per_m_ = 0.34f * static_cast<float>(height) / (kTop_m - kBottom_m);
  const float margin = text_px * 0.6f;
  const float x = static_cast<float>(width) - margin - kRight_m * scale_px_per_m_;
  const float y = static_cast<float>(height) - 4.5f * text_px - kTop_m * scale_px_per_m_;
  panel_ = new osg::MatrixTransform(osg::Matrix::scale(scale_px_per_m_, scale_px_per_m_, 1.0f) *
                                    osg::Matrix::translate(x, y, 0.0f));
  osg::ref_ptr<osg::Geometry> backdrop = new osg::Geometry;
  osg::ref_ptr<osg::Vec3Array> corners = new osg::Vec3Array;
  for (const auto& [cx, cy] : {std::pair{kLeft_m, kBottom_m}, std::pair{kRight_m, kBottom_m},
                               std::pair{kRight_m, kTop_m}, std::pair{kLeft_m, kTop_m}})
    corners->push_back(osg::Vec3(cx, cy, 0.0f));
  backdrop->setVertexArray(corners);
  osg::ref_ptr<osg::Vec4Array> dark = new osg::Vec4Array;
  dark->push_back(osg::Vec4(0.05f, 0.05f, 0.05f, 0.7f));
  backdrop->setColorArray(dark, osg::Array::BIND_OVERALL);
  backdrop->addPrimitiveSet(new osg::DrawArrays(GL_QUADS, 0, 4));
  figure_ = new osg::Geometry;
  figure_->setUseDisplayList(false);
  figure_->setUseVertexBufferObjects(true);
  figure_->setDataVariance(osg::Object::DYNAMIC);
  figure_->setVertexArray(new osg::Vec3Array);
  osg::ref_ptr<osg::Vec4Array> hi_vis = new osg::Vec4Array;
  hi_vis->push_back(osg::Vec4(1.0f, 0.85f, 0.1f, 1.0f));  // a signaller's high-visibility yellow
  figure_->setColorArray(hi_vis, osg::Array::BIND_OVERALL);
  figure_->addPrimitiveSet(new osg::DrawArrays(GL_LINES, 0, 0));
  figure_->getOrCreateStateSet()->setAttributeAndModes(new osg::LineWidth(3.0f));
  words_ = new osgText::Text;
  words_->setCharacterSize(0.85f * text_px / scale_px_per_m_);
  words_->setColor(osg::Vec4(1.0f, 0.85f, 0.1f, 1.0f));
  words_->setAlignment(osgText::Text::CENTER_BOTTOM);
  words_->setPosition(osg::Vec3(0.0f, kBottom_m + 0.08f, 0.0f));
  words_->setDataVariance(osg::Object::DYNAMIC);
  osg::ref_ptr<osg::Geode> geode = new osg::Geode;
  geode->addDrawable(backdrop);
  geode->addDrawable(figure_);
  geode->addDrawable(words_);
  panel_->addChild(geode);
  panel_->setNodeMask(0u);  // none until a signal is given
}

void SignalPanel::update(const scene::Snapshot& s) {
  const int signal = s.hand_signal >= 0 && s.hand_signal < static_cast<int>(scene::hand_signals().size()) &&
                             s.time_s - s.hand_signal_at_s < kShown_s
                         ? s.hand_signal
                         : -1;
  if (signal == shown_) return;
  shown_ = signal;
  panel_->setNodeMask(signal < 0 ? 0u : ~0u);
  if (signal < 0) return;
  const scene::HandSignal& given = scene::hand_signals()[static_cast<std::size_t>(signal)];
  auto* vertices = static_cast<osg::Vec3Array*>(figure_->getVertexArray());
  vertices->clear();
  for (const std::vector<double>& stroke : scene::signal_strokes(given))
    for (std::size_t k = 2; k + 1 < stroke.size(); k += 2) {
      vertices->push_back(
          osg::Vec3(static_cast<float>(stroke[k - 2]), static_cast<float>(stroke[k - 1]), 0.0f));
      vertices->push_back(osg::Vec3(static_cast<float>(stroke[k]), static_cast<float>(stroke[k + 1]), 0.0f));
    }
  vertices->dirty();
  static_cast<osg::DrawArrays*>(figure_->getPrimitiveSet(0))
      ->setCount(static_cast<GLsizei>(vertices->size()));
  figure_->dirtyBound();
  std::string words(given.words);
  std::transform(words.begin(), words.end(), words.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  words_->setText(words);
}

}  // namespace harbour::ig
