// Nothing lost, for every input of every verb (docs/reliability.md, issue 25): outputs that would
// replace a DEM, its sidecar files, a density map, a heightmap or the scene (through hard links
// too) are refused before any work; read-only outputs are refused; devices are written as streams,
// never replaced; a write error on stdout exits non-zero; a .vdb sequence never mixes two runs;
// corrupt .vdb files and strict command-line values get gale's own one-line message. Every case
// checks the exit code, the message and that every file in the working folder is byte for byte
// as it was (outputs of a run that is allowed to write are checked by name).

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "ReliabilitySupport.h"
#include "app/GeoTestSupport.h"

namespace gale::reliability {
namespace {

/// A tiny solve or render takes well under a second; a generous bound for the sanitizers.
constexpr double RUN_TIMEOUT_S = 120.0;

const char* const TINY = "tests/data/scenes/tiny.toml";

/// A steady solve of a few thousand cells.
const char* const SMALL_SOLVE =
    "[terrain]\nkind = \"hemisphere\"\nsize_m = [8.0, 8.0]\nradius_m = 2.0\n"
    "[wind]\nkind = \"solved\"\n[solver]\nvoxel_size_m = 0.5\n";

/// Every file under `folder` with its bytes and mode.
std::map<std::string, std::string> snapshot(const std::string& folder) {
    std::map<std::string, std::string> out;
    for (const auto& [rel, size] : listTree(folder)) {
        const std::string path = folder + "/" + rel;
        struct stat st {};
        if (::lstat(path.c_str(), &st) != 0) continue;
        const std::string mode = std::to_string(st.st_mode) + ":";
        out[rel] = S_ISREG(st.st_mode) ? mode + readFile(path) : mode;
    }
    return out;
}

std::string names(const std::map<std::string, std::string>& files) {
    std::string s;
    for (const auto& [name, bytes] : files) s += "  " + name + "\n";
    return s.empty() ? "  (nothing)\n" : s;
}

RunResult run(const std::vector<std::string>& args, const std::string& cwd) {
    RunOptions options;
    options.cwd = cwd;
    options.timeout_s = RUN_TIMEOUT_S;
    return runGale(args, options);
}

/// Runs `args` in `cwd`: exit `code`, one line on stderr starting "gale: error: " and holding
/// every fragment, and every file in `cwd` byte for byte (and mode for mode) as it was.
void expectRefused(const std::vector<std::string>& args, const std::string& cwd,
                   const std::vector<std::string>& fragments, int code = 2) {
    const auto before = snapshot(cwd);
    const RunResult r = run(args, cwd);
    EXPECT_EQ(r.exitCode, code) << r.describe();
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("gale: error: ", 0), 0u) << r.err;
    for (const std::string& f : fragments) EXPECT_NE(r.err.find(f), std::string::npos) << r.err;
    const auto after = snapshot(cwd);
    EXPECT_TRUE(after == before) << "before:\n" << names(before) << "after:\n" << names(after);
}

/// A 24 x 20 DEM of 2 m pixels (pixelWidth_m wide) in UTM 32N (a tilted plane), written by GDAL.
void writeDem(const std::string& path, const char* driver = "GTiff",
              const std::string& srs = "EPSG:32632", double x0 = 612000.0, double y0 = 4830000.0,
              double pixelWidth_m = 2.0) {
    app::test::TestRaster r;
    r.cols = 24, r.rows = 20;
    const double gt[6] = {x0, pixelWidth_m, 0.0, y0, 0.0, -2.0};
    std::copy(gt, gt + 6, r.gt);
    r.srs = srs;
    r.value = [](int c, int row) { return 150.0 + 0.1 * c - 0.05 * row; };
    ASSERT_EQ(app::test::writeTestRaster(path, r, driver), "");
}

const char* const DEM_SCENE_TAIL =
    "[wind]\nkind = \"solved\"\n[solver]\nvoxel_size_m = 4.0\ntop_m = 60.0\n";

TEST(EveryInput, SolveReportOverTheDemIsRefusedBeforeAnyWork) {
    TempDir cwd;
    writeDem(cwd / "dem.tif");
    writeFile(cwd / "s.toml",
              std::string("[terrain]\nkind = \"dem\"\ndem = \"dem.tif\"\n") + DEM_SCENE_TAIL);
    expectRefused({"solve", "s.toml", "-o", "w.vdb", "--report", "dem.tif"}, cwd.str(),
                  {"--report (the report): 'dem.tif' is also", "terrain.dem (the DEM)"});
}

TEST(EveryInput, SolveRasterNamedLikeTheDemIsRefusedBeforeAnyWork) {
    TempDir cwd;
    writeDem(cwd / "w_10m.tif");
    writeFile(cwd / "s.toml",
              std::string("[terrain]\nkind = \"dem\"\ndem = \"w_10m.tif\"\n") + DEM_SCENE_TAIL);
    expectRefused({"solve", "s.toml", "-o", "w.vdb", "--grid-height-m", "10"}, cwd.str(),
                  {"--grid-height-m w_10m (the .tif raster)", "(the DEM)"});
}

TEST(EveryInput, OutputsOverTheFilesGdalReadsBesideTheDemAreRefused) {
    // An ASCII grid takes its coordinate system from the .prj beside it.
    TempDir cwd;
    writeDem(cwd / "dem.asc", "AAIGrid");
    ASSERT_TRUE(fs::exists(cwd / "dem.prj"));
    writeFile(cwd / "s.toml",
              std::string("[terrain]\nkind = \"dem\"\ndem = \"dem.asc\"\n") + DEM_SCENE_TAIL);
    expectRefused({"solve", "s.toml", "-o", "w.vdb", "--report", "dem.prj"}, cwd.str(),
                  {"'dem.prj' is also", "terrain.dem (beside it, 'dem.prj')"});
    // The rasters of --grid-height-m write a .prj too: dem_10m.prj must not be the DEM's.
    fs::rename(cwd / "dem.prj", cwd / "w_10m.prj");
    fs::rename(cwd / "dem.asc", cwd / "w_10m.asc");
    writeFile(cwd / "s.toml",
              std::string("[terrain]\nkind = \"dem\"\ndem = \"w_10m.asc\"\n") + DEM_SCENE_TAIL);
    expectRefused({"solve", "s.toml", "-o", "w.vdb", "--grid-height-m", "10"}, cwd.str(),
                  {"--grid-height-m w_10m", "(the DEM)"});
}

/// A 16-bit PNG DEM with its world file (.pgw) and its coordinate system in the .aux.xml GDAL
/// writes beside it, as GDAL's PNG driver makes them. Returns "" or GDAL's error.
std::string writePngDem(const std::string& path) {
    app::ensureGdalRegistered();
    GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
    GDALDriver* png = GetGDALDriverManager()->GetDriverByName("PNG");
    if (!mem || !png) return "no GDAL MEM or PNG driver";
    GDALDataset* ds = mem->Create("", 24, 20, 1, GDT_UInt16, nullptr);
    if (!ds) return CPLGetLastErrorMsg();
    double gt[6] = {612000.0, 2.0, 0.0, 4830000.0, 0.0, -2.0};
    ds->SetGeoTransform(gt);
    OGRSpatialReference srs;
    srs.SetFromUserInput("EPSG:32632");
    ds->SetSpatialRef(&srs);
    std::vector<uint16_t> heights(24 * 20);
    for (size_t k = 0; k < heights.size(); ++k) heights[k] = uint16_t(150 + k % 24);
    std::string result;
    if (ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, 24, 20, heights.data(), 24, 20, GDT_UInt16,
                                       0, 0, nullptr) != CE_None)
        result = CPLGetLastErrorMsg();
    const char* options[] = {"WORLDFILE=YES", nullptr};
    GDALDataset* out =
        png->CreateCopy(path.c_str(), ds, FALSE, const_cast<char**>(options), nullptr, nullptr);
    if (!out) result = CPLGetLastErrorMsg();
    GDALClose(out);
    GDALClose(ds);
    return result;
}

