// `harboursim devices`: what SDL sees, live values, and a walk through a machine's controls that binds and
// calibrates them and writes a mapping file.

#include "harbour/station/DevicesTool.h"

#include <SDL.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <deque>
#include <fstream>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "harbour/io/MachineFiles.h"
#include "harbour/station/DeviceInput.h"
#include "harbour/station/DeviceMappingFile.h"

namespace harbour::station {
namespace {

volatile std::sig_atomic_t g_quit = 0;
extern "C" void on_quit_signal(int) {
  g_quit = 1;
}

/// The terminal in raw mode (no echo, no line buffering, reads never block) while alive.
class RawTerminal {
 public:
  RawTerminal() {
    raw_ = isatty(STDIN_FILENO) && tcgetattr(STDIN_FILENO, &saved_) == 0;
    if (!raw_) return;
    termios t = saved_;
    t.c_lflag &= static_cast<tcflag_t>(~(ICANON | ECHO));
    t.c_cc[VMIN] = 0;
    t.c_cc[VTIME] = 0;
    tcsetattr(STDIN_FILENO, TCSANOW, &t);
  }
  ~RawTerminal() {
    if (raw_) tcsetattr(STDIN_FILENO, TCSANOW, &saved_);
  }
  /// A key typed since the last call, or 0.
  static char key() {
    char c = 0;
    return read(STDIN_FILENO, &c, 1) == 1 ? c : 0;
  }

