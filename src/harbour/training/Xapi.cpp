#include "harbour/training/Xapi.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace harbour::training::xapi {

namespace {

using json = nlohmann::json;

json verb(const std::string& word) {
  return {{"id", "http://adlnet.gov/expapi/verbs/" + word}, {"display", {{"en-US", word}}}};
}

json base(const AttemptFacts& f, const std::string& word, const std::string& timestamp,
          const std::string& id) {
  json context = {{"platform", "harboursim"},
                  {"language", "en-US"},
                  {"extensions",
                   {{std::string(kIri) + "/extensions/attempt", f.attempt},
                    {std::string(kIri) + "/extensions/exercise-version", f.exercise_version}}}};
  if (!f.route.empty())
    context["contextActivities"] = {
        {"parent", json::array({{{"objectType", "Activity"},
                                 {"id", std::string(kIri) + "/routes/" + iri_segment(f.route) + "/" +
                                            iri_segment(f.stage)},
                                 {"definition", {{"name", {{"en-US", f.route + " / " + f.stage}}}}}}})}};
  json actor = {{"objectType", "Agent"},
                {"account", {{"homePage", std::string(kIri) + "/trainees"}, {"name", f.trainee}}}};
  if (!f.trainee_name.empty()) actor["name"] = f.trainee_name;
  return {
      {"id", id},
      {"timestamp", timestamp},
      {"actor", actor},
      {"verb", verb(word)},
      {"object",
       {{"objectType", "Activity"},
        {"id", std::string(kIri) + "/exercises/" + iri_segment(f.exercise)},
        {"definition",
         {{"name", {{"en-US", f.exercise}}}, {"type", "http://adlnet.gov/expapi/activities/simulation"}}}}},
      {"context", context}};
}

Statement make(const json& statement, const std::string& word) {
  return {statement["id"].get<std::string>(), word, statement.dump()};
}

void need(const std::vector<std::string>& ids, int n) {
  if (static_cast<int>(ids.size()) != n)
    throw std::invalid_argument("xapi: " + std::to_string(n) + " statement ids needed");
}

}  // namespace

std::string duration(double seconds) {
  char text[48];
  std::snprintf(text, sizeof text, "PT%.2fS", std::max(0.0, std::isfinite(seconds) ? seconds : 0.0));
  return text;
}

std::string iri_segment(const std::string& text) {
  static const char* const hex = "0123456789ABCDEF";
  std::string out;
  for (unsigned char c : text) {
    if (std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '~') {
      out += static_cast<char>(c);
    } else {
      out += '%';
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

int statements_at_start() {
  return 2;
}

int statements_at_end(const AttemptFacts& facts) {
  return facts.status == "finished" && facts.score ? 2 : 1;
}

std::vector<Statement> at_start(const AttemptFacts& f, const std::string& timestamp,
                                const std::vector<std::string>& ids) {
  need(ids, statements_at_start());
  return {make(base(f, "launched", timestamp, ids[0]), "launched"),
          make(base(f, "attempted", timestamp, ids[1]), "attempted")};
}

std::vector<Statement> at_end(const AttemptFacts& f, const std::string& timestamp,
                              const std::vector<std::string>& ids) {
  need(ids, statements_at_end(f));
  if (f.status != "finished" || !f.score) {
    json s = base(f, "terminated", timestamp, ids[0]);
    s["result"] = {{"completion", false}, {"duration", duration(f.duration_s)}};
    s["context"]["extensions"][std::string(kIri) + "/extensions/status"] = f.status;
    return {make(s, "terminated")};
  }
  const std::string word = f.passed ? "passed" : "failed";
  json judged = base(f, word, timestamp, ids[0]);
  json extensions = json::object();
  for (const auto& [name, value] : f.metrics)
    if (std::isfinite(value)) extensions[std::string(kIri) + "/metrics/" + iri_segment(name)] = value;
  const double raw = std::clamp(*f.score, 0.0, 100.0);
  judged["result"] = {{"score", {{"scaled", raw / 100.0}, {"raw", raw}, {"min", 0}, {"max", 100}}},
                      {"success", f.passed},
                      {"completion", true},
                      {"duration", duration(f.duration_s)},
                      {"extensions", extensions}};
  json completed = base(f, "completed", timestamp, ids[1]);
  completed["result"] = {{"completion", true}, {"duration", duration(f.duration_s)}};
  return {make(judged, word), make(completed, "completed")};
}

}  // namespace harbour::training::xapi
