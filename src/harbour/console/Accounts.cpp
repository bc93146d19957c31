// The console's accounts: logging in and out, who is logged in, new accounts, the audit log; the command
// line's accounts.
#include "harbour/console/ConsoleServer.h"

#include <sodium.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "harbour/bulk/BulkPublish.h"
#include "harbour/core/Text.h"
#include "harbour/io/BoundedFile.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/io/InstructorCommandText.h"
#include "harbour/io/RecordingFile.h"
#include "harbour/io/RouteFiles.h"
#include "harbour/io/TeamFiles.h"
#include "harbour/net/SceneMessages.h"
#include "harbour/records/Reports.h"
#include "harbour/sim/MachineType.h"
#include "harbour/training/Figures.h"

namespace harbour::console {

std::string random_token() {
  unsigned char bytes[32];
  randombytes_buf(bytes, sizeof bytes);
  char hex[sizeof bytes * 2 + 1];
  sodium_bin2hex(hex, sizeof hex, bytes, sizeof bytes);
  return hex;
}

std::string hash_password(const std::string& password) {
  char hash[crypto_pwhash_STRBYTES];
  if (crypto_pwhash_str(hash, password.data(), password.size(), crypto_pwhash_OPSLIMIT_INTERACTIVE,
                        crypto_pwhash_MEMLIMIT_INTERACTIVE) != 0)
    throw std::runtime_error("hashing the password: out of memory");
  return hash;
}

bool Console::login_blocked(const std::string& key, Clock::time_point now) {
  std::deque<Clock::time_point>& failures = login_failures_[key];
  while (!failures.empty() && now - failures.front() > kLoginWindow)
    failures.pop_front();
  return static_cast<int>(failures.size()) >= kLoginFailuresAllowed;
}

std::optional<Console::Response> Console::login(Call& c) {
  const auto& request = c.request;
  const std::string& peer = c.peer;
  std::string why;
  const std::optional<json> body = parse_object(request.body(), why);
  if (!body) return error(request, http::status::bad_request, why);
  const std::optional<std::string> name = text_field(*body, "name", 64, why);
  const std::optional<std::string> password =
      name ? text_field(*body, "password", 256, why, true, true) : std::nullopt;
  if (!name || !password) return error(request, http::status::bad_request, why);
  const Clock::time_point now = Clock::now();
  if (login_blocked("address " + peer, now) || login_blocked("account " + *name, now))
    return error(request, http::status::too_many_requests, "too many failed logins: wait a minute");
  const std::optional<records::AccountRow> row = db_.account(*name);
  // an unknown name costs a password check as a known one does
  const std::string& hash = row ? row->password_hash : unknown_account_hash_;
  const bool verified = crypto_pwhash_str_verify(hash.c_str(), password->data(), password->size()) == 0;
  if (!row || !verified) {
    login_failures_["address " + peer].push_back(now);
    login_failures_["account " + *name].push_back(now);
    audit_.add(*name, "login_failed", "", "from " + peer);
    return error(request, http::status::unauthorized, "wrong name or password");
  }
  const std::string token = random_token();
  LoginSession session{{row->name, row->role, row->trainee}, random_token(), now + kSessionLifetime};
  sessions_[token] = session;
  audit_.add(row->name, "login", "", "from " + peer);
  Response r = json_reply(
      request, http::status::ok,
      {{"name", row->name}, {"role", row->role}, {"trainee", row->trainee}, {"csrf", session.csrf}});
  r.set(http::field::set_cookie,
        "hs_session=" + token + "; Path=/; HttpOnly; SameSite=Strict; Max-Age=43200" + secure_cookie());
  return r;
}

// ---------------------------------------------------------------------------------------------------
// The API's resources (Console::kRoutes says who may call each)

std::optional<Console::Response> Console::me(Call& c) {
  return json_reply(c.request, http::status::ok,
                    {{"name", c.account->name},
                     {"role", c.account->role},
                     {"trainee", c.account->trainee},
                     {"csrf", sessions_.at(c.token).csrf}});
}

std::optional<Console::Response> Console::logout(Call& c) {
  sessions_.erase(c.token);
  audit_.add(c.account->name, "logout", "", "");
  Response r = json_reply(c.request, http::status::ok, {{"ok", true}});
  r.set(http::field::set_cookie,
        "hs_session=; Path=/; HttpOnly; SameSite=Strict; Max-Age=0" + secure_cookie());
  return r;
}

std::optional<Console::Response> Console::audit_log(Call& c) {
  json list = json::array();
  audit_.flush();  // the log as it stands, the entries just queued in it
  for (const records::AuditRow& a : db_.audit_log(200))
    list.push_back({{"at", a.at},
                    {"account", a.account},
                    {"action", a.action},
                    {"target", a.target},
                    {"detail", a.detail}});
  return json_reply(c.request, http::status::ok, list);
}

std::optional<Console::Response> Console::add_account(Call& c) {
  const auto& request = c.request;
  std::string why;
  const std::optional<json> body = parse_object(request.body(), why);
  const std::optional<std::string> name = body ? text_field(*body, "name", 64, why) : std::nullopt;
  const std::optional<std::string> password =
      name ? text_field(*body, "password", 256, why, true, true) : std::nullopt;
  const std::optional<std::string> role = password ? text_field(*body, "role", 16, why) : std::nullopt;
  const std::optional<std::string> trainee =
      role ? text_field(*body, "trainee", 64, why, false) : std::nullopt;
  if (!trainee) return error(request, http::status::bad_request, why);
  if (password->size() < 8)
    return error(request, http::status::bad_request, "a password of 8 characters or more");
  try {
    db_.add_account({*name, *role, hash_password(*password), *trainee});
  } catch (const std::invalid_argument& e) {
    return error(request, http::status::bad_request, e.what());
  }
  audit_.add(c.account->name, "add_account", *name, *role);
  return json_reply(request, http::status::created, {{"name", *name}, {"role", *role}});
}

int list_accounts(const std::string& database) {
  records::RecordsStore db(database.empty() ? records::default_database() : database);
  for (const records::AccountRow& a : db.accounts())
    std::printf("%-24s %s\n", core::printable(a.name).c_str(), a.role.c_str());
  return 0;
}

int add_account(const std::string& database, const std::string& name, const std::string& role,
                const std::string& trainee) {
  if (sodium_init() < 0) throw std::runtime_error("libsodium could not start");
  std::string password;
  if (!std::getline(std::cin, password)) throw std::runtime_error("no password on standard input");
  if (password.size() < 8 || password.size() > 256)
    throw std::runtime_error("the password: 8 to 256 characters");
  records::RecordsStore db(database.empty() ? records::default_database() : database);
  db.add_account({name, role, hash_password(password), trainee});
  db.audit("(command line)", "add_account", name, role);
  std::printf("account %s (%s) added\n", name.c_str(), role.c_str());
  return 0;
}

}  // namespace harbour::console
