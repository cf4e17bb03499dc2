#pragma once
/// \file Animation.h
/// What a person looks at instead of 48 PNGs: a contact sheet (a grid of evenly spaced frames)
/// and an animated GIF, both through OpenImageIO. Streaming: the sheet keeps only thumbnails and
/// the GIF is written frame by frame to a hidden temporary file that is renamed on finish(), so an
/// interrupted run leaves neither half a sheet nor half a GIF.

#include <memory>
#include <string>
#include <vector>

#include "render/GrassInput.h"

namespace gale::render {

struct AnimationOptions {
    std::string sheetPath;      ///< contact sheet (.png ...); empty: none
    std::string gifPath;        ///< animated GIF (.gif); empty: none
    double fps = 24.0;          ///< GIF playback rate, frames per second (> 0)
    int sheetColumns = 6;       ///< thumbnails per row
    int sheetFrames = 24;       ///< at most this many frames on the sheet, evenly spaced
    int sheetThumbWidth = 240;  ///< thumbnail width in pixels (height keeps the aspect ratio)
    int gifMaxWidth = 480;      ///< GIF frames wider than this are scaled down
};

/// Area-averaging downscale of an RGBA8 image to width x height (<= the source size, at least
/// 1 x 1; std::logic_error otherwise).
Image downscale(const Image& src, int width, int height);

class AnimationWriter {
  public:
    /// totalFrames is the number of frames the run will add (>= 1). Throws std::runtime_error if
    /// the GIF cannot be started (names the path), gale::ParameterError naming output.frames or
    /// output.fps when totalFrames < 1 or fps is not > 0 and finite.
    AnimationWriter(const AnimationOptions& options, int totalFrames);
    /// Removes the temporary GIF if finish() was not reached.
    ~AnimationWriter();
    AnimationWriter(const AnimationWriter&) = delete;
    AnimationWriter& operator=(const AnimationWriter&) = delete;

    /// Frame `index` (0-based, in order) of the run.
    void addFrame(const Image& frame, int index);
    /// Writes the sheet and moves the GIF into place. Frames added so far are what they show.
    void finish();

    /// Indices of the frames the sheet shows for a run of totalFrames (evenly spaced, first and
    /// last included).
    static std::vector<int> sheetIndices(int totalFrames, int sheetFrames);

  private:
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

}  // namespace gale::render
