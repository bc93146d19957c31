#pragma once

// A private PostgreSQL server for tests: a fresh cluster (initdb) in a temporary directory, listening only on
// a Unix socket there, stopped and removed with the object. Run as the `postgres` system user when the tests
// run as root (the server refuses root). Needs the Debian `postgresql` package (./harbour setup installs it).

#include <pwd.h>
#include <stdlib.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace harbour::test {

class PostgresServer {
 public:
  PostgresServer() {
    bin_ = find_bindir();
    char pattern[] = "/tmp/harbour_pg_XXXXXX";
    if (mkdtemp(pattern) == nullptr) throw std::runtime_error("postgres test server: mkdtemp failed");
    dir_ = pattern;
    if (getuid() == 0) {
      const passwd* pw = getpwnam("postgres");
      if (pw == nullptr)
        throw std::runtime_error("postgres test server: running as root and no 'postgres' user");
      if (chown(dir_.c_str(), pw->pw_uid, pw->pw_gid) != 0)
        throw std::runtime_error("postgres test server: cannot chown " + dir_.string());
      as_user_ = "runuser -u postgres -- ";
    }
    run("initdb -D " + data() + " -A trust -U harbour -E UTF8 --no-sync --no-instructions",
        dir_ / "initdb.log");
    run("pg_ctl -D " + data() + " -l " + (dir_ / "server.log").string() + " -w -t 60 -o \"-k " +
            dir_.string() + " -p " + std::to_string(port_) + " -c listen_addresses='' -c fsync=off\" start",
        dir_ / "pg_ctl.log");
    started_ = true;
  }

  ~PostgresServer() {
    if (started_) {
      const std::string stop =
          as_user_ + bin_ + "/pg_ctl -D " + data() + " -m immediate stop > /dev/null 2>&1";
      [[maybe_unused]] const int rc = std::system(stop.c_str());
    }
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }
  PostgresServer(const PostgresServer&) = delete;
  PostgresServer& operator=(const PostgresServer&) = delete;

  /// Creates an empty database and returns its SOCI connection string.
  std::string create_database(const std::string& name) {
    run("createdb -h " + dir_.string() + " -p " + std::to_string(port_) + " -U harbour " + name,
        dir_ / "createdb.log");
    return connection(name);
  }

  std::string connection(const std::string& database) const {
    return "postgresql://dbname=" + database + " host=" + dir_.string() + " port=" + std::to_string(port_) +
           " user=harbour";
  }

 private:
  static std::string find_bindir() {
    FILE* pipe = popen("pg_config --bindir 2>/dev/null", "r");
    std::string out;
    if (pipe != nullptr) {
      char buffer[512];
      while (fgets(buffer, sizeof buffer, pipe) != nullptr)
        out += buffer;
      pclose(pipe);
    }
    while (!out.empty() && (out.back() == '\n' || out.back() == ' '))
      out.pop_back();
    if (out.empty() || !std::filesystem::exists(out + "/initdb"))
      throw std::runtime_error("postgres test server: no initdb (install the Debian 'postgresql' package)");
    return out;
  }

  std::string data() const { return (dir_ / "data").string(); }

  void run(const std::string& command, const std::filesystem::path& log) const {
    const std::string line = as_user_ + bin_ + "/" + command + " > " + log.string() + " 2>&1";
    if (std::system(line.c_str()) != 0) {
      std::ifstream in(log);
      std::stringstream text;
      text << in.rdbuf();
      throw std::runtime_error("postgres test server: '" + command + "' failed:\n" + text.str());
    }
  }

  std::string bin_;
  std::filesystem::path dir_;
  std::string as_user_;
  int port_ = 5433;
  bool started_ = false;
};

}  // namespace harbour::test
