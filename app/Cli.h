#pragma once
/// \file Cli.h
/// What the verbs' command lines share. Each Commands*.cpp registers its own verb (options,
/// help, footer) into one VerbTable; main parses the command line and runs the verb it names.

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "app/scene/LoadScene.h"

namespace gale::app {

/// The verbs the command line knows, each with what runs it once the command line is parsed.
class VerbTable {
  public:
    /// Registers `run` for `verb` (a subcommand, or a subcommand of one: "bench solve").
    void add(CLI::App* verb, std::function<int()> run);
    /// What runs the deepest parsed verb; nullptr when none was parsed.
    const std::function<int()>* parsedRun() const;
    /// The help hint for the deepest parsed verb ("see 'gale bench solve --help'"), or the
    /// program's when none was parsed.
    std::string helpHint() const;

  private:
    std::vector<std::pair<CLI::App*, std::function<int()>>> mVerbs;
};

/// A path option given as "": refused, since an empty path would silently mean "the default".
extern const CLI::Validator NOT_EMPTY;

/// The exit codes, as every --help ends with them (README and docs/cli.md say the same).
extern const char* const EXIT_CODES_FOOTER;

/// SCENE, -o, --frames, --width, --height: the options of the verbs that render a scene.
void addSceneOptions(CLI::App* verb, SceneRunOptions& options);

/// One registration per verb, each in the verb's own Commands*.cpp.
void addCheckVerb(CLI::App& app, VerbTable& verbs);
void addRenderVerb(CLI::App& app, VerbTable& verbs);
void addViewVerb(CLI::App& app, VerbTable& verbs);
void addSolveVerb(CLI::App& app, VerbTable& verbs);
void addBladeVerb(CLI::App& app, VerbTable& verbs);
void addBenchVerbs(CLI::App& app, VerbTable& verbs);
void addTerrainVerb(CLI::App& app, VerbTable& verbs);
void addProbeVerb(CLI::App& app, VerbTable& verbs);

}  // namespace gale::app
