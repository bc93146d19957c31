// A mutation fuzzer over every input edge a user or another machine reaches: the exercise, machine and
// reeving loaders, the recording reader, the instructor command parser, device mappings, and the console's
// HTTP requests and WebSocket frames. Each target takes bytes and must answer with a result or its own clear
// error, never a crash, a hang or another exception. The YAML corpora hold the alias-bomb class (nested
// aliases), and a mutation nests aliases into any of them.
//
//   harbour_fuzz TARGET CORPUS_DIR [--seconds S] [--seed N]
//
// It runs every corpus file once (the regression corpus of the crash and hang classes), then mutates them for
// S seconds (0: only the corpus). On a crash it writes the input that caused it to fuzz-crash-TARGET.input.
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "harbour/core/Rng.h"
#include "harbour/io/DataError.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/io/InstructorCommandText.h"
#include "harbour/io/RecordingFile.h"
#include "harbour/io/ReevingFiles.h"
#include "harbour/machines/mhc/Files.h"
#include "harbour/machines/sts/Files.h"
#include "harbour/sim/Simulation.h"
#include "harbour/station/DeviceMappingFile.h"

namespace {

namespace fs = std::filesystem;
using harbour::io::YamlFile;

const std::string kData = HARBOUR_DATA_DIR;

// the input being tried, for the crash handler
std::string g_current;
std::string g_crash_file;

extern "C" void on_crash(int signal) {
  const int fd = ::open(g_crash_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd >= 0) {
    [[maybe_unused]] const auto n = ::write(fd, g_current.data(), g_current.size());
    ::close(fd);
  }
  const char message[] =
      "harbour_fuzz: crashed or hung (over 10 s on one input); the input is in "
      "fuzz-crash-*.input\n";
  [[maybe_unused]] const auto n = ::write(2, message, sizeof message - 1);
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

// a machine the loader accepts must also step: 300 steps of the discharge exercise with it
void step_a_while(const harbour::sim::StsCraneSettings& crane) {
  static const harbour::sim::ExerciseSettings exercise =
      harbour::io::load_exercise(kData + "/exercises/sts_discharge.yaml");
  harbour::sim::ScenarioSettings scenario = exercise.scenario;
  harbour::sim::StsSetup& sts = scenario.machine.as<harbour::sim::StsSetup>();
  sts.crane = crane;
  sts.trolley_x_m =
      std::clamp(sts.trolley_x_m, crane.trolley_drive.min_position_m, crane.trolley_drive.max_position_m);
  sts.gantry_y_m =
      std::clamp(sts.gantry_y_m, crane.gantry_drive.min_position_m, crane.gantry_drive.max_position_m);
  sts.spreader_z_m = std::min(sts.spreader_z_m, crane.trolley_rail_height_m - 3.0);
  harbour::sim::Simulation simulation(scenario);
  harbour::sim::StsControls in;
  in.hoist = -1.0;
  in.trolley = 1.0;
  for (int k = 0; k < 300; ++k)
    simulation.step(simulation.machine_as<harbour::sim::StsCrane>().controls(in));
}

// ... and an MHC file: 300 steps on the quay with every lever out
void step_a_while(const harbour::sim::MhcSettings& crane) {
  harbour::sim::ScenarioSettings scenario;
  harbour::sim::MhcSetup mhc;
  mhc.crane = crane;
  mhc.start.boom_rad = 0.5 * (crane.boom_min_angle_rad + crane.boom_max_angle_rad);
  mhc.start.hanging_z_m = std::clamp(10.0, crane.hoist_lower_limit_m, crane.hoist_upper_limit_m);
  scenario.machine = mhc;
  harbour::sim::Simulation simulation(scenario);
  harbour::scene::Controls in = simulation.control_table().neutral();
  for (const char* lever : {"slew", "luff", "hoist", "grab"})
    in.value[static_cast<std::size_t>(simulation.control_table().find(lever))] = 1.0;
  for (int k = 0; k < 300; ++k)
    simulation.step(in);
}

// ---------------------------------------------------------------------------------------------------
// The console: a `harboursim console` of its own (a fresh records file, a centre's folders so that a design
// or route saved goes there), an instructor logged in. An input is the bytes of one connection: HTTP
// requests, or an upgrade to the live socket and WebSocket frames; "@COOKIE@" and "@CSRF@" in it stand for
// the instructor's. After each, the console must still answer a request within 5 s.

// the bytes `request` sent on a fresh connection to 127.0.0.1:`port`, and what came back until the console
// closed it or `wait_ms` of quiet
std::string exchange(int port, const std::string& request, int wait_ms) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) throw std::runtime_error("no socket");
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<std::uint16_t>(port));
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  std::string got;
  if (::connect(fd, reinterpret_cast<sockaddr*>(&to), sizeof to) == 0) {
    for (std::size_t sent = 0; sent < request.size();) {
      const ssize_t n = ::send(fd, request.data() + sent, request.size() - sent, MSG_NOSIGNAL);
      if (n <= 0) break;
      sent += static_cast<std::size_t>(n);
    }
    char buffer[8192];
    for (pollfd p{fd, POLLIN, 0}; ::poll(&p, 1, wait_ms) > 0;) {
      const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
      if (n <= 0) break;
      got.append(buffer, static_cast<std::size_t>(n));
    }
  }
  ::close(fd);
  return got;
}

