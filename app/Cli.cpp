/// \file Cli.cpp
/// The verb table and the options the verbs share.

#include "app/Cli.h"

#include "app/scene/SceneParser.h"

namespace gale::app {
namespace {

/// Depth of a subcommand below the program (1 for "render", 2 for "bench solve").
int depthOf(const CLI::App* verb) {
    int depth = 0;
    for (const CLI::App* a = verb; a->get_parent() != nullptr; a = a->get_parent()) ++depth;
    return depth;
}

/// "gale bench solve" for the subcommand "solve" of "bench".
std::string pathOf(const CLI::App* verb) {
    std::string path = verb->get_name();
    for (const CLI::App* a = verb->get_parent(); a != nullptr; a = a->get_parent())
        path = (a->get_parent() == nullptr ? std::string("gale") : a->get_name()) + " " + path;
    return path;
}

const CLI::App* deepestParsed(const std::vector<std::pair<CLI::App*, std::function<int()>>>& verbs,
                              const std::function<int()>** run) {
    const CLI::App* best = nullptr;
    for (const auto& [verb, action] : verbs)
        if (verb->parsed() && (best == nullptr || depthOf(verb) > depthOf(best))) {
            best = verb;
            if (run) *run = &action;
        }
    return best;
}

}  // namespace

void VerbTable::add(CLI::App* verb, std::function<int()> run) {
    mVerbs.emplace_back(verb, std::move(run));
}

const std::function<int()>* VerbTable::parsedRun() const {
    const std::function<int()>* run = nullptr;
    deepestParsed(mVerbs, &run);
    return run;
}

std::string VerbTable::helpHint() const {
    // A parent verb ("bench") that was parsed without a runnable child still names itself.
    const CLI::App* best = deepestParsed(mVerbs, nullptr);
    for (const auto& [verb, action] : mVerbs)
        for (const CLI::App* a = verb->get_parent(); a != nullptr && a->get_parent() != nullptr;
             a = a->get_parent())
            if (a->parsed() && (best == nullptr || depthOf(a) > depthOf(best))) best = a;
    return best ? " (see '" + pathOf(best) + " --help')" : std::string(" (see 'gale --help')");
}

const CLI::Validator NOT_EMPTY(
    [](std::string& s) { return s.empty() ? std::string("must not be empty") : std::string(); },
    "NOT EMPTY", "not empty");

const char* const EXIT_CODES_FOOTER =
    "\nExit codes: 0 ok, 1 runtime failure (e.g. no GL context, a file that cannot be written), "
    "2 bad input (scene, image, arguments, output folder), 3 ran but did not converge or missed "
    "its target (outputs written, the report says so), 130/143/129 interrupted by "
    "SIGINT/SIGTERM/SIGHUP.";

void addSceneOptions(CLI::App* verb, SceneRunOptions& o) {
    verb->add_option("scene", o.scenePath, "Scene file (TOML; see docs/scene-format.md)")
        ->required();
    verb->add_option("-o,--output", o.folder,
                     "Output folder, relative to the current directory (default: the scene's "
                     "output.folder)")
        ->check(NOT_EMPTY);
    verb->add_option("--frames", o.frames, "Number of frames (overrides output.frames)")
        ->check(CLI::Range(1, MAX_FRAMES));
    verb->add_option("--width", o.width, "Image width in pixels (overrides output.width)")
        ->check(CLI::Range(1, MAX_IMAGE_SIDE_PX));
    verb->add_option("--height", o.height, "Image height in pixels (overrides output.height)")
        ->check(CLI::Range(1, MAX_IMAGE_SIDE_PX));
}

}  // namespace gale::app
