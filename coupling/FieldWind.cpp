#include "coupling/FieldWind.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <glm/geometric.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "base/Numbers.h"
#include "base/ParameterError.h"
#include "coupling/GroupGrid.h"
#include "coupling/PointSourceWind.h"

namespace gale::coupling {
namespace {

// Vertices per chunk of the group sums (fixed, so the sums do not depend on the threads).
constexpr size_t SUM_CHUNK = 65536;
// Below this many vertices a loop runs serially: TBB's overhead would dominate.
constexpr size_t PARALLEL_GRAIN = 4096;

struct Named {
    const char* name;
    int value;
};
constexpr Named RESPONSES[] = {{"static", int(BladeResponse::Static)},
                               {"oscillator", int(BladeResponse::Oscillator)}};
constexpr Named GROUPINGS[] = {{"levels", int(Grouping::Levels)},
                               {"tiles", int(Grouping::Tiles)},
                               {"per_vertex", int(Grouping::PerVertex)}};

template <size_t N>
int fromName(const Named (&table)[N], const std::string& name, const char* field) {
    std::string valid;
    for (const Named& n : table) {
        if (name == n.name) return n.value;
        valid += std::string(valid.empty() ? "" : ", ") + n.name;
    }
    throw ParameterError(field, "'" + name + "'", "expected one of: " + valid);
}

template <size_t N>
const char* toName(const Named (&table)[N], int value) {
    for (const Named& n : table)
        if (n.value == value) return n.name;
    return "unknown";
}

void requirePositive(double v, const char* field) {
    if (!std::isfinite(v) || v <= 0.0)
        throw ParameterError(field, formatG(v), "must be a finite number > 0");
}

glm::vec3 finiteOrZero(const glm::vec3& v) {
    return (std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)) ? v : glm::vec3(0.0f);
}

}  // namespace

const char* bladeResponseName(BladeResponse r) { return toName(RESPONSES, int(r)); }
const char* groupingName(Grouping g) { return toName(GROUPINGS, int(g)); }
BladeResponse bladeResponseFromName(const std::string& name) {
    return BladeResponse(fromName(RESPONSES, name, "wind.response"));
}
Grouping groupingFromName(const std::string& name) {
    return Grouping(fromName(GROUPINGS, name, "wind.grouping"));
}

void validate(const FieldWindSpec& spec) {
    if (spec.grouping != Grouping::PerVertex && (spec.groups < 1 || spec.groups > 4096))
        throw ParameterError("wind.groups", std::to_string(spec.groups), "must be in 1..4096");
    requirePositive(spec.bendSpeed_mps, "wind.bend_speed_mps");
    requirePositive(spec.maxIntensity, "wind.max_intensity");
    requirePositive(spec.frequency_hz, "wind.frequency_hz");
    requirePositive(spec.dampingRatio, "wind.damping_ratio");
    if (spec.response == BladeResponse::Oscillator && spec.grouping == Grouping::Levels)
        throw ParameterError("wind.grouping", "\"levels\"",
                             "\"tiles\" or \"per_vertex\" with response = \"oscillator\": "
                             "'levels' regroups vertices at every field step, which would tear "
                             "an oscillator's state apart");
}

