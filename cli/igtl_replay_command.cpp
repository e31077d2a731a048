// palprig igtl-replay: a tracker's OpenIGTLink server replaying a recorded path (inputs/
// igtl_pose_server.hpp), so `palprig run --input igtl:HOST:PORT` (and the tracking commands)
// run end to end without an NDI Aurora or PlusServer.
#include <chrono>
#include <iomanip>
#include <iostream>
#include <mutex>
#include <sstream>
#include <thread>

#include "cli/commands.hpp"
#include "inputs/igtl_pose_server.hpp"
#include "inputs/pose_recording.hpp"
#include "runtime/run_control.hpp"
#include "core/input_error.hpp"

using namespace palprig;

void register_igtl_replay_command(CLI::App& app) {
  struct Args {
    std::string poses;
    int port = 18944;
    bool position = false, loop = false;
    double duration_s = 0;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand(
      "igtl-replay",
      "Serve a recorded tracker path over OpenIGTLink (TRANSFORM messages per tool, in real time), as "
      "PlusServer streams an NDI Aurora");
  sub->add_option("--poses", a->poses, "Recorded path (CSV t_s,tool,x_mm,y_mm,z_mm,qx,qy,qz,qw)")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--port", a->port, "TCP port to listen on, every interface (0: any free port, printed)")
      ->default_val(18944)
      ->check(CLI::Range(0, 65535));
  sub->add_flag("--position", a->position, "Send POSITION messages (position and quaternion) instead of TRANSFORM");
  sub->add_flag("--loop", a->loop, "Start the recording over at its end (default: stay connected and silent)");
  sub->add_option("--duration-s", a->duration_s, "Stop after this long (default: until SIGINT/SIGTERM)")
      ->check(CLI::Range(0.0, 1e9));
  sub->callback([a]() {
    std::vector<RecordedPose> poses = load_pose_recording(a->poses);
    const std::vector<std::string> tools = recorded_tools(poses);
    PoseServerOptions options;
    options.port = a->port;
    options.position_messages = a->position;
    options.loop = a->loop;
    IgtlPoseServer server(std::move(poses), options);
    auto out_mutex = std::make_shared<std::mutex>();
    server.set_log_sink([out_mutex](const std::string& line) {
      std::lock_guard<std::mutex> lock(*out_mutex);
      std::cout << "palprig igtl-replay: " << line << std::endl;
    });
    install_stop_signals();
    try {
      server.start();
    } catch (const Error& e) {  // the port cannot be served: the argument's fault
      std::cerr << "palprig igtl-replay: " << e.what() << "\n";
      cli::finish(cli::kExitBadInput);
    }
    {
      std::ostringstream names;
      for (std::size_t i = 0; i < tools.size(); ++i) names << (i ? ", " : "") << tools[i];
      std::lock_guard<std::mutex> lock(*out_mutex);
      std::cout << "palprig igtl-replay: " << a->poses << ": " << tools.size()
                << (tools.size() == 1 ? " tool (" : " tools (") << names.str() << "), " << std::fixed
                << std::setprecision(2) << server.duration_s() << " s; listening on port " << server.port()
                << " (every interface), " << (a->position ? "POSITION" : "TRANSFORM")
                << " messages; each client gets the recording from its start" << std::endl;
    }
    const auto start = std::chrono::steady_clock::now();
    while (!process_run_control().stop_requested()) {
      if (a->duration_s > 0 && std::chrono::steady_clock::now() - start >= std::chrono::duration<double>(a->duration_s))
        break;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    server.stop();
    std::lock_guard<std::mutex> lock(*out_mutex);
    std::cout << "palprig igtl-replay: stopped after " << server.sent() << " messages" << std::endl;
  });
}