TEST(EveryInput, TerrainExportOverAPngDemOrItsWorldFileIsRefused) {
    TempDir cwd;
    ASSERT_EQ(writePngDem(cwd / "dem.png"), "");
    ASSERT_TRUE(fs::exists(cwd / "dem.wld") || fs::exists(cwd / "dem.pgw"))
        << describeTree(listTree(cwd.str()));
    const std::string world = fs::exists(cwd / "dem.wld") ? "dem.wld" : "dem.pgw";
    writeFile(cwd / "s.toml",
              std::string("[terrain]\nkind = \"dem\"\ndem = \"dem.png\"\n") + DEM_SCENE_TAIL);
    expectRefused({"terrain", "s.toml", "-o", "dem.png"}, cwd.str(),
                  {"-o: 'dem.png' is also", "terrain.dem (the DEM)"});
    expectRefused({"solve", "s.toml", "-o", "w.vdb", "--report", world}, cwd.str(),
                  {"terrain.dem (beside it, '" + world + "')"});
}

TEST(EveryInput, RenderOverItsOwnDensityMapIsRefusedBeforeAnyWork) {
    TempDir cwd;
    writeFile(cwd / "tiny.toml", readFile(sourcePath(TINY)));
    fs::create_directories(cwd / "out");
    // A valid grey PNG to serve as the density map: the terrain export of the tiny scene.
    ASSERT_EQ(run({"terrain", "tiny.toml", "-o", "out/frame_0000.png"}, cwd.str()).exitCode, 0);
    fs::copy_file(cwd / "out/frame_0000.png", cwd / "out/frame_sheet.png");
    const std::string scene = readFile(sourcePath(TINY));
    for (const char* mapPath : {"out/frame_0000.png", "out/frame_sheet.png"}) {
        const std::string map = mapPath;
        SCOPED_TRACE(map);
        writeFile(cwd / "d.toml", scene.substr(0, scene.find("[grass]\n") + 8) +
                                      "density_map = \"" + map + "\"\n" +
                                      scene.substr(scene.find("[grass]\n") + 8));
        expectRefused({"render", "d.toml", "-o", "out"}, cwd.str(),
                      {"grass.density_map (the density map)", "is also"});
    }
}

