// evemu pen recordings, then decoded the way the tablet reader decodes them.
#include <stdexcept>

#include "core/error.hpp"
#include "fuzz/fuzz_input.hpp"
#include "inputs/tablet_decoder.hpp"
#include "inputs/tablet_source.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = palprig::fuzz::input_file(palprig::fuzz::text(data, size), ".evemu");
  palprig::fuzz::refused_or_read([&] {
    const palprig::PenRecording r = palprig::read_pen_recording(path);
    try {
      (void)palprig::decode_pen_events(r.axes, palprig::TabletConfig{}, r.events);
    } catch (const palprig::BadInput&) {
      // axes the config cannot convert: make_tablet_input refuses these as InputError
    }
  });
  return 0;
}