FieldWind::FieldWind(const render::TerrainMesh& mesh, const FieldWindSpec& spec)
    : mSpec(spec), mOscillators(spec.frequency_hz, spec.dampingRatio) {
    validate(spec);
    const size_t count = mesh.wsPosition_m.size();
    if (count == 0) throw std::logic_error("field wind needs a terrain mesh with vertices");
    if (mesh.wsNormal.size() != count)
        throw std::logic_error("terrain mesh has " + std::to_string(count) + " positions but " +
                               std::to_string(mesh.wsNormal.size()) + " normals");
    mNormal = mesh.wsNormal;
    // The per-interval buffers, sized once here rather than at the first field step.
    mDrive0.resize(count);
    mDrive1.resize(count);
    mVertexPool.push_back(newVertexBuffer(count));
    if (spec.grouping == Grouping::PerVertex) {
        mGroupCount = static_cast<int>(count);
        mTile.resize(count);
        for (size_t v = 0; v < count; ++v) mTile[v] = static_cast<uint32_t>(v);
    } else {
        mGroupCount = spec.groups;
        mGroupColumns = spec.groups;  // levels: one row in intensity order
    }
    if (spec.grouping == Grouping::Tiles) {
        glm::vec3 lo = mesh.wsPosition_m[0], hi = lo;
        for (const glm::vec3& p : mesh.wsPosition_m) lo = glm::min(lo, p), hi = glm::max(hi, p);
        const int kx = std::max(1, static_cast<int>(std::ceil(std::sqrt(double(spec.groups)))));
        const int ky = std::max(1, (spec.groups + kx - 1) / kx);
        const float sx = std::max(hi.x - lo.x, 1e-6f), sy = std::max(hi.y - lo.y, 1e-6f);
        mTile.resize(count);
        mGroupColumns = kx;
        if (spec.blendGroups) mTileCoord.resize(count);
        for (size_t v = 0; v < count; ++v) {
            const glm::vec3& p = mesh.wsPosition_m[v];
            const int tx = std::min(kx - 1, static_cast<int>((p.x - lo.x) / sx * kx));
            const int ty = std::min(ky - 1, static_cast<int>((p.y - lo.y) / sy * ky));
            mTile[v] = static_cast<uint32_t>(std::min(spec.groups - 1, ty * kx + tx));
            if (spec.blendGroups)
                mTileCoord[v] = {binCoord(p.x, lo.x, sx, kx), binCoord(p.y, lo.y, sy, ky)};
        }
    }
}

void FieldWind::addFieldStep(double t_s, std::vector<glm::vec3> wsVelocity_mps) {
    if (!std::isfinite(t_s)) throw std::logic_error("field step time must be finite");
    if (wsVelocity_mps.size() != mNormal.size())
        throw std::logic_error("field step has " + std::to_string(wsVelocity_mps.size()) +
                               " velocities for " + std::to_string(mNormal.size()) +
                               " grass vertices");
    if (!mSteps.empty() && !(t_s > mSteps.back().t_s))
        throw std::logic_error("field step at t = " + std::to_string(t_s) +
                               " s does not follow the previous step at t = " +
                               std::to_string(mSteps.back().t_s) + " s");
    mSteps.push_back({t_s, std::move(wsVelocity_mps)});
}

void FieldWind::replaceLastStep(std::vector<glm::vec3> wsVelocity_mps) {
    if (mSteps.empty()) throw std::logic_error("no field step to replace yet");
    if (wsVelocity_mps.size() != mNormal.size())
        throw std::logic_error("field step has " + std::to_string(wsVelocity_mps.size()) +
                               " velocities for " + std::to_string(mNormal.size()) +
                               " grass vertices");
    mSpare = std::exchange(mSteps.back().wsVelocity_mps, std::move(wsVelocity_mps));
    // The interval reads the newest step when it ends there (or is the held last step).
    if (mHaveInterval && mIntervalFirst + 2 >= mSteps.size()) enterInterval(mIntervalFirst);
}

void FieldWind::dropStepsBefore(double t_s) {
    while (mSteps.size() > 2 && mSteps[1].t_s <= t_s) {
        mSpare = std::move(mSteps.front().wsVelocity_mps);
        mSteps.pop_front();
        if (mHaveInterval) {
            if (mIntervalFirst == 0)
                mHaveInterval = false;
            else
                --mIntervalFirst;
        }
    }
}

