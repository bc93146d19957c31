#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace harbour::training::xapi {

/// The IRIs harboursim's statements use: activities, extensions and the trainees' account home page.
inline constexpr const char* kIri = "https://harboursim.org/xapi";

/// What the statements of one attempt say.
struct AttemptFacts {
  std::int64_t attempt = 0;
  std::string trainee, trainee_name;
  std::string exercise, exercise_version, route, stage;
  std::string status;  ///< running (at the start), finished, interrupted, diverged
  std::optional<double> score;
  bool passed = false;
  double duration_s = 0.0;  ///< simulated time of the attempt
  std::vector<std::pair<std::string, double>> metrics;
};

/// One xAPI 1.0.3 statement: its id (a UUID), verb (the ADL verb's last word) and JSON text.
struct Statement {
  std::string id, verb, json;
};

/// The statements of an attempt's start: launched and attempted. `ids` gives one UUID per statement;
/// `timestamp` is UTC ISO 8601.
std::vector<Statement> at_start(const AttemptFacts& facts, const std::string& timestamp,
                                const std::vector<std::string>& ids);
/// The statements of its end: a finished attempt passed or failed (score scaled to [0, 1], success, duration,
/// every metric as a result extension) and completed; an interrupted or diverged one terminated (not
/// complete).
std::vector<Statement> at_end(const AttemptFacts& facts, const std::string& timestamp,
                              const std::vector<std::string>& ids);
/// How many ids at_start / at_end need for `facts`.
int statements_at_start();
int statements_at_end(const AttemptFacts& facts);

/// Where the statements go out from: the centre's IRI (its trainees' account home page is IRI/trainees, its
/// exercises IRI/exercises/NAME, its routes IRI/routes/ROUTE/STAGE) and its exercises' titles and objectives.
/// Statements are stored with harboursim's own IRIs and addressed to the centre as they leave, so two
/// centres sharing an LRS keep their trainees and exercises apart.
struct Centre {
  std::string iri;
  struct Words {
    std::string title, objective;
  };
  std::map<std::string, Words> exercises;  ///< by exercise name
};
/// The statement as the centre sends it: its home page and activity IRIs, the exercise's title and
/// objective as the activity's name and description, and the attempt's registration (context.registration,
/// one UUID per attempt, as cmi5 and LMSs group an attempt's statements). A text that is not a statement
/// of ours is returned as it is (the LRS says what is wrong with it).
std::string addressed(const std::string& statement, const Centre& centre);
/// The registration of an attempt at a centre: a name-based UUID (version 8) of the centre's IRI and the
/// attempt's id, the same for every statement of the attempt and whenever it is sent.
std::string registration(const std::string& centre_iri, std::int64_t attempt);

/// ISO 8601 duration, as xAPI wants it: "PT88.62S" (hundredths of a second).
std::string duration(double seconds);

/// `text` percent-encoded for a path segment of an IRI (unreserved characters kept).
std::string iri_segment(const std::string& text);

}  // namespace harbour::training::xapi
