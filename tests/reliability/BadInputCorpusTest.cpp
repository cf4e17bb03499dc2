// The bad-input corpus (tests/data/bad, and the app tests' tests/data/scenes) through every verb
// that reads a scene: exit code 2, one line naming the file, the field or line and the reason, no
// crash, and nothing left on disk. Each corpus scene states what its error must say in trailing
// comments (trailing, so that line numbers stay those of the scene):
//   # expect: FRAGMENT     (any number; each must appear in the message)
//   # verbs: check render  (optional; default: check render solve)
// Conditions a file cannot hold (unwritable folders, an output path that is a file, a scene too
// large to read) are built by the tests below it.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <ostream>
#include <regex>
#include <string>
#include <vector>

#include "ReliabilitySupport.h"

namespace gale::reliability {
namespace {

/// A gale run of bad input ends within this time even under AddressSanitizer (a normal build
/// answers in under half a second; the slowest corpus case reads a 4 x 4 image).
constexpr double BAD_INPUT_TIMEOUT_S = 120.0;
/// The largest scene file gale reads (app::MAX_SCENE_FILE_BYTES); the test writes one byte more.
constexpr size_t MAX_SCENE_FILE_BYTES = 16u * 1024 * 1024;

struct CorpusScene {
    std::string folder;  ///< relative to the source folder
    std::string file;    ///< file name
    std::vector<std::string> fragments;
    std::vector<std::string> verbs;
    std::string path() const { return sourcePath(folder + "/" + file); }
};

void PrintTo(const CorpusScene& s, std::ostream* os) { *os << s.folder << "/" << s.file; }

CorpusScene readCorpusScene(const std::string& folder, const std::string& file) {
    CorpusScene s{folder, file, {}, {"check", "render", "solve"}};
    const std::string text = readFile(sourcePath(folder + "/" + file));
    size_t start = 0;
    while (start < text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        const std::string line = text.substr(start, end - start);
        start = end + 1;
        if (line.rfind("# expect: ", 0) == 0) s.fragments.push_back(line.substr(10));
        if (line.rfind("# verbs: ", 0) == 0) {
            s.verbs.clear();
            std::istringstream words(line.substr(9));
            for (std::string w; words >> w;) s.verbs.push_back(w);
        }
    }
    return s;
}

/// Every .toml of tests/data/bad, and every scene of tests/data/scenes but tiny.toml (the valid
/// base the app tests vary).
std::vector<CorpusScene> corpus() {
    std::vector<CorpusScene> out;
    for (const char* folder : {"tests/data/bad", "tests/data/scenes"}) {
        std::vector<std::string> names;
        for (const auto& e : fs::directory_iterator(sourcePath(folder)))
            if (e.path().extension() == ".toml" && e.path().filename() != "tiny.toml")
                names.push_back(e.path().filename().string());
        std::sort(names.begin(), names.end());
        for (const std::string& n : names) out.push_back(readCorpusScene(folder, n));
    }
    return out;
}

/// The run ended by itself with code 2 and printed exactly one line, "gale: error: ...", holding
/// every fragment, and nothing on stdout.
void expectOneCleanError(const RunResult& r, const std::vector<std::string>& fragments) {
    ASSERT_FALSE(r.timedOut) << r.describe();
    ASSERT_EQ(r.signal, 0) << r.describe();
    EXPECT_EQ(r.exitCode, 2) << r.describe();
    EXPECT_EQ(countLines(r.err), 1) << r.describe();
    EXPECT_EQ(r.err.rfind("gale: error: ", 0), 0u) << r.describe();
    EXPECT_EQ(r.out, "") << r.describe();
    for (const std::string& f : fragments)
        EXPECT_NE(r.err.find(f), std::string::npos) << "'" << f << "' not in: " << r.err;
}

/// The arguments that run `verb` on `scene`, writing (if it writes at all) below the working
/// folder: render gets `-o frames`; check and solve use the scene's defaults, which resolve
/// against the working folder too.
std::vector<std::string> verbArgs(const std::string& verb, const std::string& scene) {
    if (verb == "render") return {"render", scene, "-o", "frames"};
    return {verb, scene};
}

class BadInputCorpus : public testing::TestWithParam<CorpusScene> {};

TEST_P(BadInputCorpus, EveryVerbExitsTwoWithOneMessageNamingFileLineAndReasonAndWritesNothing) {
    const CorpusScene& scene = GetParam();
    ASSERT_GE(scene.fragments.size(), 2u)
        << scene.file << " must say what its error names: '# expect: FILE:LINE: key' and "
        << "'# expect: reason' lines";
    const auto corpusBefore = listTree(sourcePath(scene.folder));
    // FILE:LINE: (a key's line) or FILE:LINE:COL: (a TOML syntax error).
    const std::regex fileAndLine(std::regex_replace(scene.file, std::regex(R"([.])"), R"(\.)") +
                                 R"(:[0-9]+:)");
    int ran = 0;
    for (const std::string& verb : scene.verbs) {
        SCOPED_TRACE("gale " + verb + " " + scene.folder + "/" + scene.file);
        TempDir cwd;
        RunOptions options;
        options.cwd = cwd.str();
        options.timeout_s = BAD_INPUT_TIMEOUT_S;
        const RunResult r = runGale(verbArgs(verb, scene.path()), options);
        expectOneCleanError(r, scene.fragments);
        EXPECT_TRUE(std::regex_search(r.err, fileAndLine))
            << "no '" << scene.file << ":LINE:' in: " << r.err;
        const auto left = listTree(cwd.str());
        EXPECT_TRUE(left.empty()) << "left behind in the working folder:\n" << describeTree(left);
        ++ran;
    }
    EXPECT_GE(ran, 1) << "no verb of this build reads " << scene.file;
    const auto corpusAfter = listTree(sourcePath(scene.folder));
    EXPECT_EQ(corpusBefore, corpusAfter) << "the corpus folder changed:\n"
                                         << describeTree(corpusAfter);
}

INSTANTIATE_TEST_SUITE_P(Scenes, BadInputCorpus, testing::ValuesIn(corpus()),
                         [](const testing::TestParamInfo<CorpusScene>& paramInfo) {
                             std::string name =
                                 paramInfo.param.folder.substr(11) + "_" +
                                 paramInfo.param.file.substr(0, paramInfo.param.file.size() - 5);
                             for (char& c : name)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });

// ---------------------------------------------------------------------------------------------
// Conditions built at run time

const std::vector<std::string>& sceneVerbs() {
    static const std::vector<std::string> verbs = {"check", "render", "solve"};
    return verbs;
}

/// Runs every scene verb this build has with `extra` arguments in the working folder `cwd`.
template <typename Check>
void forEachSceneVerb(const std::string& scene, const std::vector<std::string>& extra,
                      const std::string& cwd, Check check) {
    for (const std::string& verb : sceneVerbs()) {
        SCOPED_TRACE("gale " + verb);
        std::vector<std::string> args = {verb, scene};
        args.insert(args.end(), extra.begin(), extra.end());
        RunOptions options;
        options.cwd = cwd;
        options.timeout_s = BAD_INPUT_TIMEOUT_S;
        check(runGale(args, options));
    }
}

TEST(BadInputConditions, MissingSceneFileIsNamed) {
    TempDir cwd;
    forEachSceneVerb("no/such/scene.toml", {}, cwd.str(), [&](const RunResult& r) {
        expectOneCleanError(r, {"no/such/scene.toml", "no such file"});
    });
    EXPECT_TRUE(listTree(cwd.str()).empty());
}

TEST(BadInputConditions, SceneThatIsAFolderIsNamed) {
    TempDir cwd;
    fs::create_directories(cwd / "scene.toml");
    forEachSceneVerb("scene.toml", {}, cwd.str(), [&](const RunResult& r) {
        expectOneCleanError(r, {"scene.toml", "is a folder"});
    });
}

TEST(BadInputConditions, SceneFileLargerThanSixteenMegabytesIsRefusedUnread) {
    TempDir cwd;
    writeFile(cwd / "huge.toml",
              "description = \"" + std::string(MAX_SCENE_FILE_BYTES, 'x') + "\"\n");
    forEachSceneVerb("huge.toml", {}, cwd.str(), [&](const RunResult& r) {
        expectOneCleanError(r, {"huge.toml", "too large for a scene file"});
    });
    EXPECT_EQ(listTree(cwd.str()).size(), 1u);
}

TEST(BadInputConditions, OutputPathThatIsAFileIsNamedAndKept) {
    TempDir cwd;
    const std::string tiny = sourcePath("tests/data/scenes/tiny.toml");
    writeFile(cwd / "occupied", "precious\n");
    for (const char* verb : {"check", "render"}) {
        SCOPED_TRACE(verb);
        RunOptions options;
        options.cwd = cwd.str();
        expectOneCleanError(runGale({verb, tiny, "-o", "occupied"}, options),
                            {"-o", "'occupied'", "is a file, not a folder"});
        expectOneCleanError(runGale({verb, tiny, "-o", "occupied/frames"}, options),
                            {"-o", "'occupied/frames'", "cannot be created", "is a file"});
    }
    EXPECT_EQ(readFile(cwd / "occupied"), "precious\n");
    EXPECT_EQ(listTree(cwd.str()).size(), 1u) << describeTree(listTree(cwd.str()));
}

TEST(BadInputConditions, SceneOutputFolderInsideAFileNamesTheKeyAndLine) {
    TempDir cwd;
    writeFile(cwd / "occupied", "precious\n");
    writeFile(cwd / "s.toml", "[output]\nframes = 1\nfolder = \"occupied/frames\"\n");
    for (const char* verb : {"check", "render"}) {
        SCOPED_TRACE(verb);
        RunOptions options;
        options.cwd = cwd.str();
        expectOneCleanError(runGale({verb, "s.toml"}, options),
                            {"s.toml:3: output.folder", "cannot be created", "is a file"});
    }
    EXPECT_EQ(listTree(cwd.str()).size(), 2u) << describeTree(listTree(cwd.str()));
}

/// Runs gale as an unprivileged user when this test runs as root (root writes anywhere).
std::vector<std::string> unprivilegedWrapper() {
    if (::geteuid() != 0) return {};
    return {"setpriv", "--reuid=65534", "--regid=65534", "--clear-groups", "--"};
}

TEST(BadInputConditions, UnwritableOutputFolderIsNamedBeforeAnythingIsWritten) {
    TempDir cwd;
    if (::geteuid() == 0 && ::system("command -v setpriv >/dev/null 2>&1") != 0)
        GTEST_SKIP() << "running as root without setpriv: cannot make a folder unwritable";
    const std::string tiny = sourcePath("tests/data/scenes/tiny.toml");
    fs::create_directories(cwd / "locked");
    fs::permissions(cwd.path(), fs::perms::all);  // the wrapped user must reach it
    fs::permissions(cwd / "locked", fs::perms::owner_read | fs::perms::owner_exec |
                                        fs::perms::group_read | fs::perms::group_exec |
                                        fs::perms::others_read | fs::perms::others_exec);
    RunOptions options;
    options.cwd = cwd.str();
    options.wrapper = unprivilegedWrapper();
    for (const char* verb : {"check", "render"}) {
        SCOPED_TRACE(verb);
        expectOneCleanError(runGale({verb, tiny, "-o", "locked"}, options),
                            {"-o", "'locked'", "is not writable", "ermission denied"});
        expectOneCleanError(runGale({verb, tiny, "-o", "locked/frames"}, options),
                            {"-o", "'locked/frames'", "cannot be created in", "ermission denied"});
    }
    EXPECT_TRUE(listTree(cwd / "locked").empty());
}

TEST(BadInputConditions, BadCommandLineValuesExitTwoWithOneLine) {
    TempDir cwd;
    const std::string tiny = sourcePath("tests/data/scenes/tiny.toml");
    RunOptions options;
    options.cwd = cwd.str();
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"render", tiny, "--frames", "0"}, "--frames"},
        {{"render", tiny, "--frames", "many"}, "--frames"},
        {{"render", tiny, "--width", "99999"}, "--width"},
        {{"render", tiny, "--height", "-1"}, "--height"},
        {{"check", tiny, "--fram", "2"}, "--fram"},
        {{"render", tiny, "-o", ""}, "-o"},
    };
    for (const auto& [args, fragment] : cases) {
        SCOPED_TRACE(args[2] + " " + args[3]);
        expectOneCleanError(runGale(args, options), {fragment});
    }
    EXPECT_TRUE(listTree(cwd.str()).empty()) << describeTree(listTree(cwd.str()));
}

}  // namespace
}  // namespace gale::reliability
