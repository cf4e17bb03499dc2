#include "app/io/ImageCheck.h"

#include <OpenImageIO/imageio.h>

#include <cstring>
#include <stdexcept>
#include <vector>

#include "app/io/QuietStderr.h"

namespace gale::app {

void verifyImageFile(const std::string& tmpPath, const std::string& path, int width, int height,
                     int writerErrno) {
    bool ok = false;
    int subimages = 0;
    std::string detail;
    {
        const QuietStderr quiet;
        auto in = OIIO::ImageInput::open(tmpPath);
        if (in) {
            ok = true;
            std::vector<float> pixels;
            while (ok && in->seek_subimage(subimages, 0)) {
                const OIIO::ImageSpec& spec = in->spec();
                ok = width < 0 || (spec.width == width && spec.height == height);
                pixels.resize(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
                ok = ok && in->read_image(0, 0, 0, -1, OIIO::TypeDesc::FLOAT, pixels.data());
                ++subimages;
            }
            ok = ok && subimages > 0;
            detail = in->geterror();
            in->close();
        } else {
            detail = OIIO::geterror();
        }
    }
    if (ok) return;
    const std::string reason =
        writerErrno != 0 ? std::strerror(writerErrno) : "the file is incomplete";
    throw std::runtime_error(path + ": cannot write: " + reason + " (it does not read back whole)");
}

}  // namespace gale::app
