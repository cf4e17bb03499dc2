/// \file main.cpp
/// The gale program: verbs over the scene format (docs/cli.md). Each verb registers itself from
/// its own Commands*.cpp (app/Cli.h); this is the only place that catches exceptions: bad input
/// exits 2, runtime failures exit 1, each with one line on stderr.

#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <memory>
#include <new>
#include <string>

#include "app/Cli.h"
#include "app/Version.h"
#include "app/io/Errors.h"
#ifdef GALE_HAVE_DIST
#include "dist/ProcessGroup.h"
#endif

namespace {

using namespace gale::app;

int reportError(const std::string& message, int code) {
    std::string line = message;
    std::replace(line.begin(), line.end(), '\n', ' ');
    std::fflush(stdout);
    std::fprintf(stderr, "gale: error: %s\n", line.c_str());
    return code;
}

/// GALE_THREADS=N caps the worker threads of TBB (solver, field sampling), e.g. to show that
/// results do not depend on the thread count (docs/reliability.md); unset: all cores.
std::unique_ptr<tbb::global_control> threadLimitFromEnvironment() {
    const char* text = std::getenv("GALE_THREADS");
    if (!text) return nullptr;
    char* end = nullptr;
    const long n = std::strtol(text, &end, 10);
    if (end == text || *end != '\0' || n < 1 || n > 4096)
        throw InputError(std::string("GALE_THREADS: must be an integer in 1..4096 (got '") + text +
                         "')");
    return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                 static_cast<size_t>(n));
}

/// "check, render, ... or terrain": the verbs' names, for the unknown-verb message.
std::string verbList(const CLI::App& app) {
    const auto verbs = app.get_subcommands([](const CLI::App*) { return true; });
    std::string text;
    for (size_t i = 0; i < verbs.size(); ++i)
        text += (i == 0 ? "" : i + 1 == verbs.size() ? " or " : ", ") + verbs[i]->get_name();
    return text;
}

bool isVerb(const CLI::App& app, const std::string& name) {
    const auto verbs =
        app.get_subcommands([&](const CLI::App* v) { return v->get_name() == name; });
    return !verbs.empty();
}

}  // namespace

int runGale(int argc, char** argv) {
    CLI::App app{
        "gale: wind over terrain, rendered as real-time shell grass (Bakay, Lalonde, "
        "Heidrich 2002).",
        "gale"};
    app.set_version_flag("--version", std::string("gale ") + GALE_VERSION);
    app.footer(
        std::string("\nRun 'gale VERB --help' for a verb's options; docs/cli.md has them all.") +
        EXIT_CODES_FOOTER);
    app.require_subcommand(1);

    VerbTable verbs;
    addCheckVerb(app, verbs);
    addRenderVerb(app, verbs);
    addViewVerb(app, verbs);
    addBladeVerb(app, verbs);
    addBenchVerbs(app, verbs);
    addSolveVerb(app, verbs);
    addTerrainVerb(app, verbs);
    addProbeVerb(app, verbs);

    if (argc > 1 && argv[1][0] != '-' && !isVerb(app, argv[1]))
        return reportError("unknown verb '" + std::string(argv[1]) + "' (expected " +
                               verbList(app) + "; see 'gale --help')",
                           EXIT_BAD_INPUT);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
        return reportError(e.what() + verbs.helpHint(), EXIT_BAD_INPUT);
    }

    try {
        const auto threadLimit = threadLimitFromEnvironment();
        if (const auto* run = verbs.parsedRun()) {
            const int code = (*run)();
            // What the verb printed is only written now (stdout is buffered when it is not a
            // terminal): `gale probe ... > /dev/full` must not exit 0 having written nothing.
            errno = 0;
            if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
                const int err = errno;
                return reportError(std::string("stdout: cannot write: ") +
                                       (err != 0 ? std::strerror(err) : "write error"),
                                   EXIT_FAILURE_INTERNAL);
            }
            return code;
        }
        return reportError("no verb given (see 'gale --help')", EXIT_BAD_INPUT);
    } catch (const InputError& e) {
        return reportError(e.what(), EXIT_BAD_INPUT);
    } catch (const std::bad_alloc&) {
        return reportError("out of memory", EXIT_FAILURE_INTERNAL);
    } catch (const std::exception& e) {
        return reportError(e.what(), EXIT_FAILURE_INTERNAL);
    }
}

/// Under mpirun rank 0 runs the verb and the other ranks serve its solves (dist/ProcessGroup.h);
/// started without an MPI launcher, or built without gale_dist, gale is one process.
int main(int argc, char** argv) {
#ifdef GALE_HAVE_DIST
    std::unique_ptr<gale::dist::ProcessGroup> group;
    try {
        group = std::make_unique<gale::dist::ProcessGroup>();
    } catch (const std::exception& e) {
        return reportError(e.what(), EXIT_FAILURE_INTERNAL);
    }
    if (!group->leader()) return group->serve();
    const int code = runGale(argc, argv);
    group->finish(code);
    return code;
#else
    return runGale(argc, argv);
#endif
}