void FieldWind::setFlutter(std::vector<float> flutter_rad) {
    if (!flutter_rad.empty() && flutter_rad.size() != mNormal.size())
        throw std::logic_error("FieldWind::setFlutter: " + std::to_string(flutter_rad.size()) +
                               " amplitudes for " + std::to_string(mNormal.size()) + " vertices");
    // The current interval's buffer is shared with the renderer and never written: the next
    // interval entered carries the new amplitudes (with no interval yet, the first one).
    mFlutter = std::move(flutter_rad);
}

std::shared_ptr<render::VertexWind> FieldWind::newVertexBuffer(size_t count) {
    auto buffer = std::make_shared<render::VertexWind>();
    buffer->wsDirection.resize(count);
    buffer->group.resize(count);
    return buffer;
}

std::shared_ptr<render::VertexWind> FieldWind::freeVertexBuffer() {
    // A buffer only the pool holds is written by nobody else and read by nobody: reuse it. (The
    // current interval's buffer is never reused: update() may still hand it out.)
    for (const auto& buffer : mVertexPool) {
        if (buffer != mVertex && buffer.use_count() == 1) {
            // use_count() reads the count relaxed; the last other holder released its reference
            // with release semantics: this fence orders its reads of the buffer before our writes.
            std::atomic_thread_fence(std::memory_order_acquire);
            return buffer;
        }
    }
    // All held elsewhere (a viewer's snapshots): the pool lets go of those, its holders free them
    // when done, and the pool gets a fresh buffer. So the pool never outgrows what is in use.
    mVertexPool.erase(
        std::remove_if(mVertexPool.begin(), mVertexPool.end(),
                       [&](const auto& b) { return b != mVertex && b.use_count() > 1; }),
        mVertexPool.end());
    mVertexPool.push_back(newVertexBuffer(mNormal.size()));
    return mVertexPool.back();
}

