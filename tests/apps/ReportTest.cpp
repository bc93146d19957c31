// harboursim report as an instructor runs it: records written by the records store, the PDF printed by
// chromium, read back with pdftotext and rendered with pdftoppm (poppler), as a person would check it.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <vector>

#include "harbour/records/RecordsStore.h"
#include "support/PngPixels.h"

namespace harbour::apps {
namespace {

namespace fs = std::filesystem;

std::string output_of(const std::string& command) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return out;
  std::array<char, 4096> chunk;
  while (std::size_t n = std::fread(chunk.data(), 1, chunk.size(), pipe))
    out.append(chunk.data(), n);
  pclose(pipe);
  return out;
}

// pixels of a PNG within `tolerance` of an RGB colour on every channel
int pixels_like(const fs::path& png, int r, int g, int b, int tolerance = 40) {
  const std::optional<test::RgbPixels> image = test::read_png_rgb(png.string());
  if (!image) return -1;
  const std::vector<png_byte>& pixels = image->rgb;
  int count = 0;
  for (std::size_t i = 0; i + 2 < pixels.size(); i += 3)
    count += std::abs(pixels[i] - r) < tolerance && std::abs(pixels[i + 1] - g) < tolerance &&
             std::abs(pixels[i + 2] - b) < tolerance;
  return count;
}

int run(const std::string& args) {
  const int status = std::system((std::string(HARBOUR_APP) + " " + args).c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(Report, TheTraineePdfHasTheNameThePlotsAndTheFigures) {
  const fs::path folder = fs::temp_directory_path() / "harbour_report";
  fs::remove_all(folder);
  fs::create_directories(folder);
  const std::string db = "sqlite3://db=" + (folder / "records.db").string();
  {
    records::RecordsStore records(db);
    records.add_trainee("ana", "Ana Lopez");
    records.add_trainee("ben", "Ben Okafor");
    ASSERT_TRUE(records.enrol("ana", "sts_basic", "ines"));
    // ana: 60, 70, 90, 100 (a trend of +14 points per attempt); ben: 75 with 3 collisions
    const auto store = [&](const std::string& trainee, double score, int collisions, double safety) {
      const auto id = records.begin_attempt(
          {trainee, "sts_discharge", std::nullopt, 0, "", "sts_basic", "single_lift", "0123456789abcdef"});
      sim::Metrics m;
      m.time_s = 95.0;
      m.collisions = collisions;
      sim::Score s;
      s.total = score;
      s.passed = score >= 70.0;
      s.skills = {safety, 100.0, 90.0};
      records.finish_attempt(id, m, s, "");
    };
    store("ana", 60.0, 2, 40.0);
    store("ana", 70.0, 1, 70.0);
    store("ana", 90.0, 0, 100.0);
    store("ana", 100.0, 0, 100.0);
    store("ben", 75.0, 3, 50.0);
  }
  const fs::path pdf = folder / "ana.pdf";
  ASSERT_EQ(run("report trainee ana --db " + db + " --out " + pdf.string()), 0);
  const std::string text = output_of("pdftotext -layout " + pdf.string() + " -");
  EXPECT_NE(text.find("Trainee report: Ana Lopez"), std::string::npos) << text;
  EXPECT_NE(text.find("+14.0"), std::string::npos) << "the trend\n" << text;
  EXPECT_NE(text.find("Score over finished attempts"), std::string::npos) << text;
  EXPECT_NE(text.find("STS basic"), std::string::npos) << "her route\n" << text;
  const auto has_line = [&](const std::string& pattern) {
    return std::regex_search(text, std::regex(pattern));
  };
  // two of four attempts met single_lift's bounds (no collision): passed, 4 of 6 attempts used, 2 of 2 passes
  EXPECT_TRUE(has_line(R"(single_lift +Controls and a single lift +passed +4 ?/ ?6 +2 ?/ ?2 +100\.0)"))
      << text;
  // the cohort of two: her best score 100 against ben's 75, her fewest collisions 0 against his 3: first of 2
  EXPECT_TRUE(has_line(R"(score +higher +100 +1st of 2 +2)")) << text;
  EXPECT_TRUE(has_line(R"(collisions +lower +0 +1st of 2 +2)")) << text;

  // the first page as a person sees it: the score line (#1f77b4) and the safety line (#d62728) are drawn
  ASSERT_EQ(std::system(
                ("pdftoppm -r 60 -f 1 -l 1 -png " + pdf.string() + " " + (folder / "page").string()).c_str()),
            0);
  const fs::path page = folder / "page-1.png";
  ASSERT_TRUE(fs::exists(page));
  EXPECT_GT(pixels_like(page, 0x1f, 0x77, 0xb4), 150) << "the score line";
  EXPECT_GT(pixels_like(page, 0xd6, 0x27, 0x28), 150) << "the safety line";

  const fs::path class_pdf = folder / "class.pdf";
  ASSERT_EQ(run("report class --db " + db + " --out " + class_pdf.string()), 0);
  const std::string class_text = output_of("pdftotext -layout " + class_pdf.string() + " -");
  for (const char* expected : {"Class report", "Ana Lopez", "Ben Okafor", "+14.0", "2 trainees"})
    EXPECT_NE(class_text.find(expected), std::string::npos) << expected << "\n" << class_text;

  // a long report: the attempts' table runs onto a second page, which repeats its head
  {
    records::RecordsStore records(db);
    for (int n = 0; n < 60; ++n) {
      const auto id =
          records.begin_attempt({"ben", "sts_discharge", std::nullopt, 0, "", "", "", "0123456789abcdef"});
      sim::Metrics m;
      m.time_s = 90.0 + n;
      sim::Score s;
      s.total = 50.0 + n % 50;
      records.finish_attempt(id, m, s, "");
    }
  }
  const fs::path long_pdf = folder / "ben.pdf";
  ASSERT_EQ(run("report trainee ben --db " + db + " --out " + long_pdf.string()), 0);
  int continued = 0;  // pages the table's rows run onto after its first
  for (int n = 2; n <= 6; ++n) {
    const std::string text_of_page =
        output_of("pdftotext -layout -f " + std::to_string(n) + " -l " + std::to_string(n) + " " +
                  long_pdf.string() + " - 2>/dev/null");
    if (!std::regex_search(text_of_page, std::regex(R"(\d+ sts_discharge +01234567 +finished)"))) continue;
    ++continued;
    EXPECT_TRUE(std::regex_search(text_of_page, std::regex(R"(# +Exercise +Version +Stage +Status +Score)")))
        << "page " << n << "\n"
        << text_of_page;
  }
  EXPECT_GE(continued, 1);

  // refused, and nothing written
  EXPECT_EQ(run("report trainee zed --db " + db + " --out " + (folder / "zed.pdf").string() + " 2>/dev/null"),
            1);
  EXPECT_FALSE(fs::exists(folder / "zed.pdf"));
  EXPECT_EQ(run("report class --db " + db + " --out " + (folder / "class.txt").string() + " 2>/dev/null"), 2);
  EXPECT_FALSE(fs::exists(folder / "class.txt"));
  EXPECT_EQ(run("report class --db " + db + " --out " + (folder / "no/such/folder/c.pdf").string() +
                " 2>/dev/null"),
            1);
}

}  // namespace
}  // namespace harbour::apps
