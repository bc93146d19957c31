// The exercise designer as the console's library: a design checked by the simulator's own loader, saved with
// every version kept, its errors naming the design's line and field, and a shipped exercise never replaced.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "harbour/console/Designer.h"
#include "harbour/io/ExerciseFiles.h"

namespace harbour::console {
namespace {

namespace fs = std::filesystem;

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  if (at == std::string::npos) throw std::logic_error("the shipped exercise has no '" + from + "'");
  return text.replace(at, from.size(), to);
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A centre's exercise folder beside the shipped machines and vessels (its designs name ../machines/...).
struct CentreFolder {
  fs::path root = fs::temp_directory_path() / ("harbour_designer_" + std::to_string(::getpid()));
  fs::path exercises = root / "exercises";
  CentreFolder() {
    fs::remove_all(root);
    fs::create_directories(exercises);
    for (const char* shipped : {"machines", "vessels", "materials.yaml", "reeving", "trailers"})
      fs::create_symlink(fs::path(HARBOUR_DATA_DIR) / shipped, root / shipped);
  }
  ~CentreFolder() { fs::remove_all(root); }
};

std::string own_design() {
  const std::string shipped = design_source(std::string(HARBOUR_DATA_DIR) + "/exercises", "sts_discharge");
  return replaced(replaced(shipped, "name: sts_discharge", "name: night_discharge"),
                  "title: First discharge onto a truck", "title: A discharge at night");
}

TEST(Designer, ADesignIsSavedWithEveryVersionKeptAndLoadsAsTheExerciseItDescribes) {
  const CentreFolder centre;
  const DesignCheck first = check_design(centre.exercises.string(), own_design());
  EXPECT_EQ(first.exercise.name, "night_discharge");
  ASSERT_EQ(first.exercise.moves.size(), 1u);
  EXPECT_EQ(first.exercise.moves[0].container_id, "TGHU1000012");
  const std::string file = save_design(centre.exercises.string(), first);
  EXPECT_EQ(fs::path(file), centre.exercises / "night_discharge.yaml");
  EXPECT_TRUE(designed(read_text(file)));

  // an edit: a new version beside the first, which stays for the replays of its attempts
  const DesignCheck second = check_design(centre.exercises.string(),
                                          replaced(own_design(), "time_limit_s: 180", "time_limit_s: 240"));
  EXPECT_NE(second.version, first.version);
  save_design(centre.exercises.string(), second);
  const fs::path versions = centre.exercises / "versions";
  EXPECT_EQ(read_text(versions / ("night_discharge-" + first.version + ".yaml")), first.text);
  EXPECT_EQ(read_text(versions / ("night_discharge-" + second.version + ".yaml")), second.text);
  EXPECT_EQ(read_text(file), second.text);
  EXPECT_EQ(design_source(centre.exercises.string(), "night_discharge"), second.text);
  // the saved file is the exercise a station runs
  const sim::ExerciseSettings saved = io::load_exercise(file);
  EXPECT_EQ(saved.name, "night_discharge");
  EXPECT_EQ(saved.rules.time_limit_s, 240.0);
  EXPECT_EQ(saved.moves.size(), 1u);
}

TEST(Designer, ABadDesignIsNamedByItsLineAndFieldAndNothingIsSaved) {
  const CentreFolder centre;
  const std::string design = replaced(own_design(), "pass_score: 70", "pass_score: seventy");
  const auto line = 1 + std::count(design.begin(), design.begin() + design.find("pass_score"), '\n');
  try {
    check_design(centre.exercises.string(), design);
    FAIL() << "a pass score in words was taken";
  } catch (const std::invalid_argument& e) {
    const std::string why = e.what();
    EXPECT_NE(why.find("the design"), std::string::npos) << why;
    EXPECT_NE(why.find("pass_score"), std::string::npos) << why;
    EXPECT_NE(why.find("the design:" + std::to_string(line) + ":"), std::string::npos) << why;
    EXPECT_EQ(why.find(centre.root.string()), std::string::npos) << "the probe file's path leaks: " << why;
  }
  EXPECT_TRUE(fs::is_empty(centre.exercises));
}

TEST(Designer, AShippedExercisesNameOrTitleIsRefused) {
  const CentreFolder centre;
  const std::string shipped = design_source(std::string(HARBOUR_DATA_DIR) + "/exercises", "sts_discharge");
  // its title is the shipped exercise's: people pick exercises by title
  EXPECT_THROW(check_design(centre.exercises.string(),
                            replaced(shipped, "name: sts_discharge", "name: night_discharge")),
               std::invalid_argument);
  // its name is the shipped exercise's: saved, it would stand in for it at every station
  const DesignCheck renamed_title =
      check_design(centre.exercises.string(),
                   replaced(shipped, "title: First discharge onto a truck", "title: A discharge at night"));
  EXPECT_THROW(save_design(centre.exercises.string(), renamed_title), std::logic_error);
  EXPECT_FALSE(fs::exists(centre.exercises / "sts_discharge.yaml"));
}

}  // namespace
}  // namespace harbour::console