void FieldWind::enterInterval(size_t first) {
    const size_t last = std::min(first + 1, mSteps.size() - 1);
    const Step& a = mSteps[first];
    const Step& b = mSteps[last];
    const size_t count = mNormal.size();
    const std::shared_ptr<render::VertexWind> next = freeVertexBuffer();
    std::vector<glm::vec3>& direction = next->wsDirection;
    std::vector<uint32_t>& group = next->group;
    const bool levels = mSpec.grouping == Grouping::Levels;
    const bool blend = mSpec.blendGroups && mSpec.grouping != Grouping::PerVertex;
    next->groupColumns = mGroupColumns;
    std::vector<glm::vec2>& coord = next->groupCoord;
    coord.resize(blend ? count : 0);
    next->flutter_rad = mFlutter;
    const double maxI = mSpec.maxIntensity;
    const double invBend = 1.0 / mSpec.bendSpeed_mps;

    // Pass 1, per vertex: direction and drives at both ends; for levels, the range of the
    // mid-interval drives (min and max are exact in any order: the reduction is deterministic).
    using MinMax = std::pair<float, float>;
    auto directionsAndDrives = [&](size_t begin, size_t end, MinMax acc) {
        for (size_t v = begin; v != end; ++v) {
            const glm::vec3 wa = finiteOrZero(a.wsVelocity_mps[v]);
            const glm::vec3 wb = finiteOrZero(b.wsVelocity_mps[v]);
            // One direction for the interval: the tangent part of the mean wind (docs/design.md 5,
            // step 2); a wind that reverses within one step has no mean direction and gets none.
            const glm::vec3 dir = tangentWindDirection(wa + wb, mNormal[v]);
            direction[v] = dir;
            // Static response along that direction: signed tangent speed over the bend speed.
            const float d0 =
                static_cast<float>(std::clamp(glm::dot(wa, dir) * invBend, -maxI, maxI));
            const float d1 =
                static_cast<float>(std::clamp(glm::dot(wb, dir) * invBend, -maxI, maxI));
            mDrive0[v] = d0, mDrive1[v] = d1;
            const float mid = 0.5f * (d0 + d1);
            acc.first = std::min(acc.first, mid), acc.second = std::max(acc.second, mid);
        }
        return acc;
    };
    const MinMax empty{float(maxI), float(-maxI)};
    const MinMax range =
        count < PARALLEL_GRAIN
            ? directionsAndDrives(0, count, empty)
            : tbb::parallel_reduce(
                  tbb::blocked_range<size_t>(0, count, PARALLEL_GRAIN), empty,
                  [&](const tbb::blocked_range<size_t>& r, MinMax acc) {
                      return directionsAndDrives(r.begin(), r.end(), acc);
                  },
                  [](MinMax x, MinMax y) {
                      return MinMax{std::min(x.first, y.first), std::max(x.second, y.second)};
                  });

    // Pass 2, per chunk of SUM_CHUNK vertices: groups (levels: K equal bins over the range the
    // mid-interval drives span, so no level is spent on intensities no vertex has; otherwise the
    // fixed tiles) and each chunk's sums of the drives per group. The chunk sums are added in
    // chunk order: the same bits whatever the thread count.
    const float lo = range.first;
    const double binsPerDrive = mGroupCount / std::max(double(range.second) - lo, 1e-9);
    const bool perVertex = mSpec.grouping == Grouping::PerVertex;
    const size_t chunks = (count + SUM_CHUNK - 1) / SUM_CHUNK;
    struct Partial {
        std::vector<double> s0, s1;
        std::vector<uint32_t> n;
    };
    std::vector<Partial> partial(perVertex ? 0 : chunks);
    auto groupChunk = [&](size_t c) {
        const size_t begin = c * SUM_CHUNK, end = std::min(count, begin + SUM_CHUNK);
        for (size_t v = begin; v != end; ++v) {
            if (levels) {
                const double mid = 0.5 * (double(mDrive0[v]) + mDrive1[v]);
                const int level = static_cast<int>((mid - lo) * binsPerDrive);
                group[v] = static_cast<uint32_t>(std::clamp(level, 0, mGroupCount - 1));
                if (blend)
                    coord[v] = {binCoord(mid, lo, mGroupCount / binsPerDrive, mGroupCount), 0.0f};
            } else {
                group[v] = mTile[v];
                if (blend) coord[v] = mTileCoord[v];
            }
        }
        if (perVertex) return;  // one group per vertex: nothing to sum
        Partial& p = partial[c];
        p.s0.assign(mGroupCount, 0.0), p.s1.assign(mGroupCount, 0.0), p.n.assign(mGroupCount, 0);
        for (size_t v = begin; v != end; ++v) {
            p.s0[group[v]] += mDrive0[v];
            p.s1[group[v]] += mDrive1[v];
            ++p.n[group[v]];
        }
    };
    if (chunks < 2) {
        for (size_t c = 0; c < chunks; ++c) groupChunk(c);
    } else {
        tbb::parallel_for(size_t(0), chunks, groupChunk);
    }

    mGroupDrive0.assign(mGroupCount, 0.0);
    mGroupDrive1.assign(mGroupCount, 0.0);
    if (perVertex) {
        for (size_t v = 0; v < count; ++v)
            mGroupDrive0[v] = mDrive0[v], mGroupDrive1[v] = mDrive1[v];
    } else {
        std::vector<double> sum0(mGroupCount, 0.0), sum1(mGroupCount, 0.0);
        std::vector<uint32_t> members(mGroupCount, 0);
        for (const Partial& p : partial)
            for (int g = 0; g < mGroupCount; ++g)
                sum0[g] += p.s0[g], sum1[g] += p.s1[g], members[g] += p.n[g];
        for (int g = 0; g < mGroupCount; ++g) {
            if (members[g] == 0) continue;
            mGroupDrive0[g] = sum0[g] / members[g];
            mGroupDrive1[g] = sum1[g] / members[g];
        }
        // An empty level or tile continues its neighbours, so a blend towards it reads no
        // false calm.
        fillEmptyGroups(mGroupDrive0, members);
        fillEmptyGroups(mGroupDrive1, members);
    }
    mIntervalFirst = first;
    mIntervalT0_s = a.t_s;
    mIntervalT1_s = b.t_s;
    mHaveInterval = true;
    mVertex = next;
    ++mRevision;
}