struct ConsoleUnderTest {
  pid_t pid = -1;
  int port = 0;
  std::string cookie, csrf;
  fs::path dir;
  ~ConsoleUnderTest() {
    if (pid > 0) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, nullptr, 0);
    }
    std::error_code ignored;
    if (!dir.empty()) fs::remove_all(dir, ignored);
  }
  // a command's exit status, its standard input `input`
  static int run(const std::vector<std::string>& args, const std::string& input) {
    int in[2];
    if (::pipe(in) != 0) return -1;
    const pid_t child = ::fork();
    if (child == 0) {
      ::dup2(in[0], 0);
      ::close(in[1]);
      const int null = ::open("/dev/null", O_WRONLY);
      ::dup2(null, 1);
      std::vector<char*> argv;
      for (const std::string& a : args)
        argv.push_back(const_cast<char*>(a.c_str()));
      argv.push_back(nullptr);
      ::execv(HARBOUR_APP, argv.data());
      ::_exit(127);
    }
    ::close(in[0]);
    [[maybe_unused]] const auto n = ::write(in[1], input.data(), input.size());
    ::close(in[1]);
    int status = 0;
    ::waitpid(child, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  void start() {
    dir = fs::temp_directory_path() / ("harbour_fuzz_console_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir / "centre" / "exercises");
    fs::create_directories(dir / "centre" / "routes");
    for (const auto& entry : fs::directory_iterator(kData))
      if (entry.path().filename() != "exercises" && entry.path().filename() != "routes")
        fs::create_symlink(entry.path(), dir / "centre" / entry.path().filename());
    const std::string db = "sqlite3://db=" + (dir / "records.db").string();
    if (run({HARBOUR_APP, "accounts", "add", "fuzz", "--role", "administrator", "--db", db},
            "fuzz-password\n") != 0)
      throw std::logic_error("cannot add the console's account");
    const std::string out = (dir / "console.log").string();
    pid = ::fork();
    if (pid == 0) {
      const int log = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      ::dup2(log, 1);
      ::dup2(log, 2);
      const std::string exercises = (dir / "centre" / "exercises").string(),
                        routes = (dir / "centre" / "routes").string();
      ::execl(HARBOUR_APP, HARBOUR_APP, "console", "--port", "0", "--domain", "212", "--db", db.c_str(),
              "--exercises", exercises.c_str(), "--routes", routes.c_str(), nullptr);
      ::_exit(127);
    }
    for (int tries = 0; tries < 200 && port == 0; ++tries) {
      ::usleep(50000);
      std::ifstream in(out);
      const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      const std::size_t at = text.find("http://127.0.0.1:");
      if (at != std::string::npos) port = std::atoi(text.c_str() + at + 17);
    }
    if (port == 0) throw std::logic_error("the console did not start");
    log_in();
  }
  void log_in() {
    const std::string body = R"({"name":"fuzz","password":"fuzz-password"})";
    const std::string answer =
        exchange(port,
                 "POST /api/login HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n"
                 "Content-Length: " +
                     std::to_string(body.size()) + "\r\nConnection: close\r\n\r\n" + body,
                 2000);
    const std::size_t c = answer.find("hs_session="), t = answer.find("\"csrf\":\"");
    if (c == std::string::npos || t == std::string::npos) return;  // blocked by the fuzz's own failed logins
    cookie = answer.substr(c, answer.find(';', c) - c);
    csrf = answer.substr(t + 8, answer.find('"', t + 8) - t - 8);
  }
  // the console is alive when it answers a request with an HTTP status line
  bool alive() {
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) != 0) return false;
    const std::string answer = exchange(
        port,
        "GET /api/me HTTP/1.1\r\nHost: 127.0.0.1\r\nCookie: " + cookie + "\r\nConnection: close\r\n\r\n",
        5000);
    if (answer.rfind("HTTP/1.1 401", 0) == 0) log_in();  // the fuzz logged it out
    return answer.rfind("HTTP/1.1 ", 0) == 0;
  }
};

