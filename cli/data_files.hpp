#pragma once
// The shipped data (protocols, scenes, rig files, calibrations, traces, tracking examples,
// waveforms) found by name, so that an installed palprig runs `--protocol discrimination_002`
// from any folder. One resolver for every command: a value that names an existing file is that
// file; a bare name (no '/') is looked up as KIND/NAME (or NAME.json, NAME.csv) in, in order,
// $PALPRIG_DATA_DIR, the installed share/palprig beside the program (../share/palprig from the
// executable's folder), and the source tree's data/ the program was built from.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace palprig::cli {

// One folder the shipped data may be in, and why it is searched.
struct DataPlace {
  std::filesystem::path dir;
  std::string origin;  // "$PALPRIG_DATA_DIR", "installed", "source tree"
};

// Every place in search order, whether or not it exists: $PALPRIG_DATA_DIR (a lab's own
// folder, laid out like the shipped one, searched first), then the shipped files' places:
// $PALPRIG_DATA (the older variable, which replaces the shipped folder), the installed
// share/palprig, the source tree.
std::vector<DataPlace> data_places();

// The shipped files: the first of their places that exists (where defaults such as
// rigs/simulated.json are taken from, whatever $PALPRIG_DATA_DIR holds); the source tree's
// data/ when none does.
DataPlace shipped_data_place();

// The file for a value given to an option of this kind ("protocols", "scenes", "rigs",
// "calibration", "traces", "tracking", "waveforms"): the value itself when it names a file or
// has a '/' in it (a path; its reader reports a missing file), else the first KIND/NAME,
// KIND/NAME.json or KIND/NAME.csv of data_places(); nullopt when a bare name is found nowhere
// (the options then refuse a name without an extension in one line naming the places searched,
// and leave a file name such as x.json to its reader, which says the file is missing).
std::optional<std::filesystem::path> find_data_file(const std::string& given, const std::string& kind);

// The names (file stems) of the shipped files of one kind in a folder, sorted.
std::vector<std::string> data_names(const std::filesystem::path& dir, const std::string& kind);

// The kinds, in the order `palprig data list` shows them.
const std::vector<std::string>& data_kinds();

// Gives every option that takes a shipped file (--protocol, --scene, --rig, --cal, --tracking,
// and --input trace:NAME) of every subcommand the resolver; call once all commands are registered.
void resolve_data_names(CLI::App& app);

}  // namespace palprig::cli
