// Team files: the shipped team reads; each kind of mistake is refused naming the file, the line and the
// field.
#include "harbour/io/TeamFiles.h"

#include <gtest/gtest.h>

namespace harbour::io {
namespace {

const std::vector<std::string> kExercises{std::string(HARBOUR_DATA_DIR) + "/exercises"};

Team parse(const std::string& text) {
  return load_team(YamlFile::parse(text, "team.yaml"), HARBOUR_DATA_DIR, kExercises);
}

std::string refusal(const std::string& text) {
  try {
    parse(text);
  } catch (const DataError& e) {
    return e.what();
  }
  return "(read)";
}

TEST(TeamFiles, TheShippedTeamReadsWithItsRolesExercises) {
  const Team team = load_team(std::string(HARBOUR_DATA_DIR) + "/teams/sts_and_tractor.yaml", kExercises);
  EXPECT_EQ(team.name, "sts_and_tractor");
  ASSERT_EQ(team.roles.size(), 2u);
  EXPECT_EQ(team.role_list(), "crane, tractor");
  EXPECT_NE(team.find("tractor")->exercise_file.find("tractor_mafi_park.yaml"), std::string::npos);
  EXPECT_EQ(team.find("signaller"), nullptr);
}

TEST(TeamFiles, MistakesAreRefusedNamingTheField) {
  const std::string head = "team:\n  name: t\n  roles:\n";
  EXPECT_NE(
      refusal(head + "    - {role: crane, exercise: sts_discharge}\n").find("team.roles: a team has 2 to 8"),
      std::string::npos);
  EXPECT_NE(refusal(head + "    - {role: crane, exercise: sts_discharge}\n    - {role: crane, exercise: "
                           "tractor_mafi_park}\n")
                .find("team.roles[1].role: 'crane' is named twice"),
            std::string::npos);
  EXPECT_NE(
      refusal(head + "    - {role: crane, exercise: sts_discharge}\n    - {role: tractor, exercise: nope}\n")
          .find("team.roles[1].exercise: no exercise 'nope'"),
      std::string::npos);
  EXPECT_NE(refusal(head + "    - {role: crane 1, exercise: sts_discharge}\n    - {role: b, exercise: "
                           "sts_discharge}\n")
                .find("team.roles[0].role: 'crane 1': letters, digits, '-' and '_' only"),
            std::string::npos);
  EXPECT_NE(refusal("team:\n  name: a/b\n  roles: []\n").find("team.name: 'a/b'"), std::string::npos);
  EXPECT_NE(refusal(head + "    - {role: a, exercise: sts_discharge, colour: red}\n    - {role: b, exercise: "
                           "sts_discharge}\n")
                .find("colour"),
            std::string::npos);
  EXPECT_NE(
      refusal(head + "    - {role: a, exercise: sts_discharge}\n    - {role: b, exercise: sts_discharge}\n")
          .find("(read)"),
      std::string::npos);
}

}  // namespace
}  // namespace harbour::io
