#pragma once

#include <string>

namespace harbour::station {

/// `harboursim channel`: one display of an immersive station drawn on its own host (a projector's), from the
/// frames the station sends over the network, frame-locked with the station's other channels.
struct ChannelOptions {
  std::string station;                ///< the station's name on the centre's network
  std::string display;                ///< the profile's display it draws (a remote one)
  std::string profile = "immersive";  ///< the station's profile: a shipped one's name or a file
  int domain = 0;                     ///< the centre's DDS domain
  std::string window = "auto";        ///< on, off, auto (where there is a display)
  std::string size;                   ///< "WxH": draw at this size, not the display's (a smaller projector)
  double seconds = 0.0;               ///< stop after this much wall time (0: Ctrl-C, the window closed)
  std::string picture;                ///< at the end, the last picture shown (PNG)
  /// A CSV line per frame shown: which, when it was drawn and shown (this host's monotonic clock), how long
  /// its drawing took
  std::string log;
};
int run_channel(const ChannelOptions& options);

}  // namespace harbour::station
