#pragma once
// XTestInput: real key presses and mouse clicks into the X server through its XTEST extension,
// as a keyboard and a mouse would give them: the server stamps each event and delivers it to the
// window under the pointer or with the focus, which then handles it as any other. Used by the
// window's timing benchmark (bench_gui_response_time) and its end-to-end test under Xvfb
// (tests/gui/qt/participant_xtest_test.cpp). Each injecting call returns the steady_clock time
// just before its request left for the server: the event's true time, to compare with what the
// window made of it. Each press is sent right after a round trip (XSync), so the server is awake
// and stamps it on arrival rather than when a busy machine schedules it: with a real keyboard the
// kernel stamps the key at its interrupt, whatever the X server is doing. The X headers stay in xtest_input.cpp (their
// macros clash with Qt's names).
#include <chrono>
#include <string>

namespace palprig::bench {

class XTestInput {
 public:
  using time_point = std::chrono::steady_clock::time_point;
  // Opens $DISPLAY (or `display`); throws palprig::Error naming what is missing (no display,
  // no XTEST extension).
  explicit XTestInput(const char* display = nullptr);
  ~XTestInput();
  XTestInput(const XTestInput&) = delete;
  XTestInput& operator=(const XTestInput&) = delete;

  // A key by its keysym name ("space", "0", "Return", "m", "BackSpace"): down now, up right after.
  time_point key(const std::string& keysym);
  time_point key_down(const std::string& keysym);
  void key_up(const std::string& keysym);
  // The pointer to root-window coordinates (x, y).
  void move(int x, int y);
  // A click of `button` (1 left, 3 right) at (x, y): the pointer moves there first; the press is
  // sent at the returned time, the release right after.
  time_point click(int x, int y, int button = 1);
  time_point button_down(int button);
  void button_up(int button);
  // Gives the keyboard focus to the X window `window` (a QWidget's winId()), as a window manager
  // would when it is clicked; there is none on a bare Xvfb.
  void focus(unsigned long window);
  // Waits until the server has processed every request sent.
  void sync();

 private:
  unsigned keycode(const std::string& keysym);
  void* display_ = nullptr;  // Display*
};

}  // namespace palprig::bench
