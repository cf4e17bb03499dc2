// Atomic image writes and RGBA8 reads (STYLE: never write a half file).
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "RenderTestUtil.h"
#include "render/ImageIO.h"

namespace gale::render {
namespace {

namespace fs = std::filesystem;

Image makeGradient(int w, int h) {
    Image image;
    image.width = w;
    image.height = h;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            image.rgba.insert(image.rgba.end(),
                              {static_cast<uint8_t>(x * 16), static_cast<uint8_t>(y * 16),
                               static_cast<uint8_t>(x + y), static_cast<uint8_t>(255 - x)});
        }
    }
    return image;
}

std::vector<std::string> filesIn(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename());
    std::sort(names.begin(), names.end());
    return names;
}

void expectThrowNaming(const std::function<void()>& f, const std::string& fragment) {
    try {
        f();
        ADD_FAILURE() << "expected std::runtime_error naming " << fragment;
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
}

TEST(ImageIO, WriteIntoMissingFolderThrowsNamingPathAndLeavesNothing) {
    const fs::path dir = test::freshTestDir("ImageIO_missing");
    const std::string path = (dir / "no_such_folder" / "frame.png").string();
    expectThrowNaming([&] { writeImageAtomic(makeGradient(4, 4), path); }, path);
    EXPECT_TRUE(filesIn(dir).empty());
}

TEST(ImageIO, WriteIntoAFileAsFolderThrowsNamingPathAndLeavesNothing) {
    const fs::path dir = test::freshTestDir("ImageIO_fileAsFolder");
    std::ofstream(dir / "plain_file") << "not a folder";
    const std::string path = (dir / "plain_file" / "frame.png").string();
    expectThrowNaming([&] { writeImageAtomic(makeGradient(4, 4), path); }, path);
    EXPECT_EQ(filesIn(dir), std::vector<std::string>{"plain_file"});
}

TEST(ImageIO, UnknownExtensionThrowsAndLeavesNoTempFile) {
    const fs::path dir = test::freshTestDir("ImageIO_badExt");
    const std::string path = (dir / "frame.notaformat").string();
    expectThrowNaming([&] { writeImageAtomic(makeGradient(4, 4), path); }, path);
    EXPECT_TRUE(filesIn(dir).empty());
}

TEST(ImageIO, SuccessfulWriteLeavesExactlyTheTargetAndRoundTrips) {
    const fs::path dir = test::freshTestDir("ImageIO_ok");
    const Image image = makeGradient(16, 8);
    writeImageAtomic(image, (dir / "frame.png").string());
    EXPECT_EQ(filesIn(dir), std::vector<std::string>{"frame.png"});
    const Image back = readImageRgba8((dir / "frame.png").string());
    EXPECT_EQ(back.width, 16);
    EXPECT_EQ(back.height, 8);
    EXPECT_EQ(back.rgba, image.rgba);
    // Overwriting an existing file works the same way.
    writeImageAtomic(image, (dir / "frame.png").string());
    EXPECT_EQ(filesIn(dir), std::vector<std::string>{"frame.png"});
}

TEST(ImageIO, ReadExpandsSixteenBitGreyToRgba8) {
    const fs::path dir = test::freshTestDir("ImageIO_grey16");
    const std::string path = (dir / "grey16.png").string();
    {
        auto out = OIIO::ImageOutput::create(path);
        ASSERT_TRUE(out);
        OIIO::ImageSpec spec(2, 1, 1, OIIO::TypeDesc::UINT16);
        ASSERT_TRUE(out->open(path, spec));
        const uint16_t values[2] = {0, 65535};
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT16, values));
        out->close();
    }
    const Image image = readImageRgba8(path);
    ASSERT_EQ(image.rgba.size(), 8u);
    EXPECT_EQ(image.rgba, (std::vector<uint8_t>{0, 0, 0, 255, 255, 255, 255, 255}));
}

TEST(ImageIO, ReadOfTruncatedPngThrowsNamingPath) {
    const fs::path dir = test::freshTestDir("ImageIO_truncated");
    const std::string path = (dir / "cut.png").string();
    writeImageAtomic(makeGradient(64, 64), path);
    const auto size = fs::file_size(path);
    fs::resize_file(path, size / 2);
    expectThrowNaming([&] { readImageRgba8(path); }, path);
}

TEST(ImageIO, ReadOfMissingFileThrowsNamingPath) {
    const fs::path dir = test::freshTestDir("ImageIO_none");
    const std::string path = (dir / "absent.png").string();
    expectThrowNaming([&] { readImageRgba8(path); }, path);
}

}  // namespace
}  // namespace gale::render