void fuzz_console(const std::string& input) {
  static ConsoleUnderTest console;
  if (console.port == 0) console.start();
  std::string request = input;
  for (const auto& [mark, value] : {std::pair<std::string, std::string>{"@COOKIE@", console.cookie},
                                    std::pair<std::string, std::string>{"@CSRF@", console.csrf}})
    for (std::size_t at; (at = request.find(mark)) != std::string::npos;)
      request.replace(at, mark.size(), value);
  exchange(console.port, request, 40);
  if (!console.alive()) throw std::logic_error("the console stopped answering (or ended) after this input");
}

const std::map<std::string, std::function<void(const std::string&)>>& targets() {
  static const std::map<std::string, std::function<void(const std::string&)>> all = {
      {"exercise",
       [](const std::string& text) {
         harbour::io::load_exercise(YamlFile::parse(text, "fuzz.yaml"), kData + "/exercises");
       }},
      {"machine",
       [](const std::string& text) {
         const YamlFile f = YamlFile::parse(text, "fuzz.yaml");
         const YAML::Node machine = f.root().IsMap() ? f.root()["machine"] : YAML::Node();
         const YAML::Node kind = machine.IsMap() ? machine["kind"] : YAML::Node();
         if (kind.IsScalar() && kind.Scalar() == "mhc")
           step_a_while(harbour::io::load_mhc(f, kData + "/machines"));
         else
           step_a_while(harbour::io::load_sts_crane(f, kData + "/machines"));
       }},
      {"reeving",
       [](const std::string& text) { harbour::io::load_reeving(YamlFile::parse(text, "fuzz.yaml")); }},
      {"recording",
       [](const std::string& bytes) {
         static const std::string path =
             (fs::temp_directory_path() / ("harbour_fuzz_" + std::to_string(::getpid()) + ".hsrc")).string();
         std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
         harbour::io::read_recording(path);
       }},
      {"command", [](const std::string& text) { harbour::io::parse_instructor_command(text); }},
      {"mapping",
       [](const std::string& text) {
         // a mapping read against the STS's controls, then mapped from devices of every size it may meet
         static const harbour::scene::ControlTable table =
             harbour::io::load_sts_crane(HARBOUR_DATA_DIR "/machines/sts.yaml").controls;
         const harbour::station::DeviceMapping m =
             harbour::station::load_device_mapping(YamlFile::parse(text, "fuzz.yaml"), table);
         harbour::station::ControlMapper mapper(table, m);
         std::vector<harbour::station::DeviceState> states(m.devices.size());
         for (harbour::station::DeviceState& s : states)
           s = {true, {-32768.0, 32767.0}, {true}, {1}};
         mapper.map(states, std::vector<bool>(512, true));
         for (std::size_t d = 0; d < m.devices.size(); ++d)
           harbour::station::why_unfit(m, static_cast<int>(d), 2, 1, 1);
       }},
      {"console", fuzz_console},
  };
  return all;
}

// a clear error is an answer; anything else escaping is a failure
bool try_one(const std::function<void(const std::string&)>& target, const std::string& input,
             std::string& unexpected) {
  g_current = input;
  ::alarm(10);  // a hang on one input is a failure too (SIGALRM: on_crash)
  try {
    target(input);
  } catch (const harbour::io::DataError&) {
  } catch (const harbour::io::RecordingFileError&) {
  } catch (const std::invalid_argument&) {
  } catch (const std::runtime_error&) {  // e.g. a machine file the exercise names that is not there
  } catch (const std::exception& e) {
    unexpected = e.what();
    return false;
  }
  ::alarm(0);
  return true;
}

// values that broke the simulator before: extremes, non-numbers, structure
const char* const kTokens[] = {"1e300",
                               "-1e300",
                               "1e-300",
                               "0",
                               "-1",
                               ".nan",
                               ".inf",
                               "80",
                               "1099511627776",
                               "0x10",
                               "{}",
                               "[]",
                               "\"\\x1b[31m\"",
                               "&a",
                               "*a",
                               "---",
                               "\n",
                               ": ",
                               "- ",
                               ",",
                               "hoist_drum",
                               "sheave",
                               "60",
                               "600",
                               "gust"};

