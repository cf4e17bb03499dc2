/// \file SceneWind.cpp
/// The [wind] section of the scene format, with its gusts and whirlwinds: the reader SceneParser
/// calls (SceneKeys.h). Split from SceneParser.cpp, whose other sections stay there.

#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <system_error>

#include "app/io/Errors.h"
#include "app/scene/SceneKeys.h"
#include "app/scene/SceneParser.h"
#include "app/scene/SceneSection.h"
#include "render/GrassInput.h"
#include "render/RenderLimits.h"

namespace gale::app::detail {
namespace {

/// [[wind.gusts]] and [[wind.whirlwinds]]: events of the unsteady wind (sim/Gusts.h,
/// sim/Vortices.h; docs/unsteady.md). Read for every kind, noted as unused unless "unsteady".
void readGustsAndWhirlwinds(Context& ctx, Section& s) {
    WindSection& w = ctx.scene->wind;
    sim::UnsteadySettings& u = ctx.scene->unsteady.settings;
    const bool unsteady = w.kind == WindKind::Unsteady;
    for (Section& gs : s.tables("gusts")) {
        sim::GustEvent g;
        g.start_s = gs.number("start_s", g.start_s, closed(0.0, 1e9));
        g.direction_deg = gs.number("direction_deg", w.ambient.direction_deg, anyFinite());
        g.peak_mps = gs.number("peak_mps", g.peak_mps, closed(-1000.0, 1000.0));
        g.duration_s = gs.number("duration_s", g.duration_s, above(0.0, 1e9));
        const std::string env = gs.string("envelope", sim::gustEnvelopeName(g.envelope));
        try {
            g.envelope = sim::gustEnvelopeFromName(env);
        } catch (const ParameterError& e) {
            gs.failParameter(e);
        }
        g.attack_s = gs.optionalNumber("attack_s", above(0.0, 1e9));
        const std::string entry = gs.string("entry", sim::gustEntryName(g.entry));
        try {
            g.entry = sim::gustEntryFromName(entry);
        } catch (const ParameterError& e) {
            gs.failParameter(e);
        }
        g.regionStartGiven = gs.take("region_start_m") != nullptr;
        g.regionStart_m = gs.vec<2>("region_start_m", g.regionStart_m, anyFinite());
        g.regionRadius_m = gs.number("region_radius_m", g.regionRadius_m, above(0.0, 1e6));
        g.regionSpeed_mps = gs.number("region_speed_mps", g.regionSpeed_mps, closed(0.0, 1000.0));
        gs.finish();
        for (const char* key : {"region_start_m", "region_radius_m", "region_speed_mps"})
            if (gs.given(key) && g.entry != sim::GustEntry::Region)
                ctx.scene->notes.push_back(ctx.scene->where(gs.full(key)) +
                                           ": used by entry = \"region\" only (ignored)");
        if (gs.given("attack_s") && g.envelope != sim::GustEnvelope::Spline)
            ctx.scene->notes.push_back(ctx.scene->where(gs.full("attack_s")) +
                                       ": only the spline envelope has an attack time (ignored)");
        try {
            g.validate();  // what the ranges above cannot see: attack_s within duration_s
        } catch (const ParameterError& e) {
            gs.failParameter(e);
        }
        u.gusts.push_back(g);
        if (!unsteady)
            ctx.scene->notes.push_back(ctx.file + ":" + std::to_string(gs.line()) + ": " +
                                       gs.name() +
                                       ": gusts are used by kind \"unsteady\" only (ignored)");
    }
    for (Section& ws : s.tables("whirlwinds")) {
        sim::Whirlwind v;
        if (!ws.take("position_m"))
            ws.fail(ws.line(), "", "missing key position_m (required: [x, y] of the axis)");
        v.wsPosition_m = ws.vec<2>("position_m", v.wsPosition_m, anyFinite());
        v.coreRadius_m = ws.number("core_radius_m", v.coreRadius_m, above(0.0, 1e6));
        const bool hasGamma = ws.take("circulation_m2ps") != nullptr,
                   hasPeak = ws.take("peak_speed_mps") != nullptr;
        v.circulation_m2ps = ws.number("circulation_m2ps", v.circulation_m2ps, closed(-1e7, 1e7));
        v.peakSpeed_mps = ws.number("peak_speed_mps", v.peakSpeed_mps, closed(-1000.0, 1000.0));
        if (hasGamma && hasPeak)
            ws.failKey("peak_speed_mps",
                       "give either circulation_m2ps or peak_speed_mps, not both");
        if (!hasGamma && !hasPeak)
            ws.fail(ws.line(), "",
                    "missing key circulation_m2ps or peak_speed_mps (one is required)");
        if ((hasPeak && v.peakSpeed_mps == 0.0) || (hasGamma && v.circulation_m2ps == 0.0))
            ws.failKey(hasPeak ? "peak_speed_mps" : "circulation_m2ps",
                       "must not be 0 (the sign gives the sense of rotation)");
        const std::string profile = ws.string("profile", sim::vortexProfileName(v.profile));
        try {
            v.profile = sim::vortexProfileFromName(profile);
        } catch (const ParameterError& e) {
            ws.failParameter(e);
        }
        v.updraft_mps = ws.number("updraft_mps", v.updraft_mps, closed(0.0, 1000.0));
        v.start_s = ws.number("start_s", v.start_s, closed(0.0, 1e9));
        v.lifetime_s = ws.optionalNumber("lifetime_s", above(0.0));
        v.forced = ws.boolean("forced", v.forced);
        v.height_m = ws.number("height_m", v.height_m, closed(0.0, 1e6));
        ws.finish();
        try {
            v.validate();
        } catch (const ParameterError& e) {
            ws.failParameter(e);
        }
        if (ws.given("lifetime_s") && !v.forced)
            ctx.scene->notes.push_back(
                ctx.scene->where(ws.full("lifetime_s")) +
                ": the lifetime ends the forcing, and forced = false (ignored)");
        u.whirlwinds.push_back(v);
        if (!unsteady)
            ctx.scene->notes.push_back(ctx.file + ":" + std::to_string(ws.line()) + ": " +
                                       ws.name() +
                                       ": whirlwinds are used by kind \"unsteady\" only (ignored)");
    }
}

}  // namespace

void readWind(Context& ctx, Section s) {
    WindSection& w = ctx.scene->wind;
    const std::string kind = s.string("kind", windKindName(w.kind));
    if (kind == "point_source")
        w.kind = WindKind::PointSource;
    else if (kind == "solved")
        w.kind = WindKind::Solved;
    else if (kind == "unsteady")
        w.kind = WindKind::Unsteady;
    else
        s.failKey("kind",
                  "expected \"point_source\", \"solved\" or \"unsteady\" (got \"" + kind + "\")");
    coupling::PointSourceSpec& p = w.pointSource;
    w.autoSource = !s.take("source_m");
    if (!w.autoSource)
        p.wsSource_m = toVec3(s.vec<3>("source_m", fromVec3(p.wsSource_m), floatPosition()));
    p.steps = static_cast<int>(s.integer("steps", p.steps, 1, 1024));
    p.stepDelay_s = s.number("step_delay_s", p.stepDelay_s, closed(0.0, 3600.0));
    p.blowAway = s.boolean("blow_away", p.blowAway);
    p.blendGroups = s.boolean("blend_groups", p.blendGroups);

    // The ambient wind (first guess of the solve, docs/design.md 4.1): read whatever the kind,
    // since `gale solve` uses it for any scene.
    sim::AmbientWind& a = w.ambient;
    a.speed_mps = s.number("speed_mps", a.speed_mps, closed(0.0, 1000.0));
    a.referenceHeight_m = s.number("reference_height_m", a.referenceHeight_m, above(0.0, 1e5));
    a.direction_deg = s.number("direction_deg", a.direction_deg, anyFinite());
    readFromDeg(s, a);
    noteAmbientWithoutKind(ctx, s);
    const std::string profile = s.string("profile", sim::windProfileName(a.profile));
    try {
        a.profile = sim::windProfileFromName(profile);
    } catch (const ParameterError& e) {
        s.failParameter(e);
    }
    a.roughness_m = s.number("roughness_m", a.roughness_m, above(0.0, 100.0));
    if (!(a.referenceHeight_m > a.roughness_m))
        s.failKey("reference_height_m", "must be above roughness_m = " + Limit::num(a.roughness_m) +
                                            " (got " + Limit::num(a.referenceHeight_m) + ")");
    try {
        a.validate();  // the log law also needs z_ref a few z0 above the ground
    } catch (const ParameterError& e) {
        s.failParameter(e);
    }

    // How the grass answers the solved field (coupling/FieldWind.h).
    coupling::FieldWindSpec& r = w.response;
    try {
        r.response = coupling::bladeResponseFromName(
            s.string("response", coupling::bladeResponseName(r.response)));
        r.grouping = coupling::groupingFromName(s.string(
            "grouping", r.response == coupling::BladeResponse::Oscillator ? "tiles" : "levels"));
    } catch (const ParameterError& e) {
        s.failParameter(e);
    }
    r.groups = static_cast<int>(s.integer("groups", r.groups, 1, 4096));
    r.blendGroups = p.blendGroups;
    r.bendSpeed_mps = s.number("bend_speed_mps", r.bendSpeed_mps, above(0.0, 1e4));
    r.maxIntensity = s.number("max_intensity", r.maxIntensity, above(0.0, MAX_INTENSITY));
    r.frequency_hz = s.number("frequency_hz", r.frequency_hz, above(0.0, 1e3));
    r.dampingRatio = s.number("damping_ratio", r.dampingRatio, above(0.0, 100.0));
    w.sampleHeight_m = s.optionalNumber("sample_height_m", atLeast(0.0, 1e4));
    w.arrivalBands = static_cast<int>(s.integer("arrival_bands", w.arrivalBands, 1, 1024));
    w.levels = static_cast<int>(s.integer("levels", w.levels, 1, 256));
    try {
        coupling::validate(r);
    } catch (const ParameterError& e) {
        s.failParameter(e);
    }
    const bool solved = w.kind != WindKind::PointSource;
    for (const char* key : {"source_m", "steps", "step_delay_s", "blow_away"})
        if (solved && s.given(key))
            ctx.scene->notes.push_back(ctx.scene->where(s.full(key)) + ": not used by kind \"" +
                                       kind + "\" (ignored)");
    for (const char* key :
         {"response", "grouping", "groups", "bend_speed_mps", "max_intensity", "frequency_hz",
          "damping_ratio", "sample_height_m", "arrival_bands", "levels"})
        if (!solved && s.given(key))
            ctx.scene->notes.push_back(ctx.scene->where(s.full(key)) +
                                       ": not used by kind \"point_source\" (ignored)");

    readGustsAndWhirlwinds(ctx, s);

    Section g = s.table("gust");
    w.gusts = g.present();
    if (w.gusts && w.kind == WindKind::Unsteady)
        ctx.scene->notes.push_back(
            ctx.scene->where("wind.gust") +
            ": the kinematic gust curve is not used by kind \"unsteady\" (its gusts are "
            "[[wind.gusts]]) (ignored)");
    const GustShape& shape = w.gustShape;
    const double period_s = g.number("period_s", shape.period_s, above(0.0, 1e6));
    const toml::node* keys = g.take("keys");
    const bool shaped = g.take("base") || g.take("peak") || g.take("attack_s") || g.take("decay_s");
    const double base = g.number("base", shape.base, closed(-MAX_INTENSITY, MAX_INTENSITY));
    const double peak = g.number("peak", shape.peak, closed(-MAX_INTENSITY, MAX_INTENSITY));
    // Defaults scale with the period (0.4 s and 1.6 s at the default 4 s), so any period works.
    const double attack_s = g.number("attack_s", shape.attackFraction * period_s, above(0.0, 1e6));
    const double decay_s = g.number("decay_s", shape.decayFraction * period_s, above(0.0, 1e6));
    g.finish();
    s.finish();

    std::ostringstream desc;
    if (keys) {
        if (shaped) g.failKey("keys", "give either keys or base/peak/attack_s/decay_s, not both");
        const toml::array* written = keys->as_array();
        if (!written || written->empty())
            g.failValue(*keys, "keys", "expected an array of [t_s, intensity] pairs");
        std::vector<coupling::GustKey> list;
        for (size_t i = 0; i < written->size(); ++i) {
            const std::string name = "keys[" + std::to_string(i) + "]";
            const toml::array* pair = (*written)[i].as_array();
            if (!pair || pair->size() != 2)
                g.failValue((*written)[i], name, "expected a pair [t_s, intensity]");
            const double t_s = g.toNumber((*pair)[0], name + "[0]", atLeast(0.0));
            if (!(t_s < period_s))
                g.failValue((*pair)[0], name + "[0]",
                            "key time must be < period_s = " + Limit::num(period_s));
            if (!list.empty() && !(t_s > list.back().t_s))
                g.failValue((*pair)[0], name + "[0]",
                            "key times must increase strictly (previous key at " +
                                Limit::num(list.back().t_s) + " s)");
            const double intensity =
                g.toNumber((*pair)[1], name + "[1]", closed(-MAX_INTENSITY, MAX_INTENSITY));
            list.push_back({t_s, intensity});
        }
        desc << list.size() << " keys over a " << Limit::num(period_s) << " s period";
        w.curve.emplace(period_s, std::move(list));
    } else {
        if (!(attack_s + decay_s < period_s)) {
            const std::string got = Limit::num(attack_s) + " + " + Limit::num(decay_s);
            g.failKey(g.given("decay_s")    ? "decay_s"
                      : g.given("attack_s") ? "attack_s"
                                            : "period_s",
                      "attack_s + decay_s must be shorter than period_s = " + Limit::num(period_s) +
                          " (got " + got + ")");
        }
        desc << "attack " << Limit::num(attack_s) << " s to " << Limit::num(peak) << ", decay "
             << Limit::num(decay_s) << " s to " << Limit::num(base) << ", period "
             << Limit::num(period_s) << " s";
        w.curve = coupling::GustCurve::attackDecay(period_s, base, peak, attack_s, decay_s);
    }
    w.curveDescription = desc.str();
}

}  // namespace gale::app::detail
