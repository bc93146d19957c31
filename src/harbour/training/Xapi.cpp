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

std::string registration(const std::string& centre_iri, std::int64_t attempt) {
  // FNV-1a over the name, twice with different offsets: 128 bits, stable across builds and machines
  const std::string name = centre_iri + "#attempt-" + std::to_string(attempt);
  const auto fnv = [&](std::uint64_t hash) {
    for (unsigned char c : name) {
      hash ^= c;
      hash *= 1099511628211ull;
    }
    return hash;
  };
  const std::uint64_t halves[2] = {fnv(14695981039346656037ull), fnv(0x9e3779b97f4a7c15ull)};
  unsigned char b[16];
  for (int i = 0; i < 16; ++i)
    b[i] = static_cast<unsigned char>(halves[i / 8] >> (8 * (i % 8)));
  b[6] = static_cast<unsigned char>((b[6] & 0x0f) | 0x80);  // version 8: custom
  b[8] = static_cast<unsigned char>((b[8] & 0x3f) | 0x80);  // RFC 9562 variant
  char text[37];
  std::snprintf(text, sizeof text, "%02x%02x%02x%02x-%02x%02x-%02x%02x-%02x%02x-%02x%02x%02x%02x%02x%02x",
                b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7], b[8], b[9], b[10], b[11], b[12], b[13], b[14],
                b[15]);
  return text;
}

std::string addressed(const std::string& statement, const Centre& centre) {
  json s = json::parse(statement, nullptr, false);
  if (s.is_discarded() || !s.is_object()) return statement;
  const std::string ours = kIri, iri = centre.iri.empty() ? ours : centre.iri;
  const auto rebase = [&](json& id, const std::string& under) {
    const std::string from = ours + under;
    if (id.is_string() && id.get<std::string>().rfind(from, 0) == 0)
      id = iri + under + id.get<std::string>().substr(from.size());
  };
  if (s.contains("actor") && s["actor"].contains("account"))
    rebase(s["actor"]["account"]["homePage"], "/trainees");
  if (s.contains("object") && s["object"].is_object()) {
    json& object = s["object"];
    const std::string exercises = ours + "/exercises/";
    if (object.contains("id") && object["id"].is_string() &&
        object["id"].get<std::string>().rfind(exercises, 0) == 0) {
      const std::string segment = object["id"].get<std::string>().substr(exercises.size());
      for (const auto& [name, words] : centre.exercises)
        if (iri_segment(name) == segment) {
          object["definition"]["name"] = {{"en-US", words.title}};
          if (!words.objective.empty()) object["definition"]["description"] = {{"en-US", words.objective}};
        }
      rebase(object["id"], "/exercises/");
    }
  }
  if (s.contains("context") && s["context"].is_object()) {
    json& context = s["context"];
    if (context.contains("contextActivities") && context["contextActivities"].contains("parent"))
      for (json& parent : context["contextActivities"]["parent"])
        if (parent.is_object() && parent.contains("id")) rebase(parent["id"], "/routes/");
    if (context.contains("extensions") && context["extensions"].is_object()) {
      const json& extensions = context["extensions"];
      const auto attempt = extensions.find(ours + "/extensions/attempt");
      if (attempt != extensions.end() && attempt->is_number_integer())
        context["registration"] = registration(iri, attempt->get<std::int64_t>());
    }
  }
  return s.dump();
}

}  // namespace harbour::training::xapi
