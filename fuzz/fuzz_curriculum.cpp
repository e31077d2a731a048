// Training curricula through their validator, then the rules that read one: the pilot's
// prediction and the plan of a first session at every level (cases drawn, the protocol made and
// read back by its own parser). Scene paths resolve against the shipped data/curricula folder
// (the fuzz input lives in /dev/shm), so mutations reach the scene set's loading.
#include "formats/json_file.hpp"
#include "fuzz/fuzz_input.hpp"
#include "study/curriculum.hpp"
#include "study/protocol.hpp"
#include "study/pulse_protocol.hpp"
#include "study/training.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = palprig::fuzz::input_file(palprig::fuzz::text(data, size), ".json");
  const auto base = std::filesystem::path(PALPRIG_SOURCE_DIR) / "data" / "curricula";
  palprig::fuzz::refused_or_read([&] {
    const palprig::Curriculum c = palprig::parse_curriculum(palprig::read_json_file(path), path.string(), base);
    (void)palprig::predict_pilot_sessions(c, 50);
    for (std::size_t level = 0; level < c.levels.size() && level < 4; ++level) {
      if (c.levels[level].cases_per_session > 8) continue;  // each generated case is built: keep inputs fast
      const auto plan = palprig::plan_training_session(c, static_cast<int>(level), "fuzz", {}, 1);
      if (plan.pulse)
        (void)palprig::parse_pulse_protocol(plan.protocol, path.string(), base);
      else
        (void)palprig::parse_protocol(plan.protocol, path.string(), base);
    }
  });
  return 0;
}