TEST(EveryInput, ATerrainExportOverAHardLinkOfTheHeightmapIsRefused) {
    TempDir cwd;
    writeFile(cwd / "tiny.toml", readFile(sourcePath(TINY)));
    ASSERT_EQ(run({"terrain", "tiny.toml", "-o", "hill.png"}, cwd.str()).exitCode, 0);
    ASSERT_EQ(::link((cwd / "hill.png").c_str(), (cwd / "other.png").c_str()), 0);
    writeFile(cwd / "h.toml",
              "[terrain]\nkind = \"heightmap\"\nimage = \"hill.png\"\nmetres_per_pixel = 0.5\n");
    expectRefused({"terrain", "h.toml", "-o", "other.png"}, cwd.str(),
                  {"-o: 'other.png' is also", "(the heightmap)"});
    // And a hard link of the scene as the report.
    writeFile(cwd / "s.toml", SMALL_SOLVE);
    ASSERT_EQ(::link((cwd / "s.toml").c_str(), (cwd / "r.json").c_str()), 0);
    expectRefused({"solve", "s.toml", "-o", "w.vdb", "--report", "r.json"}, cwd.str(),
                  {"'r.json' is also the scene"});
}

TEST(EveryInput, ViewScreenshotIsCheckedBeforeAnyWork) {
    // Refused before the window opens: no display is needed for these.
    TempDir cwd;
    writeFile(cwd / "tiny.toml", readFile(sourcePath(TINY)));
    ASSERT_EQ(run({"terrain", "tiny.toml", "-o", "hill.png"}, cwd.str()).exitCode, 0);
    writeFile(cwd / "h.toml",
              "[terrain]\nkind = \"heightmap\"\nimage = \"hill.png\"\nmetres_per_pixel = 0.5\n");
    expectRefused({"view", "h.toml", "--frames", "1", "--screenshot", "hill.png"}, cwd.str(),
                  {"--screenshot: 'hill.png' is also", "(the heightmap)"});
    expectRefused({"view", "h.toml", "--frames", "1", "--screenshot", "shot.nosuchformat"},
                  cwd.str(), {"--screenshot: 'shot.nosuchformat': no image format"});
    expectRefused({"view", "h.toml", "--frames", "1", "--screenshot", "no/such/shot.png"},
                  cwd.str(), {"--screenshot: 'no/such/shot.png'", "does not exist"});
}

TEST(EveryInput, ViewInputEventsAreParsedWhole) {
    TempDir cwd;
    writeFile(cwd / "tiny.toml", readFile(sourcePath(TINY)));
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"1x:click:3,4", "FRAME '1x' must be a whole number"},
        {"0x10:click:3,4", "FRAME '0x10' must be a whole number"},
        {"1:click:0x10,4", "'0x10' is not a pixel coordinate"},
        {"1:click:3,4junk", "'4junk' is not a pixel coordinate"},
        {"1:click:inf,4", "'inf' is not a pixel coordinate"},
        {"2147483648:click:3,4", "beyond the last frame the viewer counts to (2147483647)"},
        {"99999999999999999999:click:3,4", "(2147483647)"},
        {"1:click:3,4,", "a coordinate is missing"},
    };
    for (const auto& [input, fragment] : cases) {
        SCOPED_TRACE(input);
        expectRefused({"view", "tiny.toml", "--frames", "1", "--input", input}, cwd.str(),
                      {"--input: entry '" + input + "'", fragment});
    }
}