double FieldWind::groupDrive(int g, double t_s) const {
    const double span = mIntervalT1_s - mIntervalT0_s;
    const double alpha = span > 0.0 ? std::clamp((t_s - mIntervalT0_s) / span, 0.0, 1.0) : 0.0;
    return mGroupDrive0[g] + (mGroupDrive1[g] - mGroupDrive0[g]) * alpha;
}

void FieldWind::advanceOscillators(double t_s) {
    mOscillators.advance(t_s, mGroupCount, [this](int g, double t) { return groupDrive(g, t); });
}

void FieldWind::update(double t_s, render::GrassWind& wind) {
    if (mSteps.empty()) throw std::logic_error("FieldWind::update before any field step");
    // The interval holding t: the last step at or before t (the first step before it).
    size_t first = 0;
    while (first + 1 < mSteps.size() && mSteps[first + 1].t_s <= t_s) ++first;
    // Past the last step, `first` is the last step: an interval of one step, held.
    if (mSpec.response == BladeResponse::Oscillator && mHaveInterval) {
        // Carry the oscillators through every interval between the last frame and this one, each
        // with its own drive.
        while (mIntervalFirst < first) {
            advanceOscillators(std::min(t_s, mIntervalT1_s));
            enterInterval(mIntervalFirst + 1);
        }
    }
    if (!mHaveInterval || mIntervalFirst != first) enterInterval(first);
    wind.time_s = t_s;
    if (wind.revision != mRevision || wind.vertex != mVertex) {
        wind.vertex = mVertex;  // shared, not copied: it is never written while handed out
        wind.revision = mRevision;
    }
    wind.groupIntensity.resize(mGroupCount);
    if (mSpec.response == BladeResponse::Oscillator) {
        advanceOscillators(t_s);
        for (int g = 0; g < mGroupCount; ++g)
            wind.groupIntensity[g] = static_cast<float>(mOscillators.bend()[g]);
    } else {
        for (int g = 0; g < mGroupCount; ++g)
            wind.groupIntensity[g] = static_cast<float>(groupDrive(g, t_s));
    }
}

std::vector<float> FieldWind::exactStaticIntensity(double t_s) {
    size_t first = 0;
    while (first + 1 < mSteps.size() && mSteps[first + 1].t_s <= t_s) ++first;
    if (!mHaveInterval || mIntervalFirst != first) enterInterval(first);
    const double span = mIntervalT1_s - mIntervalT0_s;
    const double alpha = span > 0.0 ? std::clamp((t_s - mIntervalT0_s) / span, 0.0, 1.0) : 0.0;
    std::vector<float> out(mNormal.size());
    for (size_t v = 0; v < out.size(); ++v)
        out[v] = static_cast<float>(mDrive0[v] + (mDrive1[v] - mDrive0[v]) * alpha);
    return out;
}

std::vector<float> FieldWind::shownIntensity(const render::GrassWind& wind) {
    const std::vector<uint32_t>& group = wind.group();
    std::vector<float> out(group.size());
    for (size_t v = 0; v < out.size(); ++v) out[v] = wind.groupIntensity[group[v]];
    return out;
}

std::string FieldWind::describe() const {
    std::ostringstream out;
    out << "solved-field wind: " << bladeResponseName(mSpec.response)
        << " blade response (bend speed " << mSpec.bendSpeed_mps << " m/s";
    if (mSpec.response == BladeResponse::Oscillator)
        out << ", " << mSpec.frequency_hz << " Hz, damping ratio " << mSpec.dampingRatio;
    out << "), " << mGroupCount << " groups by " << groupingName(mSpec.grouping);
    return out.str();
}

}  // namespace gale::coupling
