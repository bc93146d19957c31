#include "harbour/io/MachineFileType.h"

#include <stdexcept>

namespace harbour::io {

StartPoseField pose_number_field(const char* key, double min, double max) {
  return {key, -1, min, max};
}

StartPoseField pose_optional_field(const char* key, double fallback, double min, double max) {
  return {key, -1, min, max, false, true, fallback};
}

StartPoseForm pose_on_the_quay(const char* section) {
  StartPoseForm form{section, {}};
  for (int c = 0; c < 3; ++c)
    form.fields.push_back({"position_m", c, -kSite_m, kSite_m});
  return form;
}

core::Vec3 StartBlock::position() const {
  return file.vector3(file.required(node, "position_m", at), at + ".position_m", kSite_m);
}

double StartBlock::number(const StartPoseForm& form, const std::string& key) const {
  for (const StartPoseField& p : form.fields)
    if (p.key == key)
      return p.optional ? file.number_or(node, key, at, p.fallback, p.min, p.max, p.exclusive_min)
                        : file.number(node, key, at, p.min, p.max, p.exclusive_min);
  throw std::logic_error("the start pose of the machine has no " + key);
}

const MachineFileType* find_machine_file_type(std::string_view kind) {
  for (const MachineFileType* type : machine_file_types())
    if (kind == type->kind) return type;
  return nullptr;
}

}  // namespace harbour::io