TEST(EveryOutput, AReadOnlyOutputIsRefusedAndKeptAsItIs) {
    TempDir cwd;
    writeFile(cwd / "s.toml", SMALL_SOLVE);
    writeFile(cwd / "r.json", "an earlier report\n");
    ASSERT_EQ(::chmod((cwd / "r.json").c_str(), 0444), 0);
    expectRefused({"solve", "s.toml", "-o", "w.vdb", "--report", "r.json"}, cwd.str(),
                  {"--report (the report): 'r.json' is read-only"});
    writeFile(cwd / "tiny.toml", readFile(sourcePath(TINY)));
    writeFile(cwd / "ro.png", "not replaced\n");
    ASSERT_EQ(::chmod((cwd / "ro.png").c_str(), 0444), 0);
    expectRefused({"terrain", "tiny.toml", "-o", "ro.png"}, cwd.str(),
                  {"-o: 'ro.png' is read-only"});
}

TEST(EveryOutput, AReportToADeviceIsWrittenAsAStreamAndTheDeviceStays) {
    TempDir cwd;
    writeFile(cwd / "s.toml", SMALL_SOLVE);
    const RunResult ok =
        run({"solve", "s.toml", "-o", "w.vdb", "--report", "/dev/null"}, cwd.str());
    EXPECT_EQ(ok.exitCode, 0) << ok.describe();
    EXPECT_TRUE(fs::is_character_file("/dev/null"));
    EXPECT_TRUE(fs::is_regular_file(cwd / "w.vdb"));
    // A full device: after the solve (its progress line first), exit 1 with one error naming
    // it, and neither the field nor the device replaced.
    fs::remove(cwd / "w.vdb");
    const auto before = snapshot(cwd.str());
    const RunResult full =
        run({"solve", "s.toml", "-o", "w.vdb", "--report", "/dev/full"}, cwd.str());
    EXPECT_EQ(full.exitCode, 1) << full.describe();
    const size_t at = full.err.find("gale: error: ");
    ASSERT_NE(at, std::string::npos) << full.err;
    EXPECT_EQ(full.err.substr(at),
              "gale: error: /dev/full: cannot write: No space left on device\n");
    EXPECT_TRUE(snapshot(cwd.str()) == before) << describeTree(listTree(cwd.str()));
    EXPECT_TRUE(fs::is_character_file("/dev/full"));
}

TEST(EveryOutput, AFieldOrImageOntoADeviceIsRefusedAndTheDeviceStays) {
    TempDir cwd;
    writeFile(cwd / "s.toml", SMALL_SOLVE);
    fs::create_symlink("/dev/null", cwd / "dev.vdb");
    expectRefused({"solve", "s.toml", "-o", "dev.vdb"}, cwd.str(),
                  {"-o (the .vdb field): 'dev.vdb' is a device, FIFO or socket"});
    writeFile(cwd / "tiny.toml", readFile(sourcePath(TINY)));
    fs::create_symlink("/dev/null", cwd / "dev.png");
    expectRefused({"terrain", "tiny.toml", "-o", "dev.png"}, cwd.str(),
                  {"-o: 'dev.png' is a device, FIFO or socket"});
    EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

TEST(EveryOutput, AWriteErrorOnStdoutExitsNonZero) {
    TempDir cwd;
    RunOptions options;
    options.cwd = cwd.str();
    options.timeout_s = RUN_TIMEOUT_S;
    // The shell sends the program's stdout to the full device; $0 is gale.
    options.wrapper = {"sh", "-c", "exec \"$0\" \"$@\" > /dev/full"};
    const RunResult r =
        runGale({"blade", "--shells", "4", "--intensity", "0.5", "--stiffness", "1"}, options);
    EXPECT_EQ(r.exitCode, 1) << r.describe();
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("gale: error: stdout: cannot write: No space left on device"),
              std::string::npos)
        << r.err;
}

TEST(EveryOutput, GridHeightsThatAreNotANumberOrNameOneFileTwiceAreRefused) {
    TempDir cwd;
    writeFile(cwd / "s.toml", SMALL_SOLVE);
    expectRefused({"solve", "s.toml", "-o", "w.vdb", "--grid-height-m", "nan"}, cwd.str(),
                  {"--grid-height-m"});
    expectRefused(
        {"solve", "s.toml", "-o", "w.vdb", "--grid-height-m", "10", "--grid-height-m", "10.0"},
        cwd.str(), {"--grid-height-m: two heights write the same files 'w_10m.tif'"});
    expectRefused({"solve", "s.toml", "-o", "w.vdb", "--grid-height-m", "10.0000001",
                   "--grid-height-m", "10.0000002"},
                  cwd.str(), {"two heights write the same files"});
}

