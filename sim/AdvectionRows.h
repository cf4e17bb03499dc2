#pragma once
/// \file AdvectionRows.h
/// \internal Included only by sim/Advection.cpp (docs/architecture.md lists sim's public headers).
/// The single-precision semi-Lagrangian pass on cubic cells (AdvectionPrecision::Single,
/// docs/unsteady.md "Single precision and rows"): the samples of a placement's x row as SIMD
/// lanes (Google Highway, chosen at run time for the machine: AVX-512, AVX2, SSE4 or scalar),
/// in index space (cells) and float, with no branch per sample: every clamp a select, every
/// trilinear read a gather.
///
/// Per sample: the velocity at the sample itself, one explicit midpoint substep
///   X_mid = X - D(X) / 2,  X_dep = X - D(X_mid),   D = u dt / h (cells),
/// then q trilinearly at X_dep with the min/max of its 8 values (the limiters' bounds). That is
/// the general trace (Advection.h) whenever the trace is one substep that stays in the box and
/// ends above the terrain. Every sample where it is not (the start's displacement over
/// MAX_TRACE_CELLS_PER_SUBSTEP cells, a midpoint or departure outside the box, a departure below
/// the terrain surface, a non-finite velocity) is flagged, and the caller redoes those samples
/// on the general double-precision path: the row loop never decides what the general path would.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace gale::sim::detail {

/// What a row pass reads, in index space of a box of cubic cells of edge h.
struct RowPassInput {
    int n[3] = {0, 0, 0};      ///< cells along x, y, z (>= 2 each)
    int placement = 0;         ///< Placement of q (0 FaceX, 1 FaceY, 2 FaceZ, 3 Cell)
    const float* u = nullptr;  ///< the three MAC velocity components, m/s, as float
    const float* v = nullptr;
    const float* w = nullptr;
    const float* q = nullptr;        ///< the advected quantity as float
    const double* qExact = nullptr;  ///< the same in double: what a masked-out sample keeps
    const uint8_t* mask = nullptr;   ///< 0: copy the sample unchanged (never null)
    float cellsPerMps = 0;           ///< dt / h, s/m (negative: a forward trace)
    /// The velocity at every sample (m/s; u at [idx], v at [count + idx], w at [2 count + idx],
    /// count = samples of the placement), which depends on neither the pass nor q: a first pass
    /// writes it (recordStart), later passes of the same call read it (start) instead of
    /// interpolating again. The array holds 3 count + ROW_PASS_PADDING floats (reads run past the
    /// last row by up to a vector). Both null: interpolated in every pass.
    float* recordStart = nullptr;
    const float* start = nullptr;
    size_t count = 0;
    /// The terrain, or heights == nullptr: heights (metres, i fastest, hnx * hny), index
    /// coordinate of the heightfield = X * hScale + hOffsetX (Y likewise), and the index-space
    /// height Z of a world height z_m = z_m * zScale + zOffset. groundTop: index-space Z above
    /// which no terrain lies.
    const float* heights = nullptr;
    int hnx = 0, hny = 0;
    float hScale = 0, hOffsetX = 0, hOffsetY = 0, zScale = 0, zOffset = 0;
    float groundTop = -1e30f;
};

/// Floats past 3 count that a `start` array must hold.
constexpr size_t ROW_PASS_PADDING = 64;

/// out = a rounded to float (resized to a's length), in parallel chunks: the row kernels' inputs.
void roundToFloat(const std::vector<double>& a, std::vector<float>& out);

/// Writes out, lo and hi (lo/hi may both be null) and general (1: redo on the general path; the
/// other three are then unspecified) for every sample of row (j, k) of the input's placement.
/// Arrays are indexed like the placement's arrays (GridIndex::index).
void rowPass(const RowPassInput& in, int j, int k, double* out, double* lo, double* hi,
             uint8_t* general);

}  // namespace gale::sim::detail
