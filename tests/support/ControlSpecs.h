#pragma once

// A machine's controls written briefly, for tests that build control tables of their own.

#include <string>
#include <utility>
#include <vector>

#include "harbour/scene/Controls.h"

namespace harbour::test {

inline scene::ControlSpec axis(const char* label, double min = -1.0, double max = 1.0) {
  scene::ControlSpec c;
  c.label = label;
  c.min = min;
  c.max = max;
  return c;
}

inline scene::ControlSpec button(const char* label) {
  scene::ControlSpec c;
  c.label = label;
  c.kind = scene::ControlKind::kButton;
  return c;
}

inline scene::ControlSpec selector(const char* label, std::vector<std::string> positions, double neutral) {
  scene::ControlSpec c;
  c.label = label;
  c.kind = scene::ControlKind::kSwitch;
  c.positions = std::move(positions);
  c.neutral = c.safe = neutral;
  return c;
}

}  // namespace harbour::test