TEST(EveryOutput, AnUnsteadyRunReplacesTheWholeOfAnEarlierLongerSequence) {
    TempDir cwd;
    const std::string head =
        "[terrain]\nkind = \"hemisphere\"\nsize_m = [8.0, 8.0]\nradius_m = 2.0\n"
        "[wind]\nkind = \"unsteady\"\nspeed_mps = 2.0\n[solver]\nvoxel_size_m = 0.5\n"
        "[unsteady]\noutput_every_s = 0.2\n";
    writeFile(cwd / "long.toml", head + "duration_s = 0.6\n");
    writeFile(cwd / "short.toml", head + "duration_s = 0.2\n");
    const RunResult first = run({"solve", "long.toml", "-o", "f/w.vdb"}, cwd.str());
    ASSERT_EQ(first.exitCode, 0) << first.describe();
    ASSERT_EQ(listTree(cwd / "f").size(), 5u) << describeTree(listTree(cwd / "f"));
    // A file named like the sequence that no report lists is someone else's: it stays.
    writeFile(cwd / "f/w_0009.vdb", "not this sequence's\n");
    const RunResult second = run({"solve", "short.toml", "-o", "f/w.vdb"}, cwd.str());
    ASSERT_EQ(second.exitCode, 0) << second.describe();
    EXPECT_NE(second.err.find("removed 2 .vdb files of the earlier sequence"), std::string::npos)
        << second.err;
    EXPECT_NE(second.err.find("that no earlier report lists (e.g. w_0009.vdb)"), std::string::npos)
        << second.err;
    std::vector<std::string> left;
    for (const auto& [name, size] : listTree(cwd / "f")) left.push_back(name);
    EXPECT_EQ(left, (std::vector<std::string>{"w.json", "w_0000.vdb", "w_0001.vdb", "w_0009.vdb"}))
        << describeTree(listTree(cwd / "f"));
    EXPECT_EQ(readFile(cwd / "f/w_0009.vdb"), "not this sequence's\n");
}

TEST(EveryOutput, AnInterruptedUnsteadyRunOverALongerSequenceLeavesExactlyItsOwnFiles) {
    TempDir cwd;
    const std::string head =
        "[terrain]\nkind = \"hemisphere\"\nsize_m = [8.0, 8.0]\nradius_m = 2.0\n"
        "[wind]\nkind = \"unsteady\"\nspeed_mps = 2.0\n[solver]\nvoxel_size_m = 0.5\n"
        "[unsteady]\noutput_every_s = 0.2\n";
    writeFile(cwd / "earlier.toml", head + "duration_s = 2.0\n");  // 11 files
    writeFile(cwd / "long.toml", head + "duration_s = 200.0\n");   // stopped after a few
    const RunResult first = run({"solve", "earlier.toml", "-o", "f/w.vdb"}, cwd.str());
    ASSERT_EQ(first.exitCode, 0) << first.describe();
    RunOptions options;
    options.cwd = cwd.str();
    Child child({"solve", "long.toml", "-o", "f/w.vdb"}, options);
    ASSERT_TRUE(waitFor([&] { return child.errSoFar().find(" 3/1000") != std::string::npos; },
                        RUN_TIMEOUT_S))
        << child.errSoFar();
    child.signal(SIGTERM);
    const RunResult r = child.wait(RUN_TIMEOUT_S);
    ASSERT_EQ(r.exitCode, 128 + SIGTERM) << r.describe();
    const nlohmann::json report = nlohmann::json::parse(readFile(cwd / "f/w.json"));
    const auto& frames = report["outputs"]["vdb_sequence"];
    ASSERT_LT(frames.size(), 11u) << "the run was not stopped before the earlier run's end";
    EXPECT_NE(r.err.find("of the earlier sequence"), std::string::npos) << r.err;
    std::set<std::string> expected{"w.json"};
    for (const auto& f : frames)
        expected.insert(fs::path(f["path"].get<std::string>()).filename().string());
    std::set<std::string> found;
    for (const auto& [rel, size] : listTree(cwd / "f")) found.insert(rel);
    EXPECT_EQ(found, expected) << describeTree(listTree(cwd / "f"));
}

