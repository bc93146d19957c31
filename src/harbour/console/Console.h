#pragma once

#include <string>
#include <vector>

#include "harbour/records/Centre.h"

namespace harbour::console {

/// `harboursim console`: the instructor console, a web application and its API served over HTTP and
/// WebSocket (Boost.Beast), watching and commanding the centre's stations over DDS.
struct ConsoleOptions {
  std::string bind = "127.0.0.1";  ///< only this machine, unless told otherwise
  int port = 8470;
  std::string database;            ///< records connection (accounts, audit, trainees, attempts)
  int domain = 0;                  ///< the centre's DDS domain
  std::string name;                ///< the console's name on the network ("" : console-<pid>)
  std::string web_root;            ///< the built front end (web/dist)
  std::string lrs, lrs_auth_file;  ///< a Learning Record Store to send the xAPI statements to ("" : none)
  std::string centre_iri;          ///< the centre's xAPI IRI ("" : http://HOSTNAME/harboursim)
  /// the centre's exercise folder the designer saves in and its route folder the route editor saves in
  /// ("" : data/exercises, data/routes)
  records::CentreFolders centre;
  double seconds = 0.0;  ///< stop after this long (tests; 0: until Ctrl-C)
  /// TLS (required off loopback): the certificate chain and its private key, PEM files
  std::string tls_certificate, tls_key;
  /// Origins besides the console's own whose pages may send it changes and open its live socket (a reverse
  /// proxy's public address, e.g. https://console.centre.example)
  std::vector<std::string> allowed_origins;
};
int run_console(const ConsoleOptions& options);

/// `harboursim accounts add NAME --role ROLE [--trainee ID]`: the password is read from standard input
/// (its first line), hashed with Argon2id and stored; nothing is stored if anything is wrong.
int add_account(const std::string& database, const std::string& name, const std::string& role,
                const std::string& trainee);

/// `harboursim accounts list`: name and role, a line each.
int list_accounts(const std::string& database);

}  // namespace harbour::console