 private:
  termios saved_{};
  bool raw_ = false;
};

/// A virtual joystick moved by UDP datagrams ("axis 1 -32768", "button 0 1", "hat 0 1"): the hand on the
/// stick in tests, where this machine has no /dev/uinput for a real one.
class VirtualStick {
 public:
  VirtualStick(const std::string& spec, int port) {
    std::string name = spec;
    int counts[3] = {4, 12, 1};
    std::stringstream parts(spec);
    std::getline(parts, name, ':');
    for (int& c : counts) {
      std::string n;
      if (std::getline(parts, n, ':')) c = std::stoi(n);
    }
    SDL_VirtualJoystickDesc desc{};
    desc.version = SDL_VIRTUAL_JOYSTICK_DESC_VERSION;
    desc.type = SDL_JOYSTICK_TYPE_FLIGHT_STICK;
    desc.naxes = static_cast<Uint16>(counts[0]);
    desc.nbuttons = static_cast<Uint16>(counts[1]);
    desc.nhats = static_cast<Uint16>(counts[2]);
    name_ = name;
    desc.name = name_.c_str();
    const int index = SDL_JoystickAttachVirtualEx(&desc);
    if (index < 0) throw std::runtime_error(std::string("virtual joystick: ") + SDL_GetError());
    joystick_ = SDL_JoystickOpen(index);
    if (port <= 0) return;
    socket_ = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::bind(socket_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0)
      throw std::runtime_error("virtual joystick: cannot listen on UDP port " + std::to_string(port));
    timeval timeout{0, 50000};
    ::setsockopt(socket_, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    thread_ = std::thread([this] {
      char buffer[128];
      while (running_) {
        const ssize_t n = ::recv(socket_, buffer, sizeof buffer - 1, 0);
        if (n <= 0) continue;
        buffer[n] = 0;
        const std::lock_guard lock(mutex_);
        moves_.emplace_back(buffer);
      }
    });
  }
  ~VirtualStick() {
    running_ = false;
    if (thread_.joinable()) thread_.join();
    if (socket_ >= 0) ::close(socket_);
    SDL_JoystickClose(joystick_);
  }
  // applies the moves received (on the thread that reads the joysticks)
  void apply() {
    const std::lock_guard lock(mutex_);
    for (const std::string& m : moves_) {
      std::stringstream in(m);
      std::string what;
      int index = 0, value = 0;
      if (!(in >> what >> index >> value)) continue;
      if (what == "axis")
        SDL_JoystickSetVirtualAxis(joystick_, index, static_cast<Sint16>(std::clamp(value, -32768, 32767)));
      if (what == "button") SDL_JoystickSetVirtualButton(joystick_, index, static_cast<Uint8>(value != 0));
      if (what == "hat") SDL_JoystickSetVirtualHat(joystick_, index, static_cast<Uint8>(value));
    }
    moves_.clear();
  }

 private:
  std::string name_;
  SDL_Joystick* joystick_ = nullptr;
  int socket_ = -1;
  std::thread thread_;
  std::atomic<bool> running_{true};
  std::mutex mutex_;
  std::vector<std::string> moves_;
};

struct Opened {
  SDL_Joystick* joystick;
  station::DeviceInfo info;
  station::DeviceState state;
};

std::vector<Opened> open_all() {
  std::vector<Opened> out;
  SDL_JoystickUpdate();
  for (const station::DeviceInfo& info : station::DeviceInput::list()) {
    for (int i = 0; i < SDL_NumJoysticks(); ++i)
      if (SDL_JoystickGetDeviceInstanceID(i) == info.instance) out.push_back({SDL_JoystickOpen(i), info, {}});
  }
  return out;
}

void read(std::vector<Opened>& devices) {
  SDL_JoystickUpdate();
  for (Opened& d : devices) {
    d.state.connected = SDL_JoystickGetAttached(d.joystick);
    d.state.axes.resize(static_cast<std::size_t>(d.info.axes));
    d.state.buttons.resize(static_cast<std::size_t>(d.info.buttons));
    d.state.hats.resize(static_cast<std::size_t>(d.info.hats));
    for (int a = 0; a < d.info.axes; ++a)
      d.state.axes[static_cast<std::size_t>(a)] = SDL_JoystickGetAxis(d.joystick, a);
    for (int b = 0; b < d.info.buttons; ++b)
      d.state.buttons[static_cast<std::size_t>(b)] = SDL_JoystickGetButton(d.joystick, b);
    for (int h = 0; h < d.info.hats; ++h)
      d.state.hats[static_cast<std::size_t>(h)] = SDL_JoystickGetHat(d.joystick, h);
  }
}

void print_list() {
  const std::vector<station::DeviceInfo> list = station::DeviceInput::list();
  if (list.empty())
    std::printf("no joysticks or game controllers (the keyboard needs the station's window)\n");
  for (std::size_t n = 0; n < list.size(); ++n) {
    std::printf("%zu: %s\n   guid %s, %d axes, %d buttons, %d hats\n", n + 1, list[n].name.c_str(),
                list[n].guid.c_str(), list[n].axes, list[n].buttons, list[n].hats);
    if (list[n].controller.empty())
      std::printf("   not a game controller SDL knows: bind it raw, or give SDL a mapping line for it\n");
    else
      std::printf("   game controller \"%s\" (game_controller: true mappings read it)\n   SDL mapping: %s\n",
                  list[n].controller.c_str(), list[n].mapping.c_str());
  }
  std::fflush(stdout);
}

void print_values(const std::vector<Opened>& devices) {
  std::printf("\033[H\033[J");  // home, clear
  std::printf("live values (q quits)\n");
  for (const Opened& d : devices) {
    std::printf("%s%s\n  axes   ", d.info.name.c_str(), d.state.connected ? "" : "  (GONE)");
    for (const double a : d.state.axes)
      std::printf("%7.0f", a);
    std::printf("\n  buttons ");
    for (const bool b : d.state.buttons)
      std::printf("%c", b ? '#' : '.');
    std::printf("\n  hats   ");
    for (const int h : d.state.hats)
      std::printf(" %d", h);
    std::printf("\n");
  }
  std::fflush(stdout);
}

// what moved since `rest`: a binding for `control` (device index in `devices`), or nothing yet
std::optional<std::pair<std::size_t, station::Binding>> moved(const std::vector<Opened>& devices,
                                                              const std::vector<station::DeviceState>& rest) {
  for (std::size_t d = 0; d < devices.size(); ++d) {
    const station::DeviceState& now = devices[d].state;
    for (std::size_t a = 0; a < now.axes.size(); ++a) {
      const double delta = now.axes[a] - rest[d].axes[a];
      if (std::abs(delta) > 0.4 * 32767.0) {
        station::Binding b;
        b.source = station::Binding::Source::kAxis;
        b.index = static_cast<int>(a);
        b.invert = delta < 0.0;  // moved towards its "+" the other way
        return std::pair{d, b};
      }
    }
    for (std::size_t k = 0; k < now.buttons.size(); ++k)
      if (now.buttons[k] && !rest[d].buttons[k]) {
        station::Binding b;
        b.source = station::Binding::Source::kButton;
        b.index = static_cast<int>(k);
        return std::pair{d, b};
      }
    for (std::size_t h = 0; h < now.hats.size(); ++h)
      if (now.hats[h] != rest[d].hats[h] && now.hats[h] != 0) {
        station::Binding b;
        b.source = station::Binding::Source::kHat;
        b.index = static_cast<int>(h);
        b.hat_direction = now.hats[h];
        return std::pair{d, b};
      }
  }
  return std::nullopt;
}

std::string upper(std::string s) {
  for (char& c : s)
    c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

void pump(std::vector<Opened>& devices, VirtualStick* stick) {
  if (stick) stick->apply();
  read(devices);
  std::this_thread::sleep_for(std::chrono::milliseconds(10));
}

int bind(const DevicesOptions& options, std::vector<Opened>& devices, VirtualStick* stick) {
  const std::string& machine = options.machine;
  const scene::ControlTable table = io::machine_file_controls(machine);
  if (devices.empty()) {
    std::printf("no joysticks to bind: connect one and start again\n");
    return 2;
  }
  station::DeviceMapping mapping;
  mapping.name = options.name;
  std::vector<int> device_of(devices.size(), -1);  // opened device -> mapping device
  const RawTerminal terminal;
  std::printf(
      "Binding the controls of %s to your devices. For each control, move it (towards +) or press it;\n"
      "Enter skips it, q stops here and writes what is bound.\n\n",
      machine.c_str());
  for (int slot = 0; slot < table.size() && !g_quit; ++slot) {
    const scene::ControlSpec& c = table[slot];
    pump(devices, stick);
    std::vector<station::DeviceState> rest;
    for (const Opened& d : devices)
      rest.push_back(d.state);
    std::printf("Move the control you use for %s (%s: %s)\n", upper(c.label).c_str(),
                scene::to_string(c.kind), c.meaning.c_str());
    std::fflush(stdout);
    std::optional<std::pair<std::size_t, station::Binding>> found;
    char key = 0;
    while (!found && !g_quit) {
      pump(devices, stick);
      key = RawTerminal::key();
      if (key == '\n' || key == 'q') break;
      found = moved(devices, rest);
    }
    if (key == 'q') break;
    if (!found) {
      std::printf("  skipped\n");
      continue;
    }
    auto [d, b] = *found;
    b.control = c.label;
    b.slot = slot;
    if (device_of[d] < 0) {
      station::DeviceMatch m;
      m.id = "device" + std::to_string(mapping.devices.size() + 1);
      m.name = devices[d].info.name;
      for (std::size_t e = 0; e < d; ++e)
        m.nth += devices[e].info.name == m.name;
      device_of[d] = static_cast<int>(mapping.devices.size());
      mapping.devices.push_back(m);
    }
    b.device = device_of[d];
    if (b.source == station::Binding::Source::kAxis) {
      if (c.kind != scene::ControlKind::kAxis) {
        std::printf("  an axis cannot work %s (a %s): press a button for it instead\n", c.label.c_str(),
                    scene::to_string(c.kind));
        --slot;
        continue;
      }
      std::printf(
          "  axis %d of %s%s. Now move %s through its whole range, let it go to rest, and press Enter\n",
          b.index, devices[d].info.name.c_str(), b.invert ? " (inverted)" : "", upper(c.label).c_str());
      std::fflush(stdout);
      double low = devices[d].state.axes[static_cast<std::size_t>(b.index)], high = low;
      while (!g_quit && RawTerminal::key() != '\n') {
        pump(devices, stick);
        const double v = devices[d].state.axes[static_cast<std::size_t>(b.index)];
        low = std::min(low, v);
        high = std::max(high, v);
      }
      const double rest_value = devices[d].state.axes[static_cast<std::size_t>(b.index)];
      const double span = high - low;
      if (span < 1000.0) {
        std::printf("  it hardly moved (%.0f): %s skipped\n", span, c.label.c_str());
        continue;
      }
      // at rest near an end: a pedal or throttle (one-sided); else a lever centred at rest
      const bool one_sided = rest_value - low < 0.1 * span || high - rest_value < 0.1 * span;
      b.calibration = {low, one_sided ? 0.0 : rest_value, high, !one_sided};
      if (one_sided && high - rest_value < 0.1 * span) b.invert = !b.invert;
      b.dead_zone = 0.05;
      std::printf("  calibrated: min %.0f, %s%.0f, max %.0f, dead zone 5 %%\n", low,
                  one_sided ? "rest at an end " : "centre ", one_sided ? rest_value : rest_value, high);
    } else {
      if (c.kind == scene::ControlKind::kSwitch) b.toggle = true;  // each press steps the switch
      std::printf("  %s %d of %s\n", b.source == station::Binding::Source::kHat ? "hat" : "button", b.index,
                  devices[d].info.name.c_str());
      // wait for the release, so the press does not bind the next control too
      while (!g_quit && moved(devices, rest))
        pump(devices, stick);
    }
    mapping.bindings.push_back(b);
  }
  mapping.file = options.bind;
  const std::string text = station::device_mapping_text(mapping);
  // what is written must read back: checked before the file is replaced
  station::load_device_mapping(io::YamlFile::parse(text, options.bind), table);
  const std::string partial = options.bind + ".partial";
  {
    std::ofstream out(partial);
    out << text;
    if (!out) throw std::runtime_error(options.bind + ": cannot be written");
  }
  std::rename(partial.c_str(), options.bind.c_str());
  std::printf("\nwrote %s: %zu binding(s) on %zu device(s)\n", options.bind.c_str(), mapping.bindings.size(),
              mapping.devices.size());
  return 0;
}

}  // namespace

int run_devices(const DevicesOptions& options) {
  station::init_sdl_joysticks();
  struct Quit {
    ~Quit() { SDL_Quit(); }
  } quit;
  std::unique_ptr<VirtualStick> stick;
  if (!options.virtual_device.empty())
    stick = std::make_unique<VirtualStick>(options.virtual_device, options.virtual_port);
  g_quit = 0;
  std::signal(SIGINT, on_quit_signal);
  print_list();
  std::vector<Opened> devices = open_all();
  int status = 0;
  if (!options.bind.empty()) {
    status = bind(options, devices, stick.get());
  } else if (options.watch) {
    const RawTerminal terminal;
    while (!g_quit && RawTerminal::key() != 'q') {
      pump(devices, stick.get());
      print_values(devices);
      std::this_thread::sleep_for(std::chrono::milliseconds(40));
    }
  }
  for (Opened& d : devices)
    SDL_JoystickClose(d.joystick);
  std::signal(SIGINT, SIG_DFL);
  return status;
}

}  // namespace harbour::station