// The turbulence outputs (issue 24, item 5: the .vdb's tke grid, the GeoTIFF's k, intensity and
// gust bands) of a momentum solve stopped while it steps: no field, no raster, no temporary,
// only the report that says how far it got; the same scene run to its end writes them all.
TEST(EveryOutput, AMomentumSolveStoppedWhileSteppingLeavesNoTkeGridOrTurbulenceRaster) {
    TempDir cwd;
    const std::string scene =
        "[terrain]\nkind = \"hemisphere\"\nsize_m = [40.0, 40.0]\nradius_m = 6.0\n"
        "[wind]\nkind = \"solved\"\nspeed_mps = 5.0\n[solver]\nvoxel_size_m = 0.5\n"
        "top_m = 20.0\nmodel = \"momentum\"\nmomentum_max_iterations = 100000\n";
    writeFile(cwd / "m.toml", scene);
    RunOptions options;
    options.cwd = cwd.str();
    Child child({"solve", "m.toml", "-o", "f/w.vdb", "--grid-height-m", "2"}, options);
    ASSERT_TRUE(
        waitFor([&] { return child.errSoFar().find("pseudo-time step") != std::string::npos; },
                RUN_TIMEOUT_S))
        << child.errSoFar();
    child.signal(SIGINT);
    const RunResult r = child.wait(RUN_TIMEOUT_S);
    ASSERT_EQ(r.exitCode, 130) << r.describe();
    std::set<std::string> found;
    for (const auto& [rel, size] : listTree(cwd / "f")) found.insert(rel);
    EXPECT_EQ(found, (std::set<std::string>{"w.json"})) << describeTree(listTree(cwd / "f"));
    const nlohmann::json report = nlohmann::json::parse(readFile(cwd / "f/w.json"));
    EXPECT_TRUE(report["outputs"].empty()) << report["outputs"].dump();

    // Run to the end on a coarser grid: the same outputs, now with the turbulence in them.
    writeFile(cwd / "c.toml",
              "[terrain]\nkind = \"hemisphere\"\nsize_m = [8.0, 8.0]\nradius_m = 2.0\n"
              "[wind]\nkind = \"solved\"\n[solver]\nvoxel_size_m = 0.5\n"
              "model = \"momentum\"\nmomentum_max_iterations = 20\n");
    const RunResult done =
        run({"solve", "c.toml", "-o", "g/w.vdb", "--grid-height-m", "2"}, cwd.str());
    ASSERT_TRUE(done.exitCode == 0 || done.exitCode == 3) << done.describe();
    const nlohmann::json full = nlohmann::json::parse(readFile(cwd / "g/w.json"));
    EXPECT_NE(full["outputs"]["vdb"]["grids"].dump().find("tke (float"), std::string::npos)
        << full["outputs"]["vdb"].dump();
    EXPECT_EQ(full["outputs"]["rasters"][0]["bands"].size(), 5u);
    EXPECT_TRUE(hiddenOrTemporary(cwd.str()).empty()) << describeTree(listTree(cwd.str()));
}

TEST(EveryInput, ACorruptOrForeignVdbGetsGalesOwnMessage) {
    TempDir cwd;
    writeFile(cwd / "s.toml", SMALL_SOLVE);
    ASSERT_EQ(run({"solve", "s.toml", "-o", "w.vdb"}, cwd.str()).exitCode, 0);
    writeFile(cwd / "p.csv", "name,x,y,height_agl_m\nm,1,1,2\n");
    const std::string good = readFile(cwd / "w.vdb");
    ASSERT_GT(good.size(), 4000u);
    std::string flipped = good;
    for (size_t at = 200; at < flipped.size(); at += 997) flipped[at] = char(~flipped[at]);
    writeFile(cwd / "flipped.vdb", flipped);
    writeFile(cwd / "cut.vdb", good.substr(0, good.size() / 2));
    writeFile(cwd / "text.vdb", "this is not a field\n");
    writeFile(cwd / "empty.vdb", "");
    for (const char* badName : {"flipped.vdb", "cut.vdb", "text.vdb", "empty.vdb"}) {
        const std::string bad = badName;
        SCOPED_TRACE(bad);
        const auto before = snapshot(cwd.str());
        const RunResult r = run({"probe", "s.toml", "p.csv", "--vdb", bad}, cwd.str());
        EXPECT_EQ(r.exitCode, 2) << r.describe();
        EXPECT_EQ(countLines(r.err), 1) << r.err;
        EXPECT_NE(r.err.find("gale: error: " + bad + ": "), std::string::npos) << r.err;
        for (const char* leak : {"LookupError", "IoError", "ValueError", "KeyError"})
            EXPECT_EQ(r.err.find(leak), std::string::npos) << r.err;
        EXPECT_TRUE(snapshot(cwd.str()) == before);
    }
}

