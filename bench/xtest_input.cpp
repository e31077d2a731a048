#include "bench/xtest_input.hpp"

#include <X11/Xlib.h>
#include <X11/extensions/XTest.h>

#include <stdexcept>

#include "core/error.hpp"

namespace palprig::bench {

namespace {

Display* dpy(void* d) { return static_cast<Display*>(d); }

}  // namespace

XTestInput::XTestInput(const char* display) {
  Display* d = XOpenDisplay(display);
  if (d == nullptr) throw palprig::Error(std::string("cannot open X display ") + (display ? display : "$DISPLAY"));
  int event_base = 0, error_base = 0, major = 0, minor = 0;
  if (!XTestQueryExtension(d, &event_base, &error_base, &major, &minor)) {
    XCloseDisplay(d);
    throw palprig::Error("the X server has no XTEST extension");
  }
  display_ = d;
}

XTestInput::~XTestInput() {
  if (display_) XCloseDisplay(dpy(display_));
}

unsigned XTestInput::keycode(const std::string& keysym) {
  const KeySym sym = XStringToKeysym(keysym.c_str());
  if (sym == NoSymbol) throw palprig::Error("no keysym " + keysym);
  const KeyCode code = XKeysymToKeycode(dpy(display_), sym);
  if (code == 0) throw palprig::Error("no key gives " + keysym + " in the server's keymap");
  return code;
}

XTestInput::time_point XTestInput::key_down(const std::string& keysym) {
  const unsigned code = keycode(keysym);
  // The server has just answered a round trip, so it is awake: the time it stamps on the event
  // is when the request arrived, not when a busy machine got round to waking it (a keyboard's
  // events carry the kernel's stamp, taken at the key's interrupt, whatever the server does).
  sync();
  const time_point at = std::chrono::steady_clock::now();
  XTestFakeKeyEvent(dpy(display_), code, True, CurrentTime);
  XFlush(dpy(display_));
  return at;
}

void XTestInput::key_up(const std::string& keysym) {
  XTestFakeKeyEvent(dpy(display_), keycode(keysym), False, CurrentTime);
  XFlush(dpy(display_));
}

XTestInput::time_point XTestInput::key(const std::string& keysym) {
  const time_point at = key_down(keysym);
  key_up(keysym);
  return at;
}

void XTestInput::move(int x, int y) {
  XTestFakeMotionEvent(dpy(display_), -1, x, y, CurrentTime);
  XFlush(dpy(display_));
}

XTestInput::time_point XTestInput::button_down(int button) {
  sync();  // as key_down
  const time_point at = std::chrono::steady_clock::now();
  XTestFakeButtonEvent(dpy(display_), static_cast<unsigned>(button), True, CurrentTime);
  XFlush(dpy(display_));
  return at;
}

void XTestInput::button_up(int button) {
  XTestFakeButtonEvent(dpy(display_), static_cast<unsigned>(button), False, CurrentTime);
  XFlush(dpy(display_));
}

XTestInput::time_point XTestInput::click(int x, int y, int button) {
  move(x, y);
  sync();  // the pointer is there before the press
  const time_point at = button_down(button);
  button_up(button);
  return at;
}

void XTestInput::focus(unsigned long window) {
  XSetInputFocus(dpy(display_), static_cast<Window>(window), RevertToParent, CurrentTime);
  XFlush(dpy(display_));
}

void XTestInput::sync() { XSync(dpy(display_), False); }

}  // namespace palprig::bench