std::string mutate(const std::string& in, const std::vector<std::string>& corpus, harbour::core::Rng& rng) {
  std::string s = in;
  const auto pick = [&](std::size_t n) { return n == 0 ? std::size_t{0} : rng.next_u64() % n; };
  const int edits = 1 + static_cast<int>(pick(4));
  for (int e = 0; e < edits; ++e) {
    const std::size_t at = pick(s.size() + 1);
    switch (pick(8)) {
      case 0:  // flip a byte
        if (!s.empty()) s[std::min(at, s.size() - 1)] ^= static_cast<char>(1 + pick(255));
        break;
      case 1:  // erase a run
        if (!s.empty()) s.erase(std::min(at, s.size() - 1), 1 + pick(16));
        break;
      case 2:  // insert a token
        s.insert(at, kTokens[pick(std::size(kTokens))]);
        break;
      case 3: {  // replace a number with a token
        const std::size_t digit = s.find_first_of("0123456789", at);
        if (digit == std::string::npos) break;
        const std::size_t end = s.find_first_not_of("0123456789.e-+", digit);
        s.replace(digit, (end == std::string::npos ? s.size() : end) - digit, kTokens[pick(9)]);
        break;
      }
      case 4: {  // duplicate a line
        const std::size_t start = s.rfind('\n', at == 0 ? 0 : at - 1);
        const std::size_t from = start == std::string::npos ? 0 : start + 1;
        const std::size_t end = s.find('\n', from);
        s.insert(from, s.substr(from, (end == std::string::npos ? s.size() : end + 1) - from));
        break;
      }
      case 5: {  // splice another corpus file
        const std::string& other = corpus[pick(corpus.size())];
        const std::size_t from = pick(other.size() + 1);
        s.insert(at, other.substr(from, pick(64)));
        break;
      }
      case 6:  // truncate
        s.resize(at);
        break;
      default: {  // nest aliases: a line of an anchored list, then levels of lists of aliases to the one
                  // below
        const int levels = 1 + static_cast<int>(pick(12));
        std::string bomb = "\nb0: &b0 [x, x, x, x, x, x, x, x]\n";
        for (int n = 1; n <= levels; ++n) {
          bomb += "b" + std::to_string(n) + ": &b" + std::to_string(n) + " [";
          for (int k = 0; k < 8; ++k)
            bomb += (k ? ", *b" : "*b") + std::to_string(n - 1);
          bomb += "]\n";
        }
        s.insert(s.find('\n', at) == std::string::npos ? s.size() : s.find('\n', at), bomb);
        break;
      }
    }
  }
  if (s.size() > (1u << 20)) s.resize(1u << 20);
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3 || !targets().count(argv[1])) {
    std::fprintf(stderr,
                 "usage: harbour_fuzz exercise|machine|reeving|recording|command|mapping|console CORPUS_DIR "
                 "[--seconds S] [--seed N]\n");
    return 2;
  }
  const std::string name = argv[1];
  double seconds = 0.0;
  std::uint64_t seed = 1;
  for (int a = 3; a + 1 < argc; a += 2) {
    if (std::strcmp(argv[a], "--seconds") == 0) seconds = std::atof(argv[a + 1]);
    if (std::strcmp(argv[a], "--seed") == 0) seed = std::strtoull(argv[a + 1], nullptr, 10);
  }
  g_crash_file = "fuzz-crash-" + name + ".input";
  for (const int s : {SIGSEGV, SIGABRT, SIGFPE, SIGBUS, SIGILL, SIGALRM})
    std::signal(s, on_crash);
  const auto& target = targets().at(name);

  std::vector<std::string> corpus;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(argv[2]))
    if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files) {
    std::ifstream in(file, std::ios::binary);
    std::stringstream bytes;
    bytes << in.rdbuf();
    corpus.push_back(bytes.str());
    std::string unexpected;
    if (!try_one(target, corpus.back(), unexpected)) {
      std::fprintf(stderr, "harbour_fuzz %s: %s: unexpected exception: %s\n", name.c_str(), file.c_str(),
                   unexpected.c_str());
      return 1;
    }
  }
  if (corpus.empty()) {
    std::fprintf(stderr, "harbour_fuzz %s: no corpus in %s\n", name.c_str(), argv[2]);
    return 2;
  }

  harbour::core::Rng rng(seed);
  const auto start = std::chrono::steady_clock::now();
  long runs = 0;
  while (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < seconds) {
    const std::string input = mutate(corpus[rng.next_u64() % corpus.size()], corpus, rng);
    std::string unexpected;
    if (!try_one(target, input, unexpected)) {
      std::ofstream(g_crash_file, std::ios::binary) << input;
      std::fprintf(stderr, "harbour_fuzz %s: unexpected exception: %s (input in %s)\n", name.c_str(),
                   unexpected.c_str(), g_crash_file.c_str());
      return 1;
    }
    ++runs;
  }
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("harbour_fuzz %s: %zu corpus inputs, %ld mutated runs in %.1f s (%.0f/s), no crash\n",
              name.c_str(), corpus.size(), runs, elapsed,
              elapsed > 0 ? static_cast<double>(runs) / elapsed : 0.0);
  return 0;
}