/// Whether this test binary, and so the gale beside it, runs under a sanitizer (which maps
/// terabytes of shadow memory: an address-space limit would stop it at once).
constexpr bool UNDER_SANITIZER =
#if defined(__SANITIZE_ADDRESS__)
    true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
    true;
#else
    false;
#endif
#else
    false;
#endif

TEST(EveryInput, ACorruptVdbGridDescriptorCostsBoundedMemory) {
    if (UNDER_SANITIZER) GTEST_SKIP() << "an address-space limit cannot hold a sanitized gale";
    TempDir cwd;
    writeFile(cwd / "s.toml", SMALL_SOLVE);
    ASSERT_EQ(run({"solve", "s.toml", "-o", "w.vdb"}, cwd.str()).exitCode, 0);
    writeFile(cwd / "p.csv", "name,x,y,height_agl_m\nm,1,1,2\n");
    // The first grid descriptor: name, tree type, instance parent, then the grid's, its trees'
    // and its end's stream positions (int64 each). One byte of the end position changed sends
    // OpenVDB into the tree data for the next descriptor, whose "string length" it allocated:
    // 3.1 GB resident before (a fuzzed file found it), a bad_alloc under this limit.
    std::string bytes = readFile(cwd / "w.vdb");
    const std::string type = "Tree_vec3s_5_4_3";
    const size_t at = bytes.find(type);
    ASSERT_NE(at, std::string::npos);
    const size_t endPosition = at + type.size() + 4 + 8 + 8;
    ASSERT_LT(endPosition + 8, bytes.size());
    bytes[endPosition + 1] = char(0x4a);
    writeFile(cwd / "bad.vdb", bytes);
    RunOptions options;
    options.cwd = cwd.str();
    options.timeout_s = RUN_TIMEOUT_S;
    // 1.5 GB of address space: a good probe of this scene needs under 1 GB.
    options.wrapper = {"sh", "-c", "ulimit -v 1500000 && exec \"$0\" \"$@\""};
    options.env = {{"GALE_THREADS", "2"}};  // each worker thread maps its stack and arena
    const RunResult good = runGale({"probe", "s.toml", "p.csv", "--vdb", "w.vdb"}, options);
    ASSERT_EQ(good.exitCode, 0) << good.describe();
    const RunResult r = runGale({"probe", "s.toml", "p.csv", "--vdb", "bad.vdb"}, options);
    EXPECT_EQ(r.exitCode, 2) << r.describe();
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("gale: error: bad.vdb: not a readable .vdb file (corrupt"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(r.err.find("bad_alloc"), std::string::npos) << r.err;
}

TEST(EveryInput, AWebMercatorDemIsRefusedWithARunnableReprojection) {
    // EPSG:3857 at 47 degrees north: its "metres" are 1.47 ground metres.
    TempDir cwd;
    const double lat = 47.0 * M_PI / 180.0, lon = 9.0 * M_PI / 180.0, R = 6378137.0;
    writeDem(cwd / "dem.tif", "GTiff", "EPSG:3857", R * lon,
             R * std::log(std::tan(M_PI / 4 + lat / 2)));
    writeFile(cwd / "s.toml",
              std::string("[terrain]\nkind = \"dem\"\ndem = \"dem.tif\"\n") + DEM_SCENE_TAIL);
    expectRefused(
        {"check", "s.toml"}, cwd.str(),
        {"dem.tif", "Mercator", "scale factor", "1.466", "gdalwarp -t_srs EPSG:32632 -r bilinear"});
}

TEST(EveryInput, ADemWithANegativePixelSizeGetsNoUnrunnableCommand) {
    TempDir cwd;
    writeDem(cwd / "dem.tif", "GTiff", "EPSG:32632", 612000.0, 4830000.0, -2.0);
    writeFile(cwd / "s.toml",
              std::string("[terrain]\nkind = \"dem\"\ndem = \"dem.tif\"\n") + DEM_SCENE_TAIL);
    expectRefused({"check", "s.toml"}, cwd.str(), {"dem.tif", "not a positive size"});
    const RunResult r = run({"check", "s.toml"}, cwd.str());
    EXPECT_EQ(r.err.find("gdalwarp -tr -"), std::string::npos) << r.err;
}

TEST(EveryOutput, VorticityConfinementThatGrowsTheEnergyExitsThreeAndSaysSo) {
    // epsilon = 100, the documented maximum, drove the peak speed from 6 to 255 m/s with exit 0.
    TempDir cwd;
    writeFile(cwd / "vc.toml",
              "[terrain]\nkind = \"hemisphere\"\nsize_m = [8.0, 8.0]\nradius_m = 2.0\n"
              "[wind]\nkind = \"unsteady\"\nspeed_mps = 2.0\n[solver]\nvoxel_size_m = 0.5\n"
              "[unsteady]\noutput_every_s = 0.5\nduration_s = 1.0\nvorticity_confinement = 100\n");
    const RunResult r = run({"solve", "vc.toml", "-o", "f/w.vdb"}, cwd.str());
    EXPECT_EQ(r.exitCode, 3) << r.describe();
    EXPECT_NE(r.out.find("solve: vorticity confinement 100 grew the kinetic energy"),
              std::string::npos)
        << r.out;
    EXPECT_NE(readFile(cwd / "f/w.json").find("lower unsteady.vorticity_confinement"),
              std::string::npos);
}

TEST(EveryInput, ProbeOutputOverAnyOfItsInputsIsRefusedBeforeAnyWork) {
    TempDir cwd;
    writeFile(cwd / "s.toml", SMALL_SOLVE);
    writeFile(cwd / "pts.csv", "name,x,y,height_agl_m\na,1,4,1\n");
    ASSERT_EQ(run({"solve", "s.toml", "-o", "w.vdb"}, cwd.str()).exitCode, 0);
    fs::create_directories(cwd / "sub");
    expectRefused({"probe", "s.toml", "pts.csv", "-o", "pts.csv"}, cwd.str(),
                  {"-o (the probe output)", "the points file"});
    expectRefused({"probe", "s.toml", "pts.csv", "-o", "sub/../pts.csv"}, cwd.str(),
                  {"-o (the probe output)", "the points file"});
    expectRefused({"probe", "s.toml", "pts.csv", "-o", "s.toml"}, cwd.str(),
                  {"-o (the probe output)", "the scene"});
    expectRefused({"probe", "s.toml", "pts.csv", "--vdb", "w.vdb", "-o", "w.vdb"}, cwd.str(),
                  {"-o (the probe output)", "--vdb"});
}

TEST(EveryOutput, AProbeTableToADeviceIsAStreamAndTheDeviceStays) {
    TempDir cwd;
    writeFile(cwd / "s.toml", SMALL_SOLVE);
    writeFile(cwd / "pts.csv", "name,x,y,height_agl_m\na,1,4,1\n");
    const RunResult ok = run({"probe", "s.toml", "pts.csv", "-o", "/dev/null"}, cwd.str());
    EXPECT_EQ(ok.exitCode, 0) << ok.describe();
    EXPECT_TRUE(fs::is_character_file("/dev/null"));
    const RunResult full = run({"probe", "s.toml", "pts.csv", "-o", "/dev/full"}, cwd.str());
    EXPECT_EQ(full.exitCode, 1) << full.describe();
    EXPECT_TRUE(fs::is_character_file("/dev/full"));
}

TEST(EveryInput, AProbeSeriesOfVdbFilesFromTwoRunsIsRefused) {
    TempDir cwd;
    writeFile(cwd / "s.toml", SMALL_SOLVE);
    // The same scene with another wind: its field belongs to another run.
    std::string windier = SMALL_SOLVE;
    windier.replace(windier.find("kind = \"solved\""), 15, "kind = \"solved\"\nspeed_mps = 9.0");
    writeFile(cwd / "t.toml", windier);
    writeFile(cwd / "pts.csv", "name,x,y,height_agl_m\na,1,4,1\n");
    ASSERT_EQ(run({"solve", "s.toml", "-o", "a.vdb"}, cwd.str()).exitCode, 0);
    ASSERT_EQ(run({"solve", "t.toml", "-o", "b.vdb"}, cwd.str()).exitCode, 0);
    const RunResult r =
        run({"probe", "s.toml", "pts.csv", "--vdb", "a.vdb", "b.vdb", "-o", "o.csv"}, cwd.str());
    EXPECT_EQ(r.exitCode, 2) << r.describe();
    EXPECT_NE(r.err.find("come from different runs (their wind_digest differs)"), std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(cwd / "o.csv"));
}

}  // namespace
}  // namespace gale::reliability
